"""Shared helpers of the Python module's tests (tests/CMakeLists.txt runs them with the
built package on PYTHONPATH and STENGMC_BINARY / STENGMC_SOURCE_DIR set)."""
import os
import subprocess

import h5py
import numpy as np
import pytest

SOURCE_DIR = os.environ.get("STENGMC_SOURCE_DIR",
                            os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))


def run_cli(*arguments, cwd=None):
    """Runs the stengmc executable; fails the test with its output unless it exits 0."""
    binary = os.environ["STENGMC_BINARY"]
    done = subprocess.run([binary, *map(str, arguments)], cwd=cwd, capture_output=True, text=True)
    assert done.returncode == 0, f"stengmc {' '.join(map(str, arguments))} exited {done.returncode}:\n{done.stdout}{done.stderr}"
    return done.stdout


PURE_DIMENSION = b"This is a netCDF dimension but not a netCDF variable."
INDEX_LONG_NAME = "index along dimension "  # core/hdf5_dimensions.hpp: INDEX_LONG_NAME


def is_pure_dimension(dataset):
    """A dataset that only labels other datasets' axes, and holds nothing of the result: a
    netCDF pure dimension (files of stengmc 0.1.0) or an index coordinate 0..n-1 the writer
    made for a dimension without one (its long_name says so)."""
    if not h5py.h5ds.is_scale(dataset.id):
        return False
    name = dataset.attrs.get("NAME", b"")
    name = name if isinstance(name, bytes) else str(name).encode()
    long_name = dataset.attrs.get("long_name", "")
    long_name = long_name.decode() if isinstance(long_name, bytes) else str(long_name)
    return name.startswith(PURE_DIMENSION) or long_name.startswith(INDEX_LONG_NAME)


def read_datasets(path, group):
    """Every dataset under `group` of an HDF5 file, by its path below the group; strings as
    str. Index coordinates and netCDF's pure dimensions are left out: datasets that only
    label other datasets' axes (for xarray). Coordinates (time, frequency, ...) are data and stay."""
    out = {}
    with h5py.File(path, "r") as f:
        def visit(name, item):
            if isinstance(item, h5py.Dataset) and not is_pure_dimension(item):
                data = item[()]
                if item.dtype.kind in ("O", "S"):
                    data = [d.decode() if isinstance(d, bytes) else d for d in np.atleast_1d(data)]
                out[name] = data
        f[group].visititems(visit)
    return out


def assert_bitwise(ours, theirs, what):
    """Equal arrays of equal dtype kind and shape, value for value (NaN nowhere)."""
    if isinstance(theirs, list):
        assert list(ours) == theirs, what
        return
    ours = np.asarray(ours)
    assert ours.shape == theirs.shape, f"{what}: shape {ours.shape} against the file's {theirs.shape}"
    assert np.array_equal(ours, theirs), f"{what}: differs from the file (first at {np.flatnonzero(ours != theirs)[:3]})"


def source(*parts):
    return os.path.join(SOURCE_DIR, *parts)


@pytest.fixture
def stengmc():
    import stengmc as module
    return module
