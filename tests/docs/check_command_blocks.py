#!/usr/bin/env python3
"""Every command the README and docs/ show runs as written, or says why it is not run here.

    check_command_blocks.py SOURCE_DIR BUILD_DIR SCRATCH_DIR [--list]

Reads the ```sh / ```bash blocks of README.md and docs/*.md and takes each line that starts
a command (stengmc, a script, python3, mpirun, cmake, ...; a trailing backslash continues it;
a comment after two spaces or " # " is dropped). Every such command must be classified in
COMMANDS below, either RUN or a reason not to run it here (too long for a test, needs the
user's own data, a cluster): a new command in the docs without a class fails the test, and so
does a class whose command left the docs. The RUN ones are run in the order the docs show
them, with /bin/bash, in SCRATCH_DIR made to look like a clone (studies/, surfaces/,
scripts/ linked, build/ the given build), each within its time limit, and must exit 0.
As root, mpirun gets the two OpenMPI variables the README tells root to set.
"""
import glob
import os
import re
import shutil
import subprocess
import sys

RUN = "run"
STARTS = re.compile(r"^(\./build/src/stengmc|stengmc|bash |/usr/bin/python3|python3|mpirun|PYTHONPATH=|scripts/|"
                    r"sbatch|srun|cmake|ctest|OMPI_)")
USER_DATA = "needs the user's own file (a placeholder name)"
CLUSTER = "needs a Slurm cluster (docs/cluster.md)"

