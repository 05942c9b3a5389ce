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


def is_pure_dimension(dataset):
    name = dataset.attrs.get("NAME", b"")
    name = name if isinstance(name, bytes) else str(name).encode()
    return h5py.h5ds.is_scale(dataset.id) and name.startswith(PURE_DIMENSION)


def read_datasets(path, group):
    """Every dataset under `group` of an HDF5 file, by its path below the group; strings as
    str. netCDF's pure dimensions are left out: datasets without values that only name other
    datasets' axes (for xarray). Coordinates (time, frequency, ...) are data and stay."""
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
