#!/usr/bin/env bash
# The quick inverse demo (docs/inverse.md): a calibration bank of the demo device
# (studies/inverse/demo_device.toml: 300 simulated records, a minute or two on two cores;
# reused if present), then the shipped synthetic record studies/inverse/demo_record.csv
# (six asperities, 30 dB; studies/inverse/demo_record.toml says how it was made) inverted
# with it, with its figure. Results go to results/inverse_demo/ (or $STENGMC_RESULTS_DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${STENGMC_RESULTS_DIR:-results/inverse_demo}
stengmc=${STENGMC_BINARY:-./build/src/stengmc}
mkdir -p "$out"
[[ -f $out/demo_bank.h5 ]] || "$stengmc" calibrate studies/inverse/demo_device.toml --out "$out/demo_bank.h5"
"$stengmc" invert studies/inverse/demo_record.csv --known studies/inverse/demo_device.toml --bank "$out/demo_bank.h5" \
  --out "$out/demo_record_inverse.h5" --figures
echo "(the record was made with k = 48, 57, 66, 70, 88, 120 N/m: studies/inverse/demo_record.toml)"
echo
echo "Inverse demo (HDF5): $(realpath "$out")/*.h5"
echo "Inverse demo figure: $(realpath "$out")/demo_record_inverse.png"
