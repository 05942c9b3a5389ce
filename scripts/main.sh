#!/usr/bin/env bash
# The main job: installs what is missing, builds, runs the paper's studies, the shipped
# random surfaces and a quick ensemble with their figures, and ends with the ensemble's
# summary table and where everything is.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
bash scripts/run_paper_studies.sh
bash scripts/run_surface_examples.sh
bash scripts/run_ensemble_examples.sh
echo
echo "All results: $(realpath results)/{paper,surfaces,ensembles}/ (*.h5 and *.png)"
