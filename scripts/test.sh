#!/usr/bin/env bash
# The test command: installs what is missing, builds, and runs the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
# Two jobs: the machines have two cores; the slow tests (ngspice, Model 2 tolerance) overlap.
ctest --test-dir build --output-on-failure -j2 --timeout 900
