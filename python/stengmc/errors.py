"""The exceptions stengmc raises; the C++ library's errors arrive as these
(python/errors.cpp), with the library's message: the file, the key or line, and what
was expected."""


class Error(RuntimeError):
    """Any failure of stengmc's library."""


class InputError(Error, ValueError):
    """Bad input: a study, surface, bank or array that cannot be used (the CLI's exit code 2)."""


class ModelError(Error):
    """The model left its domain of validity, e.g. x reached l under policy "error" (exit code 3)."""
