"""A study's tables as attributes a notebook can read and set: study.noise.snr_db = 20.
Each change is written into the study's TOML and the whole study is read again by the
library's reader, so a value is checked exactly as in a study file (its type, its range,
a misspelt key), and the error names the key; a refused change leaves the study as it was."""

#: The study's tables, as attributes of a Study (README: study files).
SECTIONS = ("model", "surface", "circuit", "domain", "noise", "spectrum", "output", "ensemble", "inverse")


class Section:
    """One table of a study ([noise], [surface.summits], ...): its keys as attributes (SI
    units in their names: snr_db, belt_velocity_m_per_s, ...), nested tables as Sections,
    arrays of tables as lists of dicts (read-only copies). Setting a key re-reads the study."""

    def __init__(self, study, path):
        object.__setattr__(self, "_study", study)
        object.__setattr__(self, "_path", path)

    def _table(self):
        table = self._study._toml()
        for key in self._path:
            table = table.get(key, {})
        return table

    def __getattr__(self, key):
        if key.startswith("_"):
            raise AttributeError(key)
        table = self._table()
        dotted = ".".join(self._path + (key,))
        if key not in table:
            raise AttributeError(f"{dotted}: not set in the study (its keys here: {sorted(table) or 'none'}); "
                                 "setting it adds it, and the study's reader checks it")
        value = table[key]
        return Section(self._study, self._path + (key,)) if isinstance(value, dict) else value

    def __setattr__(self, key, value):
        self._study._set(self._path + (key,), value)

    def __delattr__(self, key):
        self._study._set(self._path + (key,), None)

    def __dir__(self):
        return sorted(self._table())

    def to_dict(self):
        """The table as a plain dict (a copy)."""
        import copy
        return copy.deepcopy(self._table())

    def __repr__(self):
        return f"<stengmc.Section [{'.'.join(self._path)}] {self._table()!r}>"
