#!/usr/bin/env bash
# The inverse estimation's validation (issue 11; docs/inverse.md, "validation"):
# for each known device of studies/inverse/ (v_b = 10 and 5 m/s), a calibration bank from
# its [inverse] prior (seeds 1100, 500), 250 validation signals of the same prior drawn as an
# ensemble with other seeds (2100, 1500), those signals inverted with the bank, and the
# results table (scripts/inverse_validation_table.py) in results/inverse/validation_table.md.
# Banks and validation ensembles already in results/inverse/ are reused (delete them to redo).
# About 40 minutes on two cores, most of it the two banks of 2000 records.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=./build/src/stengmc
out=results/inverse
mkdir -p "$out"
args=()
for device in vb10 vb5; do
  bank=$out/device_${device}_bank.h5
  [[ -f $bank ]] || "$bin" calibrate "studies/inverse/device_$device.toml" -o "$bank"
  signals=$out/validation_$device.h5
  [[ -f $signals ]] || "$bin" run "studies/inverse/validation_$device.toml" -o "$signals"
  "$bin" invert "$signals" --known "studies/inverse/device_$device.toml" --bank "$bank" -o "$out/inverted_$device.h5" > "$out/inverted_$device.log"
  args+=("$signals" "$out/inverted_$device.h5" "$bank")
done
/usr/bin/python3 scripts/inverse_validation_table.py "${args[@]}" | tee "$out/validation_table.md"
