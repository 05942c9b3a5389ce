#!/usr/bin/env python3
"""Every kind of stengmc output opens in xarray (h5netcdf engine) as labelled arrays.

    test_netcdf_outputs.py --binary build/src/stengmc [--work-dir DIR]

Makes each kind of output file with the built binary from small studies (a run with
spectra, lines and a spectrogram; a run of a random surface; `circuit`; `spectrum`;
`surface`; a single-point ensemble; a sweep with draws; a calibration bank; an inverse
result) and opens every group of each with
    xarray.open_dataset(path, engine="h5netcdf", group=...)
without any stengmc code. It asserts, against the files' own datasets read with h5py:
- the named dimensions of the main datasets (V over "time", asperity traces over
  ("asperity", "time"), ensemble tables over "realisation", spectra over "frequency"...);
- that coordinates equal the datasets they label (/time, /spectrum/frequency, ids);
- that every variable xarray shows has a `long_name` and CF `units`, or, where it has no
  single unit (a column per parameter, a law parameter whose unit is its family's), no
  units and a `comment` giving the unit of each part; and that it holds exactly the
  values h5py reads (no decoding alters them);
- that netCDF-C's `ncdump -h` reads every file, that the root says
  Conventions = "CF-1.10", and that UDUNITS-2's `udunits2` parses every `units`
  attribute of every file (each failing string is reported with its variables);
- that every dataset of the file appears as a variable of its group (no netCDF "pure"
  dimension, which would be a dimension without a coordinate);
- that every dimension of every variable has a coordinate of its name (1-D, as long, with
  long_name and units) in its group or an enclosing one, a pure index being 0..n-1;
- that a sweep whose grid is a product has one dimension per swept parameter in /summary,
  selectable by value, and one that is not keeps grid_point with auxiliary coordinates;
- that populations are CF contiguous ragged arrays (counts with sample_dimension).
xarray, h5netcdf, ncdump (netcdf-bin) and udunits2 (udunits-bin) are declared
dependencies (scripts/setup.sh): their absence fails.

    test_netcdf_outputs.py --check-units FILE...

checks only the last three points on existing files (to try the check on a planted bad unit).
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np
import xarray as xr

SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PURE_DIMENSION = b"This is a netCDF dimension but not a netCDF variable."

FAILURES = []


def check(condition, message):
    if not condition:
        FAILURES.append(message)


def run(binary, *arguments, cwd):
    done = subprocess.run([binary, *arguments], cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode != 0:
        raise SystemExit(f"stengmc {' '.join(arguments)} failed ({done.returncode}):\n{done.stdout[-3000:]}")


def groups_of(path):
    names = ["/"]
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, node: names.append("/" + name) if isinstance(node, h5py.Group) else None)
    return names


def open_group(path, group):
    return xr.open_dataset(path, engine="h5netcdf", group=group)


def check_every_group(path):
    """Every group opens; every variable is described and holds the file's values."""
    with h5py.File(path, "r") as f:
        for group in groups_of(path):
            name = f"{os.path.basename(path)}:{group}"
            try:
                ds = open_group(path, group)
            except Exception as e:  # noqa: BLE001: any failure to open is the finding
                check(False, f"{name} does not open: {e!r}")
                continue
            with ds:
                node = f[group]
                for key, item in node.items():
                    if not isinstance(item, h5py.Dataset):
                        continue
                    if PURE_DIMENSION in item.attrs.get("NAME", b""):
                        check(False, f"{name}: {key} is a netCDF pure dimension: a dimension without a coordinate")
                        continue
                    check(key in ds.variables, f"{name}: dataset {key} is not a variable")
                    if key not in ds.variables:
                        continue
                    variable = ds.variables[key]
                    described = lambda attribute: isinstance(variable.attrs.get(attribute), str) and variable.attrs[  # noqa: E731
                        attribute] != ""
                    check(described("long_name"), f"{name}/{key}: no long_name")
                    check(described("units") or ("units" not in variable.attrs and described("comment")),
                          f"{name}/{key}: no units (nor a comment saying why there is none)")
                    check(len(variable.dims) == item.ndim, f"{name}/{key}: {variable.dims} for a {item.ndim}-D dataset")
                    stored = item[()]
                    if item.dtype.kind in "iuf":
                        # (NaN marks what is absent in a tracking file's track x window tables.)
                        check(variable.dtype == item.dtype
                              and np.array_equal(variable.values, stored, equal_nan=item.dtype.kind == "f"),
                              f"{name}/{key}: xarray's values differ from the dataset's")
                    else:  # text: xarray gives str objects
                        expected = [s.decode() if isinstance(s, bytes) else s for s in np.ravel(stored)]
                        check(list(np.ravel(variable.values)) == expected, f"{name}/{key}: text differs")