# Command -> RUN or why it is not run by this test. Seconds: each RUN command's time limit.
COMMANDS = {
    "bash scripts/main.sh": "the main job itself: installs packages and runs every study (~10 min); CI runs it",
    "bash scripts/test.sh": "the test suite itself, which runs this test",
    "./build/src/stengmc run studies/paper/fig6_vb10_l50.toml --figures": RUN,
    "./build/src/stengmc circuit my_displacements.h5 -R 1e6 --out my_circuit.h5": USER_DATA,
    "./build/src/stengmc circuit my_displacements.csv -R 1e6 --interpolation linear --out my_circuit.h5": USER_DATA,
    "./build/src/stengmc spectrum results/fig6_vb10_l50.h5 --settings studies/paper/fig6_vb10_l50.toml --out spectra.h5": RUN,
    "./build/src/stengmc spectrum measured_voltage.csv --out spectra.h5 --figures": USER_DATA,
    "./build/src/stengmc spectrum TEK0001.CSV --out spectra.h5": USER_DATA,
    "./build/src/stengmc invert scope.csv --format keysight --column 2 --known device.toml --out inverse.h5": USER_DATA,
    "./build/src/stengmc spectrum scope.h5 --dataset /waveforms/ch1 --out spectra.h5": USER_DATA,
    "./build/src/stengmc invert run42.nc --dataset /v --known device.toml --out inverse.h5": USER_DATA,
    "./build/src/stengmc invert lab.h5 --dataset /signal --time-dataset /t_us --known device.toml --out inverse.h5": USER_DATA,
    "./build/src/stengmc plot results/fig6_vb10_l50.h5": RUN,
    "./build/src/stengmc surface surfaces/pet_on_steel_gw.toml --realisations 200 --seed 1 --figures": RUN,
    "./build/src/stengmc run studies/surfaces/gw_vb10.toml --realisation 3 --figures": RUN,
    "./build/src/stengmc run studies/ensembles/identifiability_quick.toml --figures": RUN,
    "./build/src/stengmc run studies/ensembles/identifiability_quick.toml --only 7": RUN,
    "mpirun -np 2 ./build/src/stengmc run studies/ensembles/identifiability_quick.toml": RUN,
    "./build/src/stengmc run studies/ensembles/identifiability_quick.toml --shard 0/2 -o s0.h5": RUN,
    "./build/src/stengmc run studies/ensembles/identifiability_quick.toml --shard 1/2 -o s1.h5": RUN,
    "./build/src/stengmc merge s0.h5 s1.h5 -o quick.h5": RUN,
    "./build/src/stengmc status s0.h5": RUN,
    "./build/src/stengmc merge --partial s0.h5 -o quick_half.h5": RUN,
    "./build/src/stengmc calibrate studies/inverse/device_vb10.toml":
        "2000 simulated records (~3 min); InverseDemo.CalibrateInvertAndRender runs calibrate and invert on the demo device",
    "./build/src/stengmc invert measured.csv --known studies/inverse/device_vb10.toml --out inverse.h5 --figures": USER_DATA,
    "./build/src/stengmc --help": RUN,
    "./build/src/stengmc run studies/monitoring/record_unexcited.toml -o monitoring_unexcited.h5": RUN,
    "./build/src/stengmc track monitoring_unexcited.h5 --known studies/monitoring/device_unexcited.toml -o monitoring_track.h5 --figures": RUN,
    "PYTHONPATH=build/python /usr/bin/python3 -c \"import stengmc; print(stengmc.load_study('studies/paper/fig2_k155.toml').run())\"": RUN,
    "./build/src/stengmc run studies/circuits/paper_resistor.toml": RUN,
    "./build/src/stengmc run studies/circuits/bridge_rectifier.toml": RUN,
    "./build/src/stengmc export-netlist studies/paper/fig6_vb10_l50.toml -o fig6.cir": RUN,
    "mpirun -np 4 --bind-to none stengmc run studies/ensembles/identifiability_vs_count.toml -j 8":
        "4 ranks x 8 threads of the 20-point sweep: a cluster node's command (docs/cluster.md)",
    "srun --cpu-bind=cores stengmc run studies/ensembles/identifiability_vs_count.toml -j \"$SLURM_CPUS_PER_TASK\" -o results/count.h5": CLUSTER,
    "stengmc run studies/ensembles/identifiability_vs_count.toml -j \"$SLURM_CPUS_PER_TASK\" --shard \"$SLURM_ARRAY_TASK_ID/$n\" -o \"shards/count.shard$SLURM_ARRAY_TASK_ID\"": CLUSTER,
    "sbatch --dependency=afterok:$jobid --wrap \"bash -c 'stengmc merge shards/count.shard{0..63} --out results/count.h5'\"": CLUSTER,
    "./build/src/stengmc calibrate studies/inverse/device_vb10.toml -j 2":
        "2000 simulated records (~3 min); InverseDemo.CalibrateInvertAndRender runs calibrate and invert on the demo device",
    "./build/src/stengmc invert record.csv --known studies/inverse/device_vb10.toml --out inverse.h5 --figures": USER_DATA,
    "./build/src/stengmc invert a.csv b.csv c.csv --known ... --out pooled.h5": USER_DATA,
    "./build/src/stengmc invert results/inverse/validation_vb10.h5 --known ...":
        "needs the validation ensemble of scripts/inverse_validation.sh (~40 min)",
    "bash scripts/run_inverse_demo.sh": "the main job's inverse demo (~2 min); InverseDemo.CalibrateInvertAndRender runs it",
    "cmake -S . -B build -DSTENGMC_BUILD_BENCHMARKS=ON && bash bench/run_all.sh": "the benchmarks (~4 min plus a build)",
    "cmake -S . -B build && cmake --build build -j2": "the build itself, done before any test runs",
    "PYTHONPATH=build/python /usr/bin/python3 -c \"import stengmc; print(stengmc.__version__)\"": RUN,
    "python3 -m venv --system-site-packages ~/stengmc-venv":
        "a venv in the user's home; Python.PipInstallIntoAVenv makes one in a temporary folder and pip-installs the clone",
    "python3 -m build --no-isolation --wheel":
        "builds in the clone's build-python/ and dist/, which the scratch clone lacks; "
        "Python.PipInstallIntoAVenv runs the same setup.py through pip",
    "python3 -m build --no-isolation --sdist":
        "Python.sdist builds the sdist from a copy of the tree and checks and configures it",
    "/usr/bin/python3 scripts/contact_sheet.py build/tests/paper-results build/tests/surface-results "
    "build/tests/ensemble-results build/tests/inverse-demo-results --out results/contact_sheet.png "
    "--thumbnails docs/figures/contact --width 520":
        "rewrites the committed thumbnails from the result folders the RunAndRender tests leave; "
        "Figures.EveryShippedFigurePassesTheChecks checks those figures",
}
LIMIT_S = 300


