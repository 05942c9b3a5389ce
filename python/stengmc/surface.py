"""stengmc.Surface: a surface's description — a surface file, a study's [surface], or
keyword arguments with a surface file's keys — and Surface.sample: one realisation's summits
and asperities as numpy arrays, drawn by the library exactly as `stengmc surface --seed S`
and `stengmc run --realisation R` draw them (the same random streams: a realisation depends
on the surface, the seed and its id alone)."""
import os

from . import _core
from .arguments import MAX_REALISATION, whole_number
from .sections import Section
from .toml_text import toml_text

#: The largest seed, as `stengmc surface --seed` takes (files store it as int64).
MAX_SEED = 2**63 - 1


def sample_surface(core_surface, realisation, seed):
    """The checked arguments handed to the library (shared by Surface and a study's [surface])."""
    realisation = whole_number("realisation", realisation, 0, MAX_REALISATION)
    seed = whole_number("seed", seed, 0, MAX_SEED)
    return _core.sample_surface(core_surface, seed, realisation)


SAMPLE_DOC = """
    Returns a dict (SI units; arrays are numpy, one value per summit or per asperity):
      realisation, seed   what was drawn
      summits             every summit drawn, in draw order (empty for a fixed list):
                          height_m [m] (z = the asperity height h), x_m, y_m [m] (position on
                          the nominal area), drive_phase_rad [rad], onset_s [s] (Model 2
                          contact onsets; 0 without an [onset] law), normal_load_n [N] (0: not
                          in contact); sampled_stiffness_n_per_m [N/m] (stiffness rule
                          "sampled" only); interference_m, patch_radius_m [m] (with
                          [materials] only)
      asperities          the summits in contact, which a run simulates, in summit order:
                          stiffness_n_per_m [N/m], mass_kg [kg], normal_load_n [N], height_m
                          [m], drive_phase_rad [rad], onset_s [s], charge_density_c_per_m2
                          [C/m^2], effective_thickness_m, width_m, length_m [m] (the S-TENG
                          element); summit (int64 index into the summit arrays; random
                          surfaces only)
      contact             with [materials]: a dict summit_radius_m [m], separation_m [m]
                          (the flat's position on the height axis; 0 under a fixed load),
                          total_load_n [N], real_area_m2 [m^2], contact_density [-] (A_r/A0),
                          screening_estimate [-], hertz_load, load_carried (bools),
                          interacting_iterations, interacting_converged; else None
    These are the `stengmc surface` file's /summits and /asperities of that realisation and
    the run file's /asperity table of `stengmc run --realisation`, value for value.
    realisation or seed not a whole number: TypeError; outside 0..2**63-1: stengmc.InputError
    (a ValueError) naming the argument. A realisation that cannot be sampled (an asperity in
    contact with k <= 0) raises stengmc.ModelError."""


class Surface:
    """A surface's description, read and checked by the library (docs/study-files.md:
    surface files): a fixed list of asperities (kind = "list") or a random surface (kind =
    "random") from which each realisation draws its summits. Make one with
    stengmc.load_surface(path, text or dict) or stengmc.surface(**keys); a study's own is
    study.surface (sample it with study.surface.sample()).

    Attributes: name (the file, or the name given to the text), is_random (bool)."""

    def __init__(self, core_surface):
        self._surface = core_surface

    @property
    def name(self):
        """The file it was read from, or the name given to its text."""
        return self._surface.name

    @property
    def is_random(self):
        """True for a random surface (kind = "random"), False for a fixed list."""
        return self._surface.is_random

    def sample(self, realisation=0, seed=0):
        """Realisation `realisation` (0 <= realisation < 2**63) of the surface under the master
        seed `seed` (0 <= seed < 2**63), as `stengmc surface --seed SEED --first REALISATION`
        draws it; a fixed list gives its asperities whatever the seed.
        """
        return sample_surface(self._surface, realisation, seed)

    def __repr__(self):
        return f"<stengmc.Surface {self.name!r}: {'random' if self.is_random else 'fixed list'}>"


Surface.sample.__doc__ += SAMPLE_DOC


def load_surface(source, name="surface.toml"):
    """A surface from a surface file's path, TOML text (a str with a line break) or a dict of
    its keys (kind = "random", nominal_area_m2, [summits], [heights], [stiffness], ...:
    docs/study-files.md, surface files).

    For text and dicts, `name` stands for the file in messages, and relative paths in it (a
    histogram file) are taken from that name's folder. Raises stengmc.InputError (a
    ValueError) naming the file, the line and the key: a misspelt key, a value out of range,
    a study file given instead of a surface file.
    """
    if isinstance(source, dict):
        try:
            text = toml_text(source)
        except TypeError as error:
            raise TypeError(f"load_surface: {error}") from None
        return Surface(_core.parse_surface(text, os.fspath(name)))
    if isinstance(source, str) and "\n" in source:
        return Surface(_core.parse_surface(source, os.fspath(name)))
    if isinstance(source, (str, os.PathLike)):
        return Surface(_core.read_surface(os.fspath(source)))
    raise TypeError(f"load_surface: expected a path, TOML text or a dict, got a {type(source).__name__}")


def surface(*, name="surface.toml", **keys):
    """A surface from keyword arguments, one per key of a surface file (as a study's inline
    [surface] table has them; nested tables as dicts), e.g.

        stengmc.surface(kind="random", nominal_area_m2=1e-7,
                        summits={"count_rule": "fixed", "count": 100},
                        heights={"kind": "normal", "mean": 110e-6, "std": 0.25e-6},
                        stiffness={"rule": "sampled", "kind": "lognormal", "median": 60, "sigma_log": 0.5})

    `file="path.toml"` alone loads that surface file. `name` stands for the file in messages.
    Checked by the library's reader: a refused key or value raises stengmc.InputError (a
    ValueError) naming it; a value TOML cannot hold (an object) raises TypeError naming it.
    """
    if set(keys) == {"file"}:
        return load_surface(keys["file"])
    return load_surface(keys, name)


class StudySurface(Section):
    """A study's [surface] table: its keys as attributes, readable and settable like every
    Section's (study.surface.heights.std = 0.3e-6), and the surface the study's realisations
    draw from (its inline table or the file `file` names), which sample() draws."""

    def sample(self, realisation=0, seed=None):
        """Realisation `realisation` of the study's surface under `seed` (None: the study's
        seed), as `stengmc run STUDY --realisation REALISATION` draws its asperities.
        """
        study = self._study
        return sample_surface(_core.study_surface(study._study), realisation, study.seed if seed is None else seed)

    def to_surface(self):
        """The study's surface as a stengmc.Surface (what every realisation draws from)."""
        return Surface(_core.study_surface(self._study._study))

    def __dir__(self):
        return sorted(set(super().__dir__()) | {"sample", "to_surface"})


StudySurface.sample.__doc__ += SAMPLE_DOC
