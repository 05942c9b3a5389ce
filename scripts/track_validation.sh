#!/usr/bin/env bash
# Held-out validation of `stengmc track` on N records of 1 ms drawn from issue 26's prior,
# half unexcited and half excited (scripts/track_validation.py says what is drawn and
# compared). Usage: scripts/track_validation.sh [N=6] [SEED=2026]; writes results/track_validation/.
set -euo pipefail
cd "$(dirname "$0")/.."
N="${1:-6}"
SEED="${2:-2026}"
[ -x build/src/stengmc ] || { echo "build first: scripts/build.sh" >&2; exit 1; }
exec /usr/bin/python3 scripts/track_validation.py "$N" --seed "$SEED" --out results/track_validation
