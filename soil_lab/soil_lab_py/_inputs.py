"""Input checks shared by the fits: 1-D finite float arrays of equal length, with errors that name
the argument, the offending index and value, and what was expected."""

import numpy as np


class FitInputError(ValueError):
    """Bad input to a fit (names the argument and what was expected)."""


def finite_array(name, values, unit=""):
    """``values`` as a 1-D float array; FitInputError naming ``name`` if it is not 1-D, is empty
    or holds a NaN or an infinity."""
    try:
        a = np.asarray(values, dtype=float)
    except (TypeError, ValueError) as e:
        raise FitInputError(f"{name} must be an array of numbers{_in(unit)}: {e}") from None
    if a.ndim == 0:
        a = a.reshape(1)
    if a.ndim != 1:
        raise FitInputError(f"{name} must be a 1-D array{_in(unit)}, got shape {a.shape}")
    if a.size == 0:
        raise FitInputError(f"{name} is empty: expected at least one value{_in(unit)}")
    bad = np.flatnonzero(~np.isfinite(a))
    if bad.size:
        i = int(bad[0])
        raise FitInputError(
            f"{name}[{i}] is {a[i]!r}: every value must be a finite number{_in(unit)}"
            + (f" ({bad.size} non-finite values)" if bad.size > 1 else "")
        )
    return a


def same_length(names, arrays):
    """FitInputError unless all arrays have the same length."""
    sizes = [a.size for a in arrays]
    if len(set(sizes)) > 1:
        listed = ", ".join(f"{n} has {s}" for n, s in zip(names, sizes))
        raise FitInputError(f"{' and '.join(names)} must have the same length: {listed} values")


def finite_scalar(name, value, unit=""):
    """``value`` as a float; FitInputError naming ``name`` if it is not a finite number."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise FitInputError(f"{name} must be a number{_in(unit)}, got {value!r}") from None
    if not np.isfinite(v):
        raise FitInputError(f"{name} must be a finite number{_in(unit)}, got {v!r}")
    return v


def _in(unit):
    return f" in {unit}" if unit else ""