def tool(name, package):
    found = shutil.which(name)
    if not found:
        raise SystemExit(f"{name} is not installed (Debian package {package}; scripts/setup.sh installs it)")
    return found


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def check_netcdf_c_and_units(paths):
    """ncdump -h reads each file; the root says CF-1.10; UDUNITS-2 parses every units."""
    ncdump, udunits2 = tool("ncdump", "netcdf-bin"), tool("udunits2", "udunits-bin")
    units = {}  # each distinct string: the variables that carry it
    for path in paths:
        name = os.path.basename(path)
        done = subprocess.run([ncdump, "-h", path], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        check(done.returncode == 0, f"{name}: ncdump -h fails ({done.returncode}): {done.stdout[-500:]}")
        with h5py.File(path, "r") as f:
            check(text(f.attrs.get("Conventions", "")) == "CF-1.10",
                  f"{name}: root Conventions is {f.attrs.get('Conventions')!r}, not 'CF-1.10'")
            f.visititems(lambda key, node: units.setdefault(text(node.attrs["units"]), []).append(f"{name}:/{key}")
                         if "units" in node.attrs else None)
    for unit, where in sorted(units.items()):
        # The tool reads a leading number as the value ("1/s" would be 1 of "/s"), so the
        # unit is given after an explicit value of 1; "-W ''" asks for its definition.
        done = subprocess.run([udunits2, "-H", f"1 {unit}", "-W", ""], stdin=subprocess.DEVNULL,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        check(unit.strip() != "" and done.returncode == 0,
              f"units {unit!r} does not parse with UDUNITS-2 ({done.stdout.strip()}): {', '.join(where[:5])}"
              + (f" and {len(where) - 5} more" if len(where) > 5 else ""))
    return len(units)


def report(success):
    if FAILURES:
        print(f"{len(FAILURES)} failures:")
        print("\n".join("  " + f for f in FAILURES))
        return 1
    print(success)
    return 0


def dims(path, group, variable):
    with open_group(path, group) as ds:
        return ds[variable].dims


def expect_dims(path, group, variable, expected):
    got = dims(path, group, variable)
    check(got == expected, f"{os.path.basename(path)}:{group}/{variable} has dims {got}, expected {expected}")


def expect_coordinate(path, group, dimension, dataset):
    """Dimension `dimension` of `group` is labelled with the values of `dataset`."""
    with open_group(path, group) as ds, h5py.File(path, "r") as f:
        ok = dimension in ds.coords and np.array_equal(ds.coords[dimension].values, f[dataset][()].astype(
            ds.coords[dimension].dtype) if f[dataset].dtype.kind in "iuf" else ds.coords[dimension].values)
        if f[dataset].dtype.kind not in "iuf":
            ok = dimension in ds.coords and list(ds.coords[dimension].values) == [
                s.decode() if isinstance(s, bytes) else s for s in f[dataset][()]]
        check(ok, f"{os.path.basename(path)}:{group}: coordinate {dimension} is not {dataset}")


def expect_length(path, group, dimension, dataset):
    with open_group(path, group) as ds, h5py.File(path, "r") as f:
        check(ds.dims.get(dimension) == f[dataset].shape[0],
              f"{os.path.basename(path)}:{group}: dimension {dimension} is not as long as {dataset}")


ENSEMBLE = """title = "xarray test ensemble"
seed = 3
duration_s = 20e-6
sample_rate_hz = 100e6
[model]
kind = "model2"
belt_velocity_m_per_s = 10
static_friction = 0.28
kinetic_friction = 0.22
[surface]
file = "{surface}"
[domain]
policy = "flag"
[spectrum]
window = "hann"
start_s = 2e-6
min_frequency_hz = 100e3
high_resolution = false
[noise]
snr_db = 30
[ensemble]
realisations = 3
trace_realisations = [0]
"""

SWEEP = """
[[ensemble.sweep]]
parameter = "surface.summits.count"
values = [1, 2]

[[ensemble.draw]]
parameter = "surface.stiffness.sigma_log"
kind = "uniform"
min = 0.1
max = 0.3
"""

# Two swept parameters: a product grid of 2 x 2 points, over grid_point.
# A value repeated: 3 grid points that are no product.
SWEEP_REPEATED = """
[[ensemble.sweep]]
parameter = "surface.summits.count"
values = [2, 1, 2]
"""

SWEEP_TWO_PARAMETERS = """
[[ensemble.sweep]]
parameter = "surface.summits.count"
values = [1, 2]

[[ensemble.sweep]]
parameter = "model.belt_velocity_m_per_s"
values = [10, 12]
"""


def dimensions_of(path):
    """Every group with the dimensions xarray sees in it."""
    found = {}
    for group in groups_of(path):
        with open_group(path, group) as ds:
            found[group] = (set(ds.dims), set(ds.coords))
    return found


def ancestors(group):
    """The group and its enclosing groups, nearest first: where netCDF-4 looks for a dimension."""
    parts = group.strip("/").split("/") if group != "/" else []
    return ["/" + "/".join(parts[:i]) for i in range(len(parts), 0, -1)] + ["/"]


def check_every_dimension_has_a_coordinate(path):
    """Every dimension of every variable of every group has a coordinate variable of its name,
    in the group or (netCDF-4's scoping, which stengmc.open's to_xarray follows) an enclosing
    one: 1-D over that dimension, as long, with a long_name, and units (or a comment saying
    whose unit it has: a swept parameter's values)."""
    name = os.path.basename(path)
    opened = {}
    for group in groups_of(path):
        with open_group(path, group) as ds:
            opened[group] = ds.load()
    for group, ds in opened.items():
        for variable in ds.variables.values():
            for dimension in variable.dims:
                holder = next((g for g in ancestors(group) if dimension in opened[g].coords
                               and opened[g].coords[dimension].dims == (dimension,)), None)
                if holder is None:
                    check(False, f"{name}:{group}: dimension {dimension} has no coordinate")
                    continue
                coordinate = opened[holder].coords[dimension]
                attrs = coordinate.attrs
                check(coordinate.size == ds.sizes[dimension],
                      f"{name}:{group}: dimension {dimension} is {ds.sizes[dimension]} long, its coordinate in "
                      f"{holder} {coordinate.size}")
                check(isinstance(attrs.get("long_name"), str) and attrs["long_name"] != ""
                      and (isinstance(attrs.get("units"), str) and attrs["units"] != "" or "comment" in attrs),
                      f"{name}:{holder}: coordinate {dimension} has no long_name or units")


def check_index_coordinate(path, group, dimension, length_of):
    """A dimension that is a pure index has the coordinate 0 .. n-1 (n: the length of `length_of`)."""
    with open_group(path, group) as ds, h5py.File(path, "r") as f:
        n = f[length_of].shape[0]
        ok = dimension in ds.coords and np.array_equal(ds.coords[dimension].values, np.arange(n)) \
            and ds.coords[dimension].attrs.get("long_name") == f"index along dimension {dimension}" \
            and ds.coords[dimension].attrs.get("units") == "1"
        check(ok, f"{os.path.basename(path)}:{group}: {dimension} is not the index coordinate 0..{n - 1}")


def check_population_ragged(path, base):
    """A population is a CF contiguous ragged array twice over: /realisations' summit_count and
    asperity_count name the sample dimensions summit and asperity, which they split, as the
    offsets say, and whose coordinates every group of the population sees."""
    name = os.path.basename(path)
    with h5py.File(path, "r") as f:
        for count, sample, table, column in (("summit_count", "summit", "summits", "height_m"),
                                             ("asperity_count", "asperity", "asperities", "stiffness_n_per_m")):
            counts = f[f"{base}/realisations/{count}"]
            check(text(counts.attrs.get("sample_dimension", "")) == sample,
                  f"{name}:{base}/realisations/{count} has no sample_dimension = {sample}")
            offsets = f[f"{base}/realisations/{sample}_offset"][()]
            check(np.array_equal(counts[()], np.diff(offsets)), f"{name}:{base}: {count} disagrees with the offsets")
            rows = f[f"{base}/{table}/{column}"].shape[0]
            check(int(counts[()].sum()) == rows == offsets[-1], f"{name}:{base}: {count} does not sum to the {table}")
            for group in ("realisations", table):
                with open_group(path, f"{base}/{group}") as ds:
                    check(sample not in ds.dims or ds.sizes[sample] == rows,
                          f"{name}:{base}/{group}: dimension {sample} is not the {table}' rows")
            with open_group(path, base or "/") as ds:
                check(sample in ds.coords and np.array_equal(ds.coords[sample].values, np.arange(rows)),
                      f"{name}:{base or '/'}: no index coordinate {sample} beside the population's groups")


def check_members(path):
    """One row per realisation of every grid point, each selected by a member index of its own."""
    name = os.path.basename(path)
    with open_group(path, "/realisations") as ds, h5py.File(path, "r") as f:
        rows = f["realisations/voltage_rms_v"].shape[0]
        members = ds["member"].values
        check(len(members) == rows and len(np.unique(members)) == rows,
              f"{name}: member is not one unique index per row of /realisations")
        check("realisation" in ds.coords and "grid_point" in ds.coords,
              f"{name}: the realisation id and grid point are not coordinates of /realisations")
        for row in range(rows):
            picked = ds.sel(member=members[row])
            check(picked["voltage_rms_v"].ndim == 0 and np.array_equal(
                picked["voltage_rms_v"].values, f["realisations/voltage_rms_v"][row], equal_nan=True)
                and int(picked["realisation"]) == f["realisations/realisation"][row]
                and int(picked["grid_point"]) == f["realisations/grid_point"][row],
                f"{name}: sel(member={members[row]}) is not row {row} of /realisations")


def check_ragged_asperities(path):
    """CF contiguous ragged array: the counts sum to the sample dimension, as the offsets say."""
    name = os.path.basename(path)
    with open_group(path, "/asperities") as ds, h5py.File(path, "r") as f:
        count = ds["asperity_count"]
        check(count.attrs.get("sample_dimension") == "asperity",
              f"{name}: /asperities/asperity_count has no sample_dimension = asperity")
        check(int(count.values.sum()) == ds.dims["asperity"] == f["asperities/natural_frequency_hz"].shape[0],
              f"{name}: the asperity counts do not sum to the asperity dimension")
        check(np.array_equal(count.values, np.diff(f["realisations/asperity_offset"][()])),
              f"{name}: the asperity counts disagree with /realisations/asperity_offset")


def grid_point_of(f, values):
    """The row of /grid/values holding `values`, read with h5py."""
    rows = [g for g, row in enumerate(f["grid/values"][()]) if list(row) == list(values)]
    check(len(rows) == 1, f"no single grid point has the values {values}")
    return rows[0]


def check_one_parameter_selects(path):
    """.sel(swept parameter = value) gives that grid point's summary, and, indexed by the
    swept value and the realisation id, exactly that grid point's rows of /realisations."""
    with h5py.File(path, "r") as f, open_group(path, "/realisations") as ds:
        rows = ds.set_index(member=["surface_summits_count", "realisation"])
        for value in f["grid/values"][:, 0]:
            g = grid_point_of(f, [value])
            picked = rows.sel(surface_summits_count=value)
            expected = f["realisations/grid_point"][()] == g
            check(picked.dims.get("realisation") == int(expected.sum())
                  and np.array_equal(picked["realisation"].values, f["realisations/realisation"][expected])
                  and np.array_equal(picked["voltage_rms_v"].values, f["realisations/voltage_rms_v"][expected],
                                     equal_nan=True),
                  f"sweep.h5: /realisations .sel(surface_summits_count={value}) is not grid point {g}'s rows")
    with h5py.File(path, "r") as f, open_group(path, "/summary/voltage_rms_v") as ds:
        swept = [v for v in f["grid/values"][:, 0]]
        check(sorted(swept) == [1.0, 2.0], f"sweep.h5: the grid is {swept}, not the study's [1, 2]")
        for value in swept:
            g = grid_point_of(f, [value])
            picked = ds.sel(surface_summits_count=value)
            for statistic in ("mean", "count", "std"):
                check(np.array_equal(picked[statistic].values, f["summary/voltage_rms_v/" + statistic][g], equal_nan=True),
                      f"sweep.h5: sel(surface_summits_count={value})[{statistic!r}] is not grid point {g}'s")


def valid_rows(f, g, statistic):
    """The valid rows of grid point g of /realisations/voltage_rms_v, read with h5py."""
    rows = (f["realisations/grid_point"][()] == g) & (f["realisations/valid"][()] == 1)
    return f["realisations/voltage_rms_v"][rows]


def check_two_parameters_select(path):
    """A product grid of two swept parameters: /summary has one dimension per parameter, with
    the parameter's values as its coordinate, and .sel on both picks the grid point whose
    /grid/values row holds them: its count and mean are those of its valid rows of /realisations."""
    names = ("surface_summits_count", "model_belt_velocity_m_per_s")
    with h5py.File(path, "r") as f, open_group(path, "/summary/voltage_rms_v") as ds:
        check(ds["mean"].dims == names, f"sweep2.h5: /summary dims {ds['mean'].dims}, not {names}")
        check(list(ds["surface_summits_count"].values) == [1.0, 2.0]
              and list(ds["model_belt_velocity_m_per_s"].values) == [10.0, 12.0],
              "sweep2.h5: the summary's coordinates are not the study's swept values")
        for count in (1.0, 2.0):
            for velocity in (10.0, 12.0):
                g = grid_point_of(f, [count, velocity])
                picked = ds.sel(surface_summits_count=count, model_belt_velocity_m_per_s=velocity)
                kept = valid_rows(f, g, "voltage_rms_v")
                check(int(picked["count"]) == len(kept) and (len(kept) == 0 or np.isclose(
                    float(picked["mean"]), kept.mean(), rtol=1e-12)) and float(picked["max"]) == kept.max(),
                      f"sweep2.h5: sel(count={count}, velocity={velocity}) is not grid point {g}'s statistics")
    with open_group(path, "/grid") as ds:
        check(ds["values"].dims == ("grid_point", "parameter") and list(ds["surface_summits_count"].values) == [1.0, 2.0],
              "sweep2.h5: /grid is not one row per grid point with each parameter's values as a coordinate")


def check_not_a_product(path):
    """A sweep whose values repeat is no product: /summary stays over grid_point, the swept
    parameter an auxiliary coordinate of it, and set_index makes it selectable (both points of 2)."""
    with h5py.File(path, "r") as f, open_group(path, "/summary/voltage_rms_v") as ds:
        check(ds["mean"].dims == ("grid_point",) and "surface_summits_count" in ds.coords
              and ds["surface_summits_count"].dims == ("grid_point",),
              f"sweep_repeated.h5: /summary is over {ds['mean'].dims}, not a grid_point with the count as coordinate")
        check(list(ds["grid_point"].values) == [0, 1, 2], "sweep_repeated.h5: grid_point is not 0, 1, 2")
        picked = ds.set_index(grid_point="surface_summits_count").sel(grid_point=2.0)
        points = [g for g, row in enumerate(f["grid/values"][()]) if row[0] == 2.0]
        check(points == [0, 2] and list(picked["count"].values) == [len(valid_rows(f, g, "voltage_rms_v")) for g in points],
              "sweep_repeated.h5: selecting count 2 does not give grid points 0 and 2")


def evolving_study():
    """The evolving contact of tests/support/evolving_contact.toml (shared with
    pipeline/test_evolving_study.cpp): a release, wear and two stiffness steps, whose
    per-asperity parameters a run file records (steps as a CF contiguous ragged array)."""
    with open(os.path.join(SOURCE_DIR, "tests", "support", "evolving_contact.toml")) as f:
        return f.read()


def check_evolving(path):
    """The evolving contact's truth in a run file: release (finite, the run's end where never
    released) with its flag, wear rates, and steps as a ragged array over `step`."""
    with h5py.File(path, "r") as f:
        check(np.array_equal(f["asperity/release"][()], [20e-6, 10e-6]) and np.array_equal(f["asperity/released"][()], [0, 1]),
              f"{path}: /asperity/release and released do not hold the study's release_s")
        check(np.array_equal(f["asperity/wear_rate"][()], [0.2, 0.0]), f"{path}: /asperity/wear_rate is not the study's")
        counts = f["asperity/step_count"]
        check(text(counts.attrs.get("sample_dimension")) == "step", f"{path}: step_count has no sample_dimension = step")
        check(int(np.sum(counts[()])) == f["step/time"].shape[0] == 2, f"{path}: step_count does not sum to the steps")
        check(np.array_equal(f["step/time"][()], [5e-6, 12e-6]) and np.array_equal(f["step/factor"][()], [1.1, 0.95]),
              f"{path}: /step/time and factor are not the study's stiffness_steps")


def device_study():
    """The known device of the inverse tests (tests/support/known_device.toml, shared with
    tests/support/inverse_device.hpp) with two asperities and the quick prior's bank."""
    support = os.path.join(SOURCE_DIR, "tests", "support")
    with open(os.path.join(support, "known_device.toml")) as device, \
            open(os.path.join(support, "known_device_quick_prior.toml")) as prior:
        return ("duration_s = 20e-6\n" + device.read() + "[[surface.asperity]]\nstiffness_n_per_m = 62\n[inverse]\n"
                + prior.read())


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--binary")
    parser.add_argument("--work-dir")
    parser.add_argument("--check-units", nargs="+", metavar="FILE")
    args = parser.parse_args()
    if args.check_units:
        distinct = check_netcdf_c_and_units(args.check_units)
        return report(f"{len(args.check_units)} files: ncdump -h reads them, CF-1.10, {distinct} units all parse")
    if not args.binary:
        parser.error("--binary is required")
    binary = os.path.abspath(args.binary)
    with tempfile.TemporaryDirectory(prefix="stengmc-netcdf-") as scratch:
        work = os.path.abspath(args.work_dir) if args.work_dir else scratch
        os.makedirs(work, exist_ok=True)
        out = lambda name: os.path.join(work, name)  # noqa: E731
        study = lambda name: os.path.join(SOURCE_DIR, "studies", name)  # noqa: E731

        # Run files: a paper study (spectra, ESPRIT lines, spectrogram, element currents)
        # and a random surface's realisation (its contact population under /surface).
        run(binary, "run", study("paper/fig6_vb1_l50.toml"), "-o", out("run.h5"), cwd=work)
        # Its k = 25 N/m asperity reaches l: the run is flagged and its circuit stops early.
        run(binary, "run", study("paper/fig6_vb1.toml"), "-o", out("flagged.h5"), cwd=work)
        run(binary, "run", study("surfaces/gw_vb10.toml"), "--realisation", "3", "-o", out("random.h5"), cwd=work)
        run(binary, "circuit", out("run.h5"), "-R", "1e6", "-o", out("circuit.h5"), cwd=work)
        with open(out("evolving.toml"), "w") as f:
            f.write(evolving_study())
        run(binary, "run", out("evolving.toml"), "-o", out("evolving.h5"), cwd=work)
        run(binary, "spectrum", out("run.h5"), "--settings", study("paper/fig6_vb1_l50.toml"), "-o", out("spectrum.h5"),
            cwd=work)
        run(binary, "surface", os.path.join(SOURCE_DIR, "surfaces", "pet_on_steel_gw.toml"), "--realisations", "2",
            "--seed", "1", "-o", out("surface.h5"), cwd=work)
        surface = os.path.join(SOURCE_DIR, "surfaces", "lognormal_count.toml")
        with open(out("single.toml"), "w") as f:
            f.write(ENSEMBLE.format(surface=surface))
        with open(out("sweep.toml"), "w") as f:
            f.write(ENSEMBLE.format(surface=surface) + SWEEP)
        with open(out("sweep2.toml"), "w") as f:
            f.write(ENSEMBLE.format(surface=surface) + SWEEP_TWO_PARAMETERS)
        run(binary, "run", out("single.toml"), "-j", "2", "-o", out("single.h5"), cwd=work)
        run(binary, "run", out("sweep.toml"), "-j", "2", "-o", out("sweep.h5"), cwd=work)
        run(binary, "run", out("sweep2.toml"), "-j", "2", "-o", out("sweep2.h5"), cwd=work)
        with open(out("sweep_repeated.toml"), "w") as f:
            f.write(ENSEMBLE.format(surface=surface) + SWEEP_REPEATED)
        run(binary, "run", out("sweep_repeated.toml"), "-j", "2", "-o", out("sweep_repeated.h5"), cwd=work)
        with open(out("device.toml"), "w") as f:
            f.write(device_study())
        run(binary, "calibrate", out("device.toml"), "-j", "2", "-o", out("bank.h5"), cwd=work)
        # A record of the device (its two asperities) as the CSV `t,V` invert reads.
        run(binary, "run", out("device.toml"), "-o", out("record.h5"), cwd=work)
        with h5py.File(out("record.h5"), "r") as f:
            np.savetxt(out("record.csv"), np.column_stack([f["time"][()], f["circuit/voltage"][()]]),
                       delimiter=",", header="t,V", comments="", fmt="%.17g")
        run(binary, "invert", out("record.csv"), "--known", out("device.toml"), "--bank", out("bank.h5"),
            "-o", out("inverse.h5"), cwd=work)

        # A tracking file (`stengmc track`): its track x window tables hold NaN where a track is absent.
        run(binary, "run", os.path.join(SOURCE_DIR, "studies", "monitoring", "record_unexcited.toml"), "-o", out("monitoring.h5"),
            cwd=work)
        run(binary, "track", out("monitoring.h5"), "--known", os.path.join(SOURCE_DIR, "studies", "monitoring", "device_unexcited.toml"),
            "-o", out("tracking.h5"), cwd=work)

        files = ["run.h5", "flagged.h5", "evolving.h5", "random.h5", "circuit.h5", "spectrum.h5", "surface.h5", "single.h5", "sweep.h5",
                 "sweep2.h5", "sweep_repeated.h5", "bank.h5", "inverse.h5", "tracking.h5"]
        for name in files:
            check_every_group(out(name))
            check_every_dimension_has_a_coordinate(out(name))
        distinct_units = check_netcdf_c_and_units([out(name) for name in files])

        expect_dims(out("tracking.h5"), "/tracking", "stiffness_n_per_m", ("track", "window_time"))
        expect_coordinate(out("tracking.h5"), "/tracking", "window_time", "/tracking/window_time")
        with xr.open_dataset(out("tracking.h5"), group="/tracking", engine="h5netcdf") as ds:
            k = ds["stiffness_n_per_m"].values
            check(np.isnan(k).any() and np.isfinite(k).any(), "tracking.h5: stiffness has no NaN gaps or no values")

        for name in ("run.h5", "random.h5"):
            r = out(name)
            expect_coordinate(r, "/", "time", "/time")
            expect_dims(r, "/circuit", "voltage", ("time",))
            expect_dims(r, "/circuit", "charge", ("time",))
            expect_length(r, "/circuit", "time", "/time")
            expect_dims(r, "/asperity", "x", ("asperity", "time"))
            expect_dims(r, "/asperity", "v", ("asperity", "time"))
            expect_dims(r, "/asperity", "k", ("asperity",))
            expect_dims(r, "/events", "time", ("event",))
            expect_coordinate(r, "/spectrum", "frequency", "/spectrum/frequency")
            expect_dims(r, "/spectrum", "voltage", ("frequency",))
            expect_dims(r, "/spectrum/peaks", "frequency", ("peak",))
            expect_coordinate(r, "/surface/realisations", "realisation", "/surface/realisations/realisation")
            expect_dims(r, "/surface/asperities", "stiffness_n_per_m", ("asperity",))
        r = out("run.h5")
        expect_dims(r, "/asperity", "current", ("asperity", "time"))
        expect_dims(r, "/spectrum", "current", ("asperity", "frequency"))
        expect_dims(r, "/spectrum/lines", "frequency", ("line",))
        expect_dims(r, "/spectrogram", "voltage", ("window_time", "frequency"))
        expect_coordinate(r, "/spectrogram", "window_time", "/spectrogram/window_time")
        expect_coordinate(r, "/spectrogram", "frequency", "/spectrogram/frequency")
        expect_dims(out("random.h5"), "/surface/summits", "height_m", ("summit",))
        check_population_ragged(out("random.h5"), "/surface")
        # Pure indices: 0 .. n-1 with a long_name saying so.
        check_index_coordinate(r, "/events", "event", "/events/time")
        check_index_coordinate(r, "/asperity", "asperity", "/asperity/k")
        check_index_coordinate(r, "/spectrum/lines", "line", "/spectrum/lines/frequency")
        # A flagged run's circuit spans the leading samples of /time only: its own axis.
        f = out("flagged.h5")
        expect_dims(f, "/circuit", "voltage", ("valid_time",))
        expect_dims(f, "/asperity", "current", ("asperity", "valid_time"))
        expect_dims(f, "/asperity", "x", ("asperity", "time"))
        with h5py.File(f, "r") as h:
            check(h["circuit/voltage"].shape[0] < h["time"].shape[0], "flagged.h5: the circuit did not stop early")
            # Its own axis has the times of the samples it reached, in seconds.
            reached = h["circuit/voltage"].shape[0]
            check("valid_time" in h and np.array_equal(h["valid_time"][()], h["time"][:reached])
                  and text(h["valid_time"].attrs.get("units")) == "s",
                  "flagged.h5: /valid_time is not the leading samples of /time")
        expect_coordinate(f, "/", "valid_time", "/valid_time")

        check_evolving(out("evolving.h5"))
        expect_dims(out("evolving.h5"), "/step", "time", ("step",))

        c = out("circuit.h5")
        expect_coordinate(c, "/", "time", "/time")
        expect_dims(c, "/circuit", "voltage", ("time",))
        expect_dims(c, "/asperity", "v", ("asperity", "time"))
        s = out("spectrum.h5")
        expect_coordinate(s, "/spectrum", "frequency", "/spectrum/frequency")
        expect_dims(s, "/spectrum", "voltage", ("frequency",))
        expect_dims(s, "/spectrogram", "voltage", ("window_time", "frequency"))

        p = out("surface.h5")
        expect_coordinate(p, "/realisations", "realisation", "/realisations/realisation")
        expect_dims(p, "/realisations", "summit_count", ("realisation",))
        expect_dims(p, "/summits", "height_m", ("summit",))
        expect_dims(p, "/asperities", "stiffness_n_per_m", ("asperity",))
        expect_coordinate(p, "/target/heights", "value", "/target/heights/value")
        expect_dims(p, "/target/heights", "density", ("value",))
        expect_dims(p, "/load_separation", "total_load_n", ("separation_m",))
        check_population_ragged(p, "")
        check_index_coordinate(p, "/realisations", "realisation_boundary", "/realisations/summit_offset")

        for name, summary_dimensions in (("single.h5", ("grid_point",)), ("sweep.h5", ("surface_summits_count",)),
                                         ("sweep2.h5", ("surface_summits_count", "model_belt_velocity_m_per_s")),
                                         ("sweep_repeated.h5", ("grid_point",))):
            e = out(name)
            expect_coordinate(e, "/realisations", "member", "/realisations/member")
            for variable in ("voltage_rms_v", "valid", "grid_point", "realisation", "fft_ratio"):
                expect_dims(e, "/realisations", variable, ("member",))
            expect_dims(e, "/asperities", "natural_frequency_hz", ("asperity",))
            expect_dims(e, "/summary/voltage_rms_v", "mean", summary_dimensions)
            expect_dims(e, "/summary/pooled", "fft_ratio_low", summary_dimensions)
            check_members(e)
            check_ragged_asperities(e)
        check_one_parameter_selects(out("sweep.h5"))
        check_two_parameters_select(out("sweep2.h5"))
        check_not_a_product(out("sweep_repeated.h5"))
        trace = "/traces/realisation_0"
        expect_coordinate(out("single.h5"), trace, "time", trace + "/time")
        expect_dims(out("single.h5"), trace, "voltage", ("time",))
        w = out("sweep.h5")
        expect_dims(w, "/grid", "values", ("surface_summits_count", "parameter"))
        expect_coordinate(w, "/grid", "parameter", "/grid/parameter")
        expect_dims(w, "/draws", "values", ("member", "parameter"))
        expect_coordinate(w, "/draws", "parameter", "/draws/parameter")
        trace = "/traces/point_1/realisation_0"
        expect_coordinate(w, trace, "time", trace + "/time")
        expect_dims(w, trace, "voltage", ("time",))

        b = out("bank.h5")
        expect_coordinate(b, "/records", "realisation", "/records/realisation")
        expect_dims(b, "/records", "naive_counts", ("realisation", "threshold"))
        expect_dims(b, "/atoms", "onset_values", ("onset_node", "theta_sample"))
        expect_dims(b, "/atoms", "tail_phase", ("node",))
        for fit_class in ("fits", "misfits"):
            expect_dims(b, "/maps/" + fit_class, "confusion", ("estimated_count", "count"))
            expect_dims(b, "/maps/" + fit_class, "median_score_quantile", ("count_bin",))

        i = out("inverse.h5")
        expect_dims(i, "/inverse/records", "noise_sigma_v", ("record",))
        check_index_coordinate(i, "/inverse/records", "record", "/inverse/records/noise_sigma_v")
        expect_coordinate(i, "/inverse/count", "counts", "/inverse/count/counts")
        expect_dims(i, "/inverse/count", "probability", ("record", "counts"))
        expect_dims(i, "/inverse/lines", "frequency_hz", ("line",))
        trace = "/inverse/traces/record_0"
        expect_coordinate(i, trace, "time", trace + "/time")
        expect_dims(i, trace, "model", ("time",))

    return report(f"all {len(files)} output kinds open in xarray with named dimensions, units and long names, "
                  f"ncdump -h reads them, and UDUNITS-2 parses their {distinct_units} distinct units")


if __name__ == "__main__":
    sys.exit(main())
