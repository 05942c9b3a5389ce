#!/usr/bin/env bash
# Runs every benchmark in bench/ and prints each target of issue 12 with its ratio against
# the previous code path (a build of the base revision BASELINE, default the commit
# issue 12 started from) or the peer (scipy's Radau):
#
#   bash bench/run_all.sh            # ~10 min on 2 cores, plus the base build the first time
#   bash bench/run_all.sh --quick    # 100 ensemble realisations instead of 1000, fewer repeats
#   BASELINE=<rev> bash bench/run_all.sh
#
# The base revision is exported with `git archive` into build/baseline-src (no worktree,
# nothing in the repository changes) and built in build/baseline (stengmc only). Output:
# the targets table (bench_targets), the scipy comparison (compare_scipy.py), the chain's
# accuracy against its independent reference (test_chain_reference), and the component
# benchmarks (bench_model2, bench_spectral, bench_pipeline, bench_ensemble), and the long
# records' memory and time (bench_long_run; its base-revision ratio needs --baseline by hand).
set -euo pipefail

cd "$(dirname "$0")/.."
BASELINE=${BASELINE:-53dffc8}
QUICK=""
if [[ "${1:-}" == "--quick" ]]; then
  QUICK="--quick"
  export STENGMC_BENCH_QUICK=1
fi
JOBS=${JOBS:-2}

echo "== building the current tree (Release)"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j"$JOBS" --target stengmc bench_targets bench_asperity_run bench_model2 bench_spectral \
  bench_pipeline bench_ensemble bench_long_run test_chain_reference > /dev/null

echo "== building the base revision $BASELINE (once; stengmc only)"
rev=$(git rev-parse "$BASELINE")
if [[ ! -f build/baseline-src/.revision || "$(cat build/baseline-src/.revision)" != "$rev" ]]; then
  rm -rf build/baseline-src build/baseline
  mkdir -p build/baseline-src
  git archive "$rev" | tar -x -C build/baseline-src
  echo "$rev" > build/baseline-src/.revision
fi
cmake -S build/baseline-src -B build/baseline -DCMAKE_BUILD_TYPE=Release -DSTENGMC_BUILD_TESTS=OFF \
  -DSTENGMC_BUILD_BENCHMARKS=OFF > /dev/null
cmake --build build/baseline -j"$JOBS" --target stengmc > /dev/null

echo
echo "== 1. targets against the base revision"
./build/bench/bench_targets $QUICK --baseline build/baseline/src/stengmc

echo
echo "== 2. one asperity-run against scipy's Radau"
/usr/bin/python3 bench/compare_scipy.py build

echo
echo "== 3. the chain's accuracy against its independent reference (coupled rosenbrock4)"
./build/tests/test_chain_reference | grep "relative L2"

echo
echo "== 4. component benchmarks"
./build/bench/bench_model2 --benchmark_format=console 2>/dev/null | grep -E "median|Benchmark|---"
./build/bench/bench_spectral
./build/bench/bench_pipeline
./build/bench/bench_ensemble $QUICK

echo
echo "== 5. long records (issue 26): 1 and 10 ms of 50 excited asperities, peak memory and time"
./build/bench/bench_long_run $QUICK
