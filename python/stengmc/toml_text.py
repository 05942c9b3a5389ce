"""A study given as a dict, written as TOML text for the library's study reader.

The standard library reads TOML (tomllib) but does not write it; a study needs only
tables, arrays of tables and arrays of numbers, strings and booleans, which this writes.
Floats are written with repr(), the shortest text that reads back as the same double, so
a study from a dict runs bitwise as the same study from a file.
"""
import json
import math
import re

_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")


def _key(name):
    if not isinstance(name, str):
        raise TypeError(f"study key {name!r}: keys are strings")
    return name if _BARE_KEY.match(name) else json.dumps(name)


def _value(value, where):
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)  # a TOML basic string
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_value(v, where) for v in value) + "]"
    if hasattr(value, "tolist"):  # a numpy array or scalar
        return _value(value.tolist(), where)
    raise TypeError(f"study key {where}: cannot write a {type(value).__name__} in TOML")


def _is_table_array(value):
    return isinstance(value, (list, tuple)) and len(value) > 0 and all(isinstance(v, dict) for v in value)


def _table(table, path, lines):
    # A table's own keys come before its sub-tables (TOML's rule).
    for name, value in table.items():
        if not isinstance(value, dict) and not _is_table_array(value):
            lines.append(f"{_key(name)} = {_value(value, '.'.join(path + [str(name)]))}")
    for name, value in table.items():
        inner = path + [_key(name)]
        if isinstance(value, dict):
            lines.append("")
            lines.append("[" + ".".join(inner) + "]")
            _table(value, inner, lines)
        elif _is_table_array(value):
            for item in value:
                lines.append("")
                lines.append("[[" + ".".join(inner) + "]]")
                _table(item, inner, lines)


def toml_text(study):
    """The dict `study` (nested dicts are tables, lists of dicts arrays of tables) as TOML."""
    if not isinstance(study, dict):
        raise TypeError(f"a study dict was expected, got a {type(study).__name__}")
    lines = []
    _table(study, [], lines)
    return "\n".join(lines).lstrip("\n") + "\n"
