#!/usr/bin/env python3
"""Golden digests: a fingerprint of every number the shipped studies produce.

    golden_digest.py check      --binary build/src/stengmc [--work-dir DIR]
    golden_digest.py regenerate --binary build/src/stengmc [--work-dir DIR]
    golden_digest.py digest FILE.h5 [FILE.h5 ...]
    golden_digest.py same A.h5 B.h5 [--ignore PATH[@ATTRIBUTE] ...]

`check` runs every case below with the given binary and compares the digest of each
output file with tests/regression/golden_digests.txt; it exits 1 on any difference and
names what changed. `regenerate` rewrites that file. `digest` prints the lines of
existing files (to compare two builds by hand). `same` exits 0 when two files agree in
every dataset and every attribute, text ones included (the study text, the input paths),
except the excluded ones below; else it prints the differences and exits 1 (the tests of
distributed and sharded runs compare them with a single run this way).

What is fingerprinted, per output file:
- every dataset: dtype, shape and a SHA-256 of its values (little-endian bytes; text
  datasets as UTF-8, NUL-separated), so a change in the last bit of one sample shows.
  Numeric datasets also carry their L2 norm: not compared, but printed beside a
  mismatch, so a roundoff-sized change (relative 1e-16) is told from a real one;
- every attribute that is a number, written as its exact value (repr round-trips a
  double). Text attributes (study text, paths, titles, method names) are not digested;
- except the attributes named in EXCLUDED_ATTRIBUTES / EXCLUDED_ATTRIBUTE_PATTERNS:
  what records when, where or how fast a file was made rather than what it computed;
- the dimension scales (HDF5 H5DS, what makes the files netCDF-4): each dataset's
  DIMENSION_LIST as the paths of the scales of its axes, so a relabelled axis shows.
  REFERENCE_LIST, its inverse kept on each scale, adds nothing and is skipped.

The digests are bitwise, so they hold for one platform (the reference is Debian 12,
x86-64, its GCC, FFTW and libm); the file's header records where it was generated.
The rule: a commit that changes tests/regression/golden_digests.txt says in its message
which numbers changed and why. A refactoring must leave it unchanged.

Run with Debian's python3 (python3-h5py, python3-numpy).
"""
import argparse
import fnmatch
import glob
import hashlib
import os
import platform
import subprocess
import sys
import tempfile

import h5py
import numpy as np

SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DIGEST_FILE = os.path.join(SOURCE_DIR, "tests", "regression", "golden_digests.txt")
REGENERATE = "/usr/bin/python3 scripts/golden_digest.py regenerate --binary build/src/stengmc"

#: Attributes that say when, where or how fast a file was made: not results.
EXCLUDED_ATTRIBUTES = {"created_utc", "git_revision", "program_version"}
#: The same by pattern, for wall times and thread counts a writer may add.
EXCLUDED_ATTRIBUTE_PATTERNS = ["*wall*", "*elapsed*", "*_seconds", "*_utc", "threads"]

#: Characters of the SHA-256 kept per dataset: 64 bits, so a chance collision between
#: two different results is ~1e-19.
HASH_CHARS = 16


def cases():
    """(name, stengmc arguments, output file name) of every case, in run order.

    The paper studies (every study in studies/paper/, so a new one cannot be forgotten),
    a realisation of a random surface, the three kinds of random surface through
    `stengmc surface`, the `circuit` and `spectrum` commands on run outputs, and the quick
    ensemble (a 12-point sweep, 240 realisations: the ensemble path end to end).
    Outputs are named "{out}/<name>.h5"; {out} is filled in when run.
    """
    listed = []
    for study in sorted(glob.glob(os.path.join(SOURCE_DIR, "studies", "paper", "*.toml"))):
        name = os.path.splitext(os.path.basename(study))[0]
        listed.append((f"paper_{name}", ["run", os.path.relpath(study, SOURCE_DIR)]))
    listed += [
        ("random_gw_vb10_realisation3", ["run", "studies/surfaces/gw_vb10.toml", "--realisation", "3"]),
        ("surface_pet_on_steel_gw", ["surface", "surfaces/pet_on_steel_gw.toml", "--realisations", "4", "--seed", "1"]),
        ("surface_pet_on_steel_mindlin", ["surface", "surfaces/pet_on_steel_mindlin.toml", "--realisations", "4", "--seed", "1"]),
        ("surface_pet_on_steel_dense", ["surface", "surfaces/pet_on_steel_dense.toml", "--realisations", "2", "--seed", "1"]),
        ("circuit_paper_fig2_k155", ["circuit", "{out}/paper_fig2_k155.h5", "-R", "1e6"]),
        ("circuit_linear_paper_fig5b", ["circuit", "{out}/paper_fig5b_four_phases.h5", "-R", "1e6", "-C", "1e-12",
                                        "--interpolation", "linear"]),
        ("spectrum_paper_fig6_vb1_l50", ["spectrum", "{out}/paper_fig6_vb1_l50.h5",
                                         "--settings", "studies/paper/fig6_vb1_l50.toml"]),
        ("ensemble_identifiability_quick", ["run", "studies/ensembles/identifiability_quick.toml", "-j", "2"]),
    ]
    return listed


