"""stengmc.open: one call for every output file, dispatching on its root attribute
file_type. A run file comes back as a RunFile (a Run); every other kind as an OutputFile,
whose to_xarray() reads each group generically."""
from .output_file import OutputFile
from .run_file import RunFile


def open(path):  # noqa: A001 - stengmc.open, like h5py.File / xarray.open_dataset for our files
    """Opens a file the command line (or Python) wrote: `stengmc run`'s as a RunFile (a Run,
    with to_xarray()); an ensemble, spectrum, circuit, surface, inverse or bank file as an
    OutputFile (attrs, groups, to_xarray() -> dict group path -> xarray.Dataset).
    Raises FileNotFoundError for a missing path, ValueError for a file that is not HDF5."""
    import os
    path = os.fspath(path)
    if not os.path.exists(path):
        raise FileNotFoundError(f"path = {path!r}: no such file")
    try:
        opened = OutputFile(path)
    except OSError as error:  # h5py's "file signature not found" and the like
        raise ValueError(f"path = {path!r}: not an HDF5 output file of stengmc ({error})") from None
    return RunFile(path) if opened.file_type == "stengmc-run" else opened
