"""Any file the command line writes (run, ensemble, spectrum, circuit, surface, inverse,
calibration bank, ...), opened generically: its root attributes, its groups, and each group
as an xarray.Dataset. Nothing here names a dataset, so a file whose layout grows or changes
(the ensemble file's sweep coordinates) opens the same way."""
import os


def _h5py():
    try:
        import h5py
    except ImportError:
        raise ImportError("stengmc.open needs h5py (Debian: apt-get install python3-h5py; pip install h5py)") from None
    return h5py


def _text(value):
    """HDF5 string attributes come back as bytes or numpy strings: plain str for a notebook."""
    if isinstance(value, bytes):
        return value.decode("utf-8", "replace")
    if hasattr(value, "item") and getattr(value, "shape", None) == ():
        return value.item()
    return value


def _ancestors(group):
    """"a/b/c" -> "a/b", "a", "/": where netCDF-4 looks for a dimension a group uses."""
    parts = group.split("/")
    return ["/".join(parts[:i]) for i in range(len(parts) - 1, 0, -1)] + ["/"]


class OutputFile:
    """A stengmc output file (HDF5, netCDF-4 compatible), read lazily.

    path          the file
    file_type     its root attribute file_type ("stengmc-run", "stengmc-ensemble", ...)
    attrs         dict of its root attributes (the study text, seed, version, ...)
    groups        the paths of its groups that hold datasets, "/" for the root, as h5py names them
    to_xarray()   dict group path -> xarray.Dataset (one per entry of `groups`; xarray 2023.01,
                  Debian 12's, has no DataTree), every array in memory and the file closed
    dataset(g)    the xarray.Dataset of one group
    """

    def __init__(self, path):
        self.path = os.fspath(path)
        h5py = _h5py()
        groups = []
        with h5py.File(self.path, "r") as f:
            self.attrs = {name: _text(value) for name, value in f.attrs.items()}

            def visit(name, item):
                if isinstance(item, h5py.Group) and any(isinstance(child, h5py.Dataset) for child in item.values()):
                    groups.append(name)

            if any(isinstance(child, h5py.Dataset) for child in f.values()):
                groups.append("/")
            f.visititems(visit)
        self.groups = groups
        self.file_type = self.attrs.get("file_type", "")

    def dataset(self, group="/"):
        """One group as an xarray.Dataset (xarray's h5netcdf engine), loaded and closed.
        Its dimensions, coordinates, units and long names are the file's."""
        try:
            import xarray
        except ImportError:
            raise ImportError("to_xarray needs xarray and h5netcdf (Debian: apt-get install python3-xarray "
                              "python3-h5netcdf; pip install 'stengmc[xarray]')") from None
        if group not in self.groups:
            raise ValueError(f"group = {group!r}: {self.path} has no group of datasets by that name; "
                             f"it has {self.groups}")
        with xarray.open_dataset(self.path, engine="h5netcdf", group=None if group == "/" else group) as opened:
            return opened.load()

    def to_xarray(self):
        """Every group of datasets as an xarray.Dataset: a dict group path -> Dataset, "/" the
        root (a run's time axis). Groups nest as paths ("spectrum/peaks"). A dimension a group
        uses without a coordinate of its own gets its enclosing group's coordinate of that name
        and length (netCDF-4 scopes dimensions that way; xarray opens one group alone), so a
        run's /asperity traces have the root's time: traces.sel(time=..., method="nearest")."""
        datasets = {group: self.dataset(group) for group in self.groups}
        for group, dataset in datasets.items():
            if group == "/":
                continue
            inherited = {}
            for dim, size in dataset.sizes.items():
                if dim in dataset.coords:
                    continue
                for ancestor in _ancestors(group):
                    outer = datasets.get(ancestor)
                    if outer is not None and dim in outer.coords and outer.sizes[dim] == size:
                        inherited[dim] = outer.coords[dim].variable
                        break
            if inherited:
                datasets[group] = dataset.assign_coords(inherited)
        return datasets

    def __repr__(self):
        return f"<stengmc.OutputFile {self.path!r}: {self.file_type or 'no file_type'}, {len(self.groups)} groups>"
