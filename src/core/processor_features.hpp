#pragma once
//! What the processor running this process offers beyond the build's baseline (x86-64:
//! SSE2), for the few loops compiled twice, once for the baseline and once with
//! gnu::target("avx"/"avx2"). Those loops use no fused multiply-add, so both versions give
//! the same bits and results do not depend on the machine.

namespace stengmc {

//! AVX (256-bit floating point) is available; false on other architectures.
bool processor_has_avx();

//! AVX2 is available; false on other architectures.
bool processor_has_avx2();

//! With `baseline` true, the two functions above answer false from then on, so every such
//! loop takes its baseline version: how the tests compare the two versions on a machine
//! that has both.
void use_baseline_instructions_only(bool baseline);

}  // namespace stengmc
