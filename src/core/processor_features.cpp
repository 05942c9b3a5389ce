#include "core/processor_features.hpp"

#include <atomic>

namespace stengmc {

namespace {
std::atomic<bool> baseline_only{false};
}  // namespace

void use_baseline_instructions_only(bool baseline) { baseline_only.store(baseline, std::memory_order_relaxed); }

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
bool processor_has_avx() {
  static const bool has = __builtin_cpu_supports("avx");
  return has && !baseline_only.load(std::memory_order_relaxed);
}
bool processor_has_avx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has && !baseline_only.load(std::memory_order_relaxed);
}
#else
bool processor_has_avx() { return false; }
bool processor_has_avx2() { return false; }
#endif

}  // namespace stengmc
