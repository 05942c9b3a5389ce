"""`pip install .` (issue 25): into a fresh venv that sees Debian's numpy (created with
--system-site-packages), offline and without build isolation, as docs/python.md says. The
installed package must be the venv's own (not build/python through PYTHONPATH, which this
test's subprocesses do not inherit), carry pip's metadata with the project's version (CMake's
project(VERSION), passed in by CTest: setup.py reads it on its own), import from a folder that
is not the clone, and compute what the command line computes (fig. 2's voltage, bitwise)."""
import os
import subprocess
import sys

import h5py
import numpy as np

from conftest import run_cli, source


def clean_environment():
    """Without PYTHONPATH (CTest sets it to build/python) and PYTHONHOME: what a user's shell has."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    env["PYTHONNOUSERSITE"] = "1"  # ~/.local must not supply a stengmc either
    return env


def run(command, cwd, env):
    done = subprocess.run(command, cwd=cwd, env=env, capture_output=True, text=True)
    assert done.returncode == 0, f"{' '.join(map(str, command))} exited {done.returncode}:\n{done.stdout[-4000:]}{done.stderr[-4000:]}"
    return done.stdout


def test_pip_install_into_a_venv_imports_from_anywhere(tmp_path):
    env = clean_environment()
    venv = tmp_path / "venv"
    run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], tmp_path, env)
    python = venv / "bin" / "python"
    run([python, "-m", "pip", "install", "--no-build-isolation", "--no-index", source()], tmp_path, env)

    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    run_file = elsewhere / "fig2.h5"
    run_cli("run", source("studies/paper/fig2_k155.toml"), "-o", run_file)
    probe = (
        "import importlib.metadata, sys, numpy as np, stengmc\n"
        "print(stengmc.__file__)\n"
        "print(importlib.metadata.version('stengmc'))\n"
        "print(stengmc.__version__)\n"
        f"np.save('voltage.npy', stengmc.load_study({source('studies/paper/fig2_k155.toml')!r}).run().voltage_v)\n"
    )
    lines = run([python, "-c", probe], elsewhere, env).splitlines()
    module_file, metadata_version, module_version = lines[-3:]

    assert os.path.realpath(module_file).startswith(os.path.realpath(venv) + os.sep), \
        f"stengmc imported from {module_file}, not from the venv {venv}"
    assert metadata_version == os.environ["STENGMC_PROJECT_VERSION"]
    assert module_version == os.environ["STENGMC_PROJECT_VERSION"]
    with h5py.File(run_file, "r") as f:
        expected = f["circuit/voltage"][()]
    assert np.array_equal(np.load(elsewhere / "voltage.npy"), expected)

    # pip sees it: `pip show` is what a user checks, and uninstall removes it from the venv
    # (a system-wide install, which the venv also sees, may then answer the import).
    assert "Name: stengmc" in run([python, "-m", "pip", "show", "stengmc"], elsewhere, env)
    run([python, "-m", "pip", "uninstall", "-y", "stengmc"], elsewhere, env)
    gone = subprocess.run([python, "-c", "import stengmc; print(stengmc.__file__)"], cwd=elsewhere, env=env,
                          capture_output=True, text=True)
    if gone.returncode == 0:
        assert not os.path.realpath(gone.stdout.strip()).startswith(os.path.realpath(venv) + os.sep)
    else:
        assert "No module named 'stengmc'" in gone.stderr
