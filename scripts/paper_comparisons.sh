#!/usr/bin/env bash
# Figures that put several paper runs side by side (after run_paper_studies.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${STENGMC_PYTHON:-/usr/bin/python3}
r=${1:-results/paper}
$PY scripts/plot_run.py --compare "$r/fig4_four_identical.h5" "$r/fig4_single_same_area.h5" --out "$r/fig4_comparison.png"