def excluded(attribute_name):
    return attribute_name in EXCLUDED_ATTRIBUTES or any(
        fnmatch.fnmatchcase(attribute_name, p) for p in EXCLUDED_ATTRIBUTE_PATTERNS)


def value_bytes(values, dtype):
    """Canonical bytes of an array: text as UTF-8 joined by NUL, numbers little-endian."""
    if h5py.check_string_dtype(dtype) is not None or dtype.kind in "OSU":
        items = [v.decode("utf-8") if isinstance(v, bytes) else str(v) for v in np.ravel(values)]
        return "\0".join(items).encode("utf-8")
    if dtype.kind not in "biuf":
        raise SystemExit(f"golden_digest: no canonical form for dtype {dtype}; extend value_bytes()")
    array = np.ascontiguousarray(values)
    return array.astype(array.dtype.newbyteorder("<"), copy=False).tobytes()


def dataset_line(path, dataset):
    values = dataset[()]
    dtype = dataset.dtype
    shape = "x".join(str(n) for n in dataset.shape) or "scalar"
    text = h5py.check_string_dtype(dtype) is not None or dtype.kind in "OSU"
    kind = "text" if text else np.dtype(dtype).newbyteorder("<").str
    digest = hashlib.sha256(f"{kind}|{shape}|".encode() + value_bytes(values, dtype)).hexdigest()[:HASH_CHARS]
    line = f"{path} {kind} {shape} {digest}"
    if not text and dataset.size:
        line += f" l2={float(np.linalg.norm(np.asarray(values, dtype=np.float64).ravel()))!r}"
    return line


#: Dimension-scale bookkeeping digested separately (dimension_line) or not at all.
SCALE_ATTRIBUTES = {"DIMENSION_LIST", "REFERENCE_LIST"}


def dimension_line(path, dataset):
    """The scales attached to each axis of a dataset, as paths: "a|b" per axis, space-separated."""
    axes = ["|".join(dataset.file[ref].name for ref in refs) for refs in dataset.attrs["DIMENSION_LIST"]]
    return f"{path}@DIMENSION_LIST dims {' '.join(axes)}"


def attribute_lines(path, attributes, include_text=False):
    lines = []
    for name in sorted(attributes):
        if excluded(name) or name in SCALE_ATTRIBUTES:
            continue
        value = attributes[name]
        array = np.asarray(value)
        if array.dtype.kind not in "biuf":
            if include_text:  # `same`: the provenance must agree too
                digest = hashlib.sha256(value_bytes(array, array.dtype)).hexdigest()[:HASH_CHARS]
                lines.append(f"{path}@{name} text {digest}")
            continue  # text attributes are provenance and labels, not results
        if array.size == 1:
            number = array.ravel()[0]
            shown = repr(float(number)) if array.dtype.kind == "f" else str(int(number))
            lines.append(f"{path}@{name} {array.dtype.newbyteorder('<').str} {shown}")
        else:
            digest = hashlib.sha256(value_bytes(array, array.dtype)).hexdigest()[:HASH_CHARS]
            lines.append(f"{path}@{name} {array.dtype.newbyteorder('<').str} {'x'.join(map(str, array.shape))} {digest}")
    return lines


def file_lines(h5_path, include_text=False):
    """The digest lines of one HDF5 file, sorted by object path."""
    lines = []
    with h5py.File(h5_path, "r") as f:
        lines += attribute_lines("/", f.attrs, include_text)

        def visit(name, obj):
            path = "/" + name
            if isinstance(obj, h5py.Dataset):
                lines.append(dataset_line(path, obj))
                if "DIMENSION_LIST" in obj.attrs:
                    lines.append(dimension_line(path, obj))
            lines.extend(attribute_lines(path, obj.attrs, include_text))

        f.visititems(visit)
    return sorted(lines)


