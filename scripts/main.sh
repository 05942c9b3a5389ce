#!/usr/bin/env bash
# The main job: installs what is missing, builds, runs the paper's studies and the
# shipped random surfaces with their figures, then says where everything is.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
bash scripts/run_paper_studies.sh
bash scripts/run_surface_examples.sh
