#!/usr/bin/env bash
# The main job: installs what is missing, builds, installs the Python module (as root,
# system-wide with pip: scripts/install_python.sh), runs the paper's studies, the shipped
# random surfaces and a quick ensemble with their figures, the monitoring example (a 1 ms
# record of a contact that changes, with its spectrogram), then the quick inverse demo (a
# small calibration bank and one synthetic record inverted), and ends with where
# everything is.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
bash scripts/install_python.sh
bash scripts/run_paper_studies.sh
bash scripts/run_surface_examples.sh
bash scripts/run_ensemble_examples.sh
bash scripts/run_monitoring_example.sh
bash scripts/run_inverse_demo.sh
bash scripts/run_tracking_demo.sh
echo
echo "All results: $(realpath results)/{paper,surfaces,ensembles,monitoring,inverse_demo,tracking_demo}/ (*.h5 and *.png)"
