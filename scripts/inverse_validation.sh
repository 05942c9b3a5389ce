#!/usr/bin/env bash
# The inverse estimation's validation (docs/inverse.md, "validation"), in two parts.
#
# Issue 11, the ideal device: for each known device of studies/inverse/ (v_b = 10 and 5 m/s),
# a calibration bank from its [inverse] prior (seeds 1100, 500), 250 validation signals of the
# same prior drawn as an ensemble with other seeds (2100, 1500), those signals inverted with
# the bank; table in results/inverse/validation_table.md.
#
# Issue 23, real devices: banks of the broadened priors of studies/inverse/device_vb{10,1}_real.toml
# (seeds 1200, 1300), and eight held-out families of 100 signals each (studies/inverse/validation/,
# seeds 2101-2108, disjoint from every bank): ideal, unequal loads, staggered onsets, +-5 %
# parameters, coloured noise with an offset, v_b = 1 m/s, all departures at once, and pure
# noise. Each is inverted with the broadened bank of its belt velocity; the ideal family also
# with the ideal bank (today's figures). Table in results/inverse/validation_real_table.md.
#
# Banks, signals and inversions already in results/inverse/ are reused (delete them to redo).
# About 40 minutes for each part on two cores, most of it the banks of 2000 records.
#   scripts/inverse_validation.sh          both parts
#   scripts/inverse_validation.sh ideal    issue 11's part only
#   scripts/inverse_validation.sh real     issue 23's part only
#   scripts/inverse_validation.sh raw      issue 23's families inverted without a bank (the
#                                          estimator's own counts and its rules without a bank;
#                                          no bank to make: FAMILY_SIZE=40 takes ~1 h on two cores);
#                                          table in results/inverse/validation_raw_table.md
# Environment (defaults in brackets): BANK_RECORDS, records per bank [the device's
# calibration_records, 2000]: a smaller bank calibrates the intervals more coarsely, but it
# is what two cores can afford in a working session (a broadened record costs ~9 s);
# FAMILY_SIZE, signals per held-out family [100, the family studies' realisations]: the first
# FAMILY_SIZE realisations of each family (the same records as in the full family), in
# results/inverse/families<FAMILY_SIZE>/; FAMILIES (raw part only), the families to invert [all
# eight: ideal loads onset tolerance noise vb1 all pure_noise]: the cheap ones (ideal, tolerance,
# noise, pure_noise: ~1.5 s a record) can be run at full size apart from the hard ones (~25 s); STENGMC_BIN, the binary [build/src/stengmc]: pin a copy when the build may change under a
# run of hours; OUT, the output folder [results/inverse].
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${STENGMC_BIN:-./build/src/stengmc}
out=${OUT:-results/inverse}
part=${1:-both}
mkdir -p "$out"
bank_records=()
[[ -n ${BANK_RECORDS:-} ]] && bank_records=(--records "$BANK_RECORDS")

# bank DEVICE.toml BANK.h5: calibrate unless the bank is there (an interrupted calibration
# resumes from its journal).
bank() { [[ -f $2 ]] || "$bin" calibrate "$1" "${bank_records[@]}" -o "$2"; }
# invert SIGNALS.h5 DEVICE.toml BANK.h5 OUT.h5: invert unless done.
invert() { [[ -f $4 ]] || "$bin" invert "$1" --known "$2" --bank "$3" -o "$4" > "${4%.h5}.log"; }

if [[ $part == both || $part == ideal ]]; then
  args=()
  for device in vb10 vb5; do
    bank "studies/inverse/device_$device.toml" "$out/device_${device}_bank.h5"
    signals=$out/validation_$device.h5
    [[ -f $signals ]] || "$bin" run "studies/inverse/validation_$device.toml" -o "$signals"
    invert "$signals" "studies/inverse/device_$device.toml" "$out/device_${device}_bank.h5" "$out/inverted_$device.h5"
    args+=("$signals" "$out/inverted_$device.h5" "$out/device_${device}_bank.h5")
  done
  /usr/bin/python3 scripts/inverse_validation_table.py "${args[@]}" | tee "$out/validation_table.md"
fi

# family_signals FAMILY FOLDER: the family's signals, its first FAMILY_SIZE realisations.
family_signals() {
  local study=studies/inverse/validation/$1.toml
  if [[ -n ${FAMILY_SIZE:-} ]]; then
    sed "s/^realisations = 100$/realisations = $FAMILY_SIZE/" "$study" > "$2/$1.toml"
    study=$2/$1.toml
  fi
  [[ -f $2/$1.h5 ]] || "$bin" run "$study" -o "$2/$1.h5" > /dev/null
}

if [[ $part == raw ]]; then
  families=$out/families${FAMILY_SIZE:-}
  mkdir -p "$families"
  args=()
  for family in ${FAMILIES:-ideal loads onset tolerance noise vb1 all pure_noise}; do
    [[ -f studies/inverse/validation/$family.toml ]] || { echo "FAMILIES: no family '$family' (studies/inverse/validation/$family.toml)" >&2; exit 2; }
    vb=10; [[ $family == vb1 || $family == all ]] && vb=1
    family_signals "$family" "$families"
    raw=$families/raw_$family.h5
    [[ -f $raw ]] || "$bin" invert "$families/$family.h5" --known "studies/inverse/device_vb${vb}_real.toml" -o "$raw" > "${raw%.h5}.log"
    args+=("$families/$family.h5" "$raw")
  done
  /usr/bin/python3 scripts/inverse_raw_table.py "${args[@]}" | tee "$out/validation_raw_table.md"
fi

if [[ $part == both || $part == real ]]; then
  families=$out/families${FAMILY_SIZE:-}
  mkdir -p "$families"
  for vb in 10 1; do bank "studies/inverse/device_vb${vb}_real.toml" "$out/device_vb${vb}_real_bank.h5"; done
  args=()
  for family in ideal loads onset tolerance noise vb1 all pure_noise; do
    vb=10; [[ $family == vb1 || $family == all ]] && vb=1
    device=studies/inverse/device_vb${vb}_real.toml
    signals=$families/$family.h5
    family_signals "$family" "$families"
    invert "$signals" "$device" "$out/device_vb${vb}_real_bank.h5" "$families/inverted_$family.h5"
    args+=("$signals" "$families/inverted_$family.h5" "$out/device_vb${vb}_real_bank.h5")
  done
  # The ideal family on the ideal device's bank: what a user who assumes the ideal device gets.
  ln -sf ideal.h5 "$families/ideal_on_ideal_bank.h5"
  bank studies/inverse/device_vb10.toml "$out/device_vb10_bank.h5"
  invert "$families/ideal_on_ideal_bank.h5" studies/inverse/device_vb10.toml "$out/device_vb10_bank.h5" \
    "$families/inverted_ideal_on_ideal_bank.h5"
  args+=("$families/ideal_on_ideal_bank.h5" "$families/inverted_ideal_on_ideal_bank.h5" "$out/device_vb10_bank.h5")
  /usr/bin/python3 scripts/inverse_validation_table.py "${args[@]}" | tee "$out/validation_real_table.md"
fi
