#!/usr/bin/env bash
# Installs the Debian 12 packages stengmc needs (as root), only those missing.
# Idempotent: a machine that has everything does not touch apt at all.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  libeigen3-dev libfftw3-dev libboost-dev libboost-math-dev
  libhdf5-dev libtomlplusplus-dev libcli11-dev
  libomp-dev libopenmpi-dev openmpi-bin  # for the ensemble runner (OpenMP, MPI) and spectra (FFTW)
  libgtest-dev libgmock-dev libbenchmark-dev
  ngspice libngspice0-dev  # the independent circuit reference (tests) and [circuit] netlist loads
  python3 python3-h5py python3-matplotlib python3-numpy
  python3-scipy  # bench/compare_scipy.py: the peer for one asperity-run
  python3-xarray python3-h5netcdf  # outputs open as labelled arrays (test Io.OutputsOpenInXarray)
  pybind11-dev python3-dev python3-pytest  # the Python module (python/) and its tests
  python3-pip python3-venv python3-setuptools python3-wheel python3-build  # pip install . / a wheel, offline (docs/python.md)
  netcdf-bin udunits-bin  # test Io.OutputsOpenInXarray: ncdump -h reads every output, udunits2 parses every unit
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  echo "setup: all ${#packages[@]} Debian packages present"
  exit 0
fi

if [[ $(id -u) -ne 0 ]]; then
  echo "setup: missing packages: ${missing[*]}" >&2
  echo "setup: run as root (or: sudo apt-get install ${missing[*]})" >&2
  exit 1
fi

echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
