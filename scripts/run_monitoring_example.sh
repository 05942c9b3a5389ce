#!/usr/bin/env bash
# The monitoring example (issue 26): studies/monitoring/excited_contact.toml, 1 ms of 16
# asperities on a rough counterface whose contacts start, end, wear and step through the
# record, with 30 dB noise; run and its figures rendered (the spectrogram shows the lines
# come, go and drift), then tracked (stengmc track) with its figure. ~15 s on two cores. Results go to results/monitoring/ (or
# $STENGMC_RESULTS_DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${STENGMC_RESULTS_DIR:-results/monitoring}
stengmc=${STENGMC_BINARY:-./build/src/stengmc}
mkdir -p "$out"
"$stengmc" run studies/monitoring/excited_contact.toml --out "$out/excited_contact.h5"
"$stengmc" plot "$out/excited_contact.h5"

# Tracked with the known device (studies/monitoring/device_excited.toml: the same Table 1-2
# asperities at 5 m/s, excited) and drawn: docs/tracking.md says what the tracker gets right
# here and what it does not yet.
"$stengmc" track "$out/excited_contact.h5" --known studies/monitoring/device_excited.toml \
  --out "$out/excited_contact_track.h5" --figures

echo
echo "Monitoring example (HDF5): $(realpath "$out")/excited_contact.h5"
echo "Monitoring figures (PNG):  $(realpath "$out")/excited_contact*.png (the tracks: excited_contact_track.png)"
