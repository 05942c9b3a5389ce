#!/usr/bin/env bash
# The monitoring example (issue 26): studies/monitoring/excited_contact.toml, 1 ms of 16
# asperities on a rough counterface whose contacts start, end, wear and step through the
# record, with 30 dB noise; run and its figures rendered (the spectrogram shows the lines
# come, go and drift). ~10 s on two cores. Results go to results/monitoring/ (or
# $STENGMC_RESULTS_DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${STENGMC_RESULTS_DIR:-results/monitoring}
stengmc=${STENGMC_BINARY:-./build/src/stengmc}
mkdir -p "$out"
"$stengmc" run studies/monitoring/excited_contact.toml --out "$out/excited_contact.h5"
"$stengmc" plot "$out/excited_contact.h5"

# ---- TRACKING (issue 26, part 3) -------------------------------------------------------
# `stengmc track` is being built separately. When it lands, track the record here, e.g.
#   "$stengmc" track "$out/excited_contact.h5" --known studies/monitoring/excited_contact.toml \
#     --out "$out/excited_contact_tracks.h5" --figures
# (the command's final options are its author's to choose).
# ----------------------------------------------------------------------------------------

echo
echo "Monitoring example (HDF5): $(realpath "$out")/excited_contact.h5"
echo "Monitoring figures (PNG):  $(realpath "$out")/excited_contact*.png"