def commands(source_dir):
    """[(file:line, command)] of every command line in the docs' shell blocks."""
    found = []
    for path in ["README.md"] + sorted(glob.glob(os.path.join(source_dir, "docs", "*.md"))):
        full = os.path.join(source_dir, path)
        block, lang, pending, where = False, "", None, ""
        for number, line in enumerate(open(full, encoding="utf-8"), 1):
            fence = re.match(r"^\s*```(\w*)", line)
            if fence:
                block, lang = not block, fence.group(1)
                continue
            if not block or lang not in ("sh", "bash"):
                continue
            text = line.rstrip("\n")
            if pending is not None:
                pending += " " + text.strip().rstrip("\\").strip()
                if not text.rstrip().endswith("\\"):
                    found.append((where, pending))
                    pending = None
                continue
            text = re.sub(r"(\s{2,}|\s)#(\s.*)?$", "", text).strip()
            if not STARTS.match(text):
                continue
            where = f"{os.path.relpath(full, source_dir)}:{number}"
            if text.endswith("\\"):
                pending = text.rstrip("\\").strip()
            else:
                found.append((where, text))
    return found


def scratch_clone(source_dir, build_dir, scratch):
    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(scratch)
    for name in ("studies", "surfaces", "scripts", "docs"):
        os.symlink(os.path.join(source_dir, name), os.path.join(scratch, name))
    os.symlink(build_dir, os.path.join(scratch, "build"))


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    source_dir, build_dir, scratch = (os.path.abspath(a) for a in argv[:3])
    found = commands(source_dir)
    failures = []
    shown = {command for _, command in found}
    for where, command in found:
        if command not in COMMANDS:
            failures.append(f"{where}: `{command}` is not classified: add it to COMMANDS in {__file__} (RUN or why not)")
    for command in COMMANDS:
        if command not in shown:
            failures.append(f"COMMANDS has `{command}`, which no doc shows any more: remove it")
    if "--list" in argv:
        for where, command in found:
            print(f"{where}: {COMMANDS.get(command, 'UNCLASSIFIED')}: {command}")
        return 0
    scratch_clone(source_dir, build_dir, scratch)
    environment = dict(os.environ)
    if os.geteuid() == 0:  # what the README tells root to set
        environment.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    ran = set()
    for where, command in found:
        if COMMANDS.get(command) != RUN or command in ran:
            continue
        ran.add(command)
        if command.startswith("mpirun") and not shutil.which("mpirun"):
            print(f"skipped (no mpirun on PATH): {command}")
            continue
        if command.startswith("PYTHONPATH=build/python") and not os.path.isdir(os.path.join(build_dir, "python", "stengmc")):
            print(f"skipped (built without the Python module): {command}")
            continue
        try:
            done = subprocess.run(["/bin/bash", "-c", command], cwd=scratch, env=environment, capture_output=True,
                                  text=True, timeout=LIMIT_S)
        except subprocess.TimeoutExpired:
            failures.append(f"{where}: `{command}` did not finish in {LIMIT_S} s")
            continue
        if done.returncode != 0:
            failures.append(f"{where}: `{command}` exited {done.returncode}:\n{(done.stdout + done.stderr)[-2000:]}")
        else:
            print(f"ok: {command}")
    for failure in failures:
        print("FAIL:", failure)
    skipped = sum(1 for c in COMMANDS.values() if c != RUN)
    print(f"documented commands: {len(shown)}; run {len(ran)}, not run here (with reasons) {skipped}; {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
