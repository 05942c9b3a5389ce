"""Whole-number arguments checked before they reach the library: pybind11 turns one that does
not fit its C++ type (realisation=-1, 2**64) into a raw "incompatible function arguments",
and the thread library crashed on threads=100000. Each is refused naming the argument and
its range, as the command line refuses its options."""
import operator

from .errors import InputError

#: The largest realisation id, as `stengmc run --realisation` takes (files store it as int64).
MAX_REALISATION = 2**63 - 1


def whole_number(name, value, low, high):
    """`value` as an int in [low, high]: TypeError when it is not a whole number (a float, a
    string), stengmc.InputError (a ValueError) when it is outside the range."""
    if isinstance(value, bool):
        raise TypeError(f"{name} = {value!r}: expected a whole number from {low} to {high}, not a bool")
    try:
        number = operator.index(value)  # int and numpy integers; not 1.0, which may have been rounded
    except TypeError:
        raise TypeError(f"{name} = {value!r}: expected a whole number from {low} to {high}, "
                        f"not a {type(value).__name__}") from None
    if not low <= number <= high:
        raise InputError(f"{name} = {number}: expected a whole number from {low} to {high}")
    return number
