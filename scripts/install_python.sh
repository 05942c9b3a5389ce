#!/usr/bin/env bash
# Installs the Python module `stengmc` with pip for Debian's python3 (docs/python.md:
# Installing), offline and from this clone; main.sh runs it after the build. As root it
# installs system-wide: Debian's pip puts it in /usr/local/lib/python3.11/dist-packages, on
# python3's path and never written by apt. Debian marks its python3 "externally managed"
# (PEP 668) so that pip and apt do not overwrite each other's files in /usr/lib; that cannot
# happen in /usr/local, hence --break-system-packages. As another user it says how to
# install into a venv instead and leaves the system alone.
set -euo pipefail
cd "$(dirname "$0")/.."
python=/usr/bin/python3
if [[ $(id -u) -ne 0 ]]; then
  echo "python: not root, so not installed system-wide; into a venv of your own:"
  echo "  python3 -m venv --system-site-packages ~/stengmc-venv"
  echo "  ~/stengmc-venv/bin/pip install --no-build-isolation --no-index $(pwd)"
  exit 0
fi
# build.sh's tree, configured with the module for this python, already holds it: pip takes
# it from there (setup.py only brings the target up to date) instead of compiling the library
# a third time (~3 min on two cores). Otherwise setup.py builds in build-python/.
if grep -q '^STENGMC_WITH_PYTHON:BOOL=ON$' build/CMakeCache.txt 2>/dev/null &&
   grep -qx "_Python3_EXECUTABLE:INTERNAL=$python" build/CMakeCache.txt; then
  export STENGMC_PYTHON_CONFIGURED_BUILD_DIR=$PWD/build
fi
export CMAKE_BUILD_PARALLEL_LEVEL=${CMAKE_BUILD_PARALLEL_LEVEL:-$(nproc)}
"$python" -m pip install --no-build-isolation --no-index --break-system-packages --root-user-action=ignore . \
  > build-python.log 2>&1 || { tail -60 build-python.log; exit 1; }
echo "python: stengmc $("$python" -c 'import importlib.metadata as m; print(m.version("stengmc"))') installed for $python (log: build-python.log)"