def run_cases(binary, work_dir):
    """Runs every case into work_dir; returns {case: [lines]}. Stops at the first failure."""
    os.makedirs(work_dir, exist_ok=True)
    digests = {}
    for name, arguments in cases():
        out = os.path.join(work_dir, f"{name}.h5")
        for stale in (out, out + ".journal"):
            if os.path.exists(stale):
                os.remove(stale)
        command = [binary] + [a.replace("{out}", work_dir) for a in arguments] + ["--out", out]
        done = subprocess.run(command, cwd=SOURCE_DIR, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if done.returncode != 0:
            raise SystemExit(f"golden_digest: case {name} failed (exit {done.returncode}): {' '.join(command)}\n"
                             f"{done.stdout[-4000:]}")
        digests[name] = file_lines(out)
    return digests


def platform_note():
    try:
        with open("/etc/debian_version") as f:
            debian = "Debian " + f.read().strip()
    except OSError:
        debian = "not Debian"
    return f"{debian}, {platform.machine()}"


def write_digests(digests, path, binary):
    printed = subprocess.run([binary, "--version"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                             text=True).stdout.strip()
    version = printed.splitlines()[0] if printed else "an unknown version"
    with open(path, "w") as f:
        f.write("# Golden digests of the shipped studies (scripts/golden_digest.py; docs/development.md, 'Tests').\n")
        f.write(f"# Regenerate: {REGENERATE}\n")
        f.write("# A commit that changes this file says which numbers changed and why.\n")
        f.write(f"# Generated on {platform_note()} by {version}\n")
        for name in sorted(digests):
            f.write(f"\n[{name}]\n")
            for line in digests[name]:
                f.write(line + "\n")


def read_digests(path):
    digests, header, current = {}, [], None
    with open(path) as f:
        for raw in f:
            line = raw.rstrip("\n")
            if line.startswith("#"):
                header.append(line)
            elif line.startswith("[") and line.endswith("]"):
                current = line[1:-1]
                digests[current] = []
            elif line:
                if current is None:
                    raise SystemExit(f"{path}: digest line before any [case]: {line}")
                digests[current].append(line)
    return digests, header


def key_of(line):
    """The object a line describes: its path, or path@attribute."""
    return line.split(" ", 1)[0]


def l2_of(line):
    for field in line.split(" "):
        if field.startswith("l2="):
            return float(field[3:])
    return None


def describe_change(old, new):
    old_l2, new_l2 = l2_of(old), l2_of(new)
    if old_l2 is not None and new_l2 is not None and old.split(" ")[:3] == new.split(" ")[:3]:
        scale = max(abs(old_l2), abs(new_l2))
        relative = abs(new_l2 - old_l2) / scale if scale > 0 else 0.0
        return f"values changed; L2 norm {old_l2!r} -> {new_l2!r} (relative {relative:.2g})"
    return f"was: {' '.join(old.split(' ')[1:])}\n        now: {' '.join(new.split(' ')[1:])}"


def compare(expected, actual, limit=60):
    """Lines describing every difference (empty: identical)."""
    report = []
    for name in sorted(set(expected) | set(actual)):
        if name not in actual:
            report.append(f"[{name}] in the digest file but no longer a case")
            continue
        if name not in expected:
            report.append(f"[{name}] a new case with no digest")
            continue
        old = {key_of(l): l for l in expected[name]}
        new = {key_of(l): l for l in actual[name]}
        for key in sorted(set(old) | set(new)):
            if key not in new:
                report.append(f"[{name}] {key}: gone from the output")
            elif key not in old:
                report.append(f"[{name}] {key}: new in the output")
            elif old[key] != new[key]:
                report.append(f"[{name}] {key}: {describe_change(old[key], new[key])}")
    if len(report) > limit:
        report = report[:limit] + [f"... and {len(report) - limit} more differences"]
    return report


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    for command in ("check", "regenerate"):
        p = sub.add_parser(command)
        p.add_argument("--binary", required=True, help="the stengmc executable to run")
        p.add_argument("--work-dir", help="where the outputs go (default: a temporary folder)")
        p.add_argument("--digests", default=DIGEST_FILE, help="the golden digest file")
    p = sub.add_parser("digest")
    p.add_argument("files", nargs="+")
    p = sub.add_parser("same")
    p.add_argument("files", nargs=2)
    p.add_argument("--ignore", action="append", default=[],
                   help="an object not to compare, as path or path@attribute (e.g. a dataset of timings)")
    args = parser.parse_args()

    if args.command == "same":
        first, second = args.files
        kept = lambda lines: [line for line in lines if key_of(line) not in args.ignore]  # noqa: E731
        differences = compare({"file": kept(file_lines(first, True))}, {"file": kept(file_lines(second, True))})
        if not differences:
            return 0
        print(f"{first} and {second} differ:")
        print("\n".join("  " + d for d in differences))
        return 1

    if args.command == "digest":
        for path in args.files:
            print(f"[{path}]")
            print("\n".join(file_lines(path)))
        return 0

    binary = os.path.abspath(args.binary)
    with tempfile.TemporaryDirectory(prefix="stengmc-golden-") as scratch:
        work_dir = os.path.abspath(args.work_dir) if args.work_dir else scratch
        actual = run_cases(binary, work_dir)
    if args.command == "regenerate":
        write_digests(actual, args.digests, binary)
        print(f"wrote {args.digests}: {len(actual)} cases, {sum(map(len, actual.values()))} lines")
        return 0

    expected, header = read_digests(args.digests)
    differences = compare(expected, actual)
    if not differences:
        print(f"golden digests: {len(actual)} cases, {sum(map(len, actual.values()))} datasets and "
              f"attributes, all identical to {os.path.relpath(args.digests, SOURCE_DIR)}")
        return 0
    print("golden digests differ from " + os.path.relpath(args.digests, SOURCE_DIR) + ":")
    print("\n".join("  " + d for d in differences))
    print("\n".join(h for h in header if h.startswith("# Generated")))
    print(f"This machine: {platform_note()}. If the change is intended, regenerate with\n  {REGENERATE}\n"
          "and say in the commit message which numbers changed and why.")
    return 1


if __name__ == "__main__":
    sys.exit(main())
