"""A study: read from a file, from TOML text, or from a dict (README: study files)."""
import os
import tomllib

from . import _core
from .arguments import MAX_REALISATION, whole_number
from .errors import InputError
from .progress import Progress
from .results import Ensemble, Run
from .sections import SECTIONS, Section
from .surface import StudySurface
from .toml_text import toml_text


class Study:
    """A study read and checked by the library; run it with run() or run_ensemble().

    Attributes: file, text (the TOML), title, seed, duration_s [s], sample_rate_hz [Hz],
    surface_file, output_file, random_surface (bool), is_ensemble, realisations; and the
    study's tables as Sections, readable and settable: model, surface, circuit, domain, noise,
    spectrum, output, ensemble, inverse (study.noise.snr_db = 20; study.model.kind is the
    model's name). A set value is checked by the study reader: a refused one raises
    stengmc.InputError (a ValueError) naming the key, and the study stays as it was.
    """

    def __init__(self, core_study):
        self._study = core_study

    def __getattr__(self, name):
        if name.startswith("_"):  # not set yet (copy, pickle): no delegation
            raise AttributeError(name)
        if name == "surface":  # its keys, and sample() of the surface the study draws from
            return StudySurface(self, (name,))
        if name in SECTIONS:
            return Section(self, (name,))
        return getattr(self._study, name)

    def __setattr__(self, name, value):
        # Top-level keys (duration_s, seed, ...) are set through the study reader too.
        if name.startswith("_"):
            object.__setattr__(self, name, value)
        elif name in SECTIONS:
            raise AttributeError(f"{name}: set its keys (study.{name}.<key> = ...), not the table")
        else:
            self._set((name,), value)

    def _toml(self):
        """The study as a dict, read from its text (tomllib: Python's reader, not ours)."""
        return tomllib.loads(self._study.text)

    def _set(self, path, value):
        """Sets (or, for None, removes) the key at `path` and reads the whole study again;
        InputError (a ValueError) naming the key when the reader refuses it, study unchanged."""
        study = self._toml()
        table = study
        for key in path[:-1]:
            table = table.setdefault(key, {})
            if not isinstance(table, dict):
                raise TypeError(f"{'.'.join(path)}: {key} is not a table")
        if value is None:
            table.pop(path[-1], None)
        else:
            table[path[-1]] = value
        try:
            text = toml_text(study)
        except (TypeError, ValueError) as error:
            raise TypeError(f"{'.'.join(path)} = {value!r}: {error}") from None
        try:
            core = _core.parse_study(text, self._study.file)
        except InputError as error:
            raise InputError(f"{'.'.join(path)} = {value!r} refused: {error}") from None
        object.__setattr__(self, "_study", core)

    def __dir__(self):
        # The study's attributes live on the extension's object: list them, so tab completion
        # and dir() in a notebook show what there is to read.
        own = set(super().__dir__())
        return sorted(own | {name for name in dir(self._study) if not name.startswith("_")} | set(SECTIONS))

    def run(self, realisation=0, progress=False):
        """Runs one realisation (as `stengmc run --realisation R`, 0 <= R < 2**63); a Run."""
        realisation = whole_number("realisation", realisation, 0, MAX_REALISATION)
        return Run(_core.run(self._study, realisation, progress))

    def run_ensemble(self, threads=0, progress=False):
        """Runs every realisation of the [ensemble] (0 threads: every core; at most
        _core.MAX_THREADS, 1024); an Ensemble. The records are the same for any number of threads.

        progress: False (nothing), True (a tqdm bar when tqdm is installed, else the
        library's bar on stderr), or a callable(done, total) called as each realisation
        finishes, counting over the whole job (every grid point of a sweep); it is called
        from a worker thread, one call at a time, and an exception it raises stops the
        ensemble and is raised here."""
        threads = whole_number("threads", threads, 0, _core.MAX_THREADS)
        reporter = Progress(progress)
        try:
            return Ensemble(_core.run_ensemble(self._study, threads, reporter.library_bar, reporter.on_progress))
        finally:
            reporter.close()

    def __repr__(self):
        return (f"<stengmc.Study {self.file!r}: {self._study.model}, {self.duration_s:g} s at "
                f"{self.sample_rate_hz:g} Hz>")


def load_study(source, name="study.toml"):
    """A study from a file path, TOML text (a str with a line break) or a dict.

    For text and dicts, `name` stands for the file in messages, and relative paths in it
    (a surface file) are taken from that name's folder (the working folder by default).
    Raises stengmc.InputError (a ValueError) naming the file, the line and the key.
    """
    if isinstance(source, dict):
        return Study(_core.parse_study(toml_text(source), os.fspath(name)))
    if isinstance(source, str) and "\n" in source:
        return Study(_core.parse_study(source, os.fspath(name)))
    if isinstance(source, (str, os.PathLike)):
        return Study(_core.read_study(os.fspath(source)))
    raise TypeError(f"load_study: expected a path, TOML text or a dict, got a {type(source).__name__}")
