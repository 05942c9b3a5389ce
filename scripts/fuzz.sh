#!/usr/bin/env bash
# More of the readers' fuzz tests than CI runs (CI: 2000 executions per reader, seed 1):
#   bash scripts/fuzz.sh [RUNS] [SEED] [READER ...]     defaults: 20000, 2, every reader
# READER: study | surface | csv | hdf5 | record | netlist | bank. Runs the sanitizer build's fuzzer
# when there is one (scripts/test.sh builds it in build-sanitize/), else build/'s. The same RUNS and SEED give
# the same inputs on every machine; findings are kept in results/fuzz-findings/ and make
# this script exit 1.
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-20000}
seed=${2:-2}
shift $(( $# > 2 ? 2 : $# ))
readers=("$@")
((${#readers[@]})) || readers=(study surface csv hdf5 record netlist bank)
fuzzer=build-sanitize/tests/fuzz_readers
[[ -x $fuzzer ]] || fuzzer=build/tests/fuzz_readers
[[ -x $fuzzer ]] || { echo "fuzz: no fuzz_readers built: run scripts/build.sh (or scripts/test.sh) first" >&2; exit 1; }
fuzzer=$PWD/$fuzzer
mkdir -p results
cd results
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
status=0
for reader in "${readers[@]}"; do
  "$fuzzer" "$reader" "$runs" "$seed" || status=1
done
((status == 0)) || echo "fuzz: findings in results/fuzz-findings/" >&2
exit $status
