"""The sdist (issue 25): `python3 -m build --no-isolation --sdist` of the project carries what
`pip install` of it needs. Built from a copy of the source tree (this test does not write into
the clone), it must hold every file of the folders the module's CMake build reads (src/,
python/, cmake/, scripts/) and of those its install rules list (docs/, studies/, surfaces/),
the top-level CMake, packaging and licence files, and no compiled objects; and CMake must
configure its unpacked tree as setup.py configures it (the module on, tests off). Compiling
the wheel from it takes minutes on two cores and is left to the hand check in docs/python.md
(`python3 -m build --no-isolation`, which builds the wheel from the sdist)."""
import os
import shutil
import subprocess
import sys
import tarfile

from conftest import SOURCE_DIR

# Folders of the clone the sdist must carry whole, and single files it must carry.
FOLDERS = ("src", "python", "cmake", "scripts", "docs", "studies", "surfaces")
FILES = ("CMakeLists.txt", "pyproject.toml", "setup.py", "MANIFEST.in", "README.md", "LICENSE", "CITATION.cff",
         "CHANGELOG.md")
# What a developer's tree holds that is not source (.gitignore's build output).
NOT_SOURCE = shutil.ignore_patterns(".git", "build*", "dist", "results", "__pycache__", "*.egg-info", "*.pyc", "*.so")


def run(command, cwd):
    done = subprocess.run(command, cwd=cwd, capture_output=True, text=True)
    assert done.returncode == 0, f"{' '.join(map(str, command))} exited {done.returncode}:\n{done.stdout[-4000:]}{done.stderr[-4000:]}"
    return done.stdout


def files_under(root, folder):
    out = set()
    for directory, _, names in os.walk(os.path.join(root, folder)):
        for name in names:
            out.add(os.path.relpath(os.path.join(directory, name), root))
    return out


def test_the_sdist_holds_what_pip_install_needs_and_configures(tmp_path):
    tree = tmp_path / "clone"
    shutil.copytree(SOURCE_DIR, tree, ignore=NOT_SOURCE, symlinks=True)
    run([sys.executable, "-m", "build", "--no-isolation", "--sdist", "--outdir", str(tmp_path / "dist")], tree)
    (archive,) = list((tmp_path / "dist").glob("stengmc-*.tar.gz"))
    with tarfile.open(archive) as tar:
        top = os.path.commonpath(tar.getnames())
        held = {os.path.relpath(name, top) for name in tar.getnames() if tar.getmember(name).isfile()}
        tar.extractall(tmp_path / "unpacked")

    expected = set(FILES)
    for folder in FOLDERS:
        expected |= files_under(tree, folder)
    assert len(expected) > 400, f"only {len(expected)} files in the copy: {tree} is not the project"
    missing = sorted(expected - held)
    assert not missing, f"the sdist lacks {len(missing)} files the build or install reads: {missing[:20]}"
    compiled = sorted(name for name in held if name.endswith((".so", ".o", ".a", ".pyc")))
    assert not compiled, f"the sdist carries compiled files: {compiled}"

    # CMake configures the unpacked sdist as setup.py does (configure only: it reads every
    # CMakeLists.txt and script path the build needs; compiling is the hand check's).
    unpacked = tmp_path / "unpacked" / top
    run(["cmake", "-S", str(unpacked), "-B", str(tmp_path / "configured"), "-DCMAKE_BUILD_TYPE=Release",
         "-DSTENGMC_WITH_PYTHON=ON", "-DSTENGMC_BUILD_TESTS=OFF", f"-DPython3_EXECUTABLE={sys.executable}"], tmp_path)
    assert (tmp_path / "configured" / "python").is_dir(), "the configured sdist has no Python module target"
