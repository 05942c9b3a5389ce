#!/usr/bin/env python3
"""The README table "interaction magnitude against contact density": runs `stengmc surface`
on the shipped random surfaces, and on the Greenwood-Williamson one at several nominal
loads, and prints a Markdown table of the means over the realisations.

    /usr/bin/python3 scripts/interaction_table.py [--binary build/src/stengmc] [-k 200]
"""
import argparse
import pathlib
import re
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = pathlib.Path(__file__).resolve().parent.parent


def examine(binary, surface_text, name, realisations, scratch):
    source = scratch / f"{name}.toml"
    source.write_text(surface_text)
    out = scratch / f"{name}.h5"
    subprocess.run([binary, "surface", str(source), "-k", str(realisations), "--seed", "1", "-o", str(out)],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with h5py.File(out, "r") as f:
        r = f["realisations"]
        return {
            "contacts": np.mean(r["asperity_count"][:]),
            "density": np.mean(r["contact_density"][:]),
            "screening": np.mean(r["screening_estimate"][:]),
            "moved": np.mean(r["load_redistribution"][:]),
            "moved95": np.percentile(r["load_redistribution"][:], 95),
            "independent": np.mean(r["independence_holds"][:]),
        }


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", default=str(ROOT / "build" / "src" / "stengmc"))
    parser.add_argument("-k", "--realisations", type=int, default=200)
    args = parser.parse_args()
    gw = (ROOT / "surfaces" / "pet_on_steel_gw.toml").read_text()
    rows = []
    for load in (0.002, 0.02, 0.2, 2.0):
        text = re.sub(r"(?m)^nominal_load_n = \S+", f"nominal_load_n = {load}", gw)
        rows.append((f"pet_on_steel_gw, W = {load:g} N", text))
    for name in ("pet_on_steel_mindlin", "pet_on_steel_dense"):
        rows.append((name + " (as shipped)", (ROOT / "surfaces" / f"{name}.toml").read_text()))
    print("| surface | in contact | A_r/A0 | screening (4/3π)(A_r/A0)^1.5 | load moved, mean | load moved, 95 % | independent (< 5 %) |")
    print("|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as scratch:
        for i, (label, text) in enumerate(rows):
            s = examine(args.binary, text, f"s{i}", args.realisations, pathlib.Path(scratch))
            print(f"| {label} | {s['contacts']:.1f} | {100 * s['density']:.3g} % | {100 * s['screening']:.2g} % | "
                  f"{100 * s['moved']:.3g} % | {100 * s['moved95']:.3g} % | {100 * s['independent']:.0f} % |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
