"""stengmc from Python: load a study (a file, TOML text or a dict), run one realisation or
an ensemble and get numpy arrays and the summaries the command line prints, or invert a
measured record (README: Python; docs/python.md).

    import stengmc
    study = stengmc.load_study("studies/paper/fig2_k155.toml")
    run = study.run()                  # run.time_s, run.voltage_v, run.summary, ...
    stengmc.open("results/fig2_k155.h5").to_xarray()   # any output file: group -> xarray.Dataset
"""
from . import _core
from .circuit import circuit
from .errors import Error, InputError, ModelError
from .inverse import invert
from .opening import open
from .output_file import OutputFile
from .results import Ensemble, Run
from .run_file import RunFile
from .spectrum import spectrum
from .study import Study, load_study
from .surface import Surface, load_surface, surface
from .toml_text import toml_text

__version__ = _core.version
git_revision = _core.git_revision


def run(study, realisation=0, progress=False):
    """Runs one realisation of `study` (a Study, or what load_study takes); a Run."""
    return (study if isinstance(study, Study) else load_study(study)).run(realisation, progress)


def run_ensemble(study, threads=0, progress=False):
    """Runs every realisation of an [ensemble] study on `threads` threads; an Ensemble."""
    return (study if isinstance(study, Study) else load_study(study)).run_ensemble(threads, progress)


__all__ = ["circuit", "Ensemble", "Error", "InputError", "ModelError", "OutputFile", "Run", "RunFile", "Study", "invert",
           "load_study", "load_surface", "open", "run", "spectrum", "surface", "Surface",
           "run_ensemble", "toml_text", "git_revision"]
