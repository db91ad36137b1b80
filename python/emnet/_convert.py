"""Python values as the bindings take them: numbers and sequences of numbers (Python's, numpy's,
pandas') as floats and ints, texts as str, flags as bool; anything else raises an emnet.InputError
naming the keyword argument (or scene key) it was given for, never pybind11's TypeError."""

import math
from collections.abc import Iterable
from numbers import Integral, Real
from typing import Any, Optional, Sequence, Union

import numpy
from numpy.typing import NDArray

from . import _emnet

#: A number: a Python int or float, a numpy scalar (pandas' scalars are numpy's). A one-element
#: array, Series, list or tuple is taken as its element.
Number = Union[float, numpy.floating[Any], numpy.integer[Any]]
#: An integer: a Python int or a numpy integer (a float with an integral value is taken too).
Integer = Union[int, numpy.integer[Any]]
#: Numbers: one number, or any sequence of them: a list, tuple, range, numpy array, pandas Series.
Numbers = Union[Number, Sequence[Number], NDArray[Any]]
#: Texts: one text or a sequence of texts.
Texts = Union[str, Sequence[str]]
#: A flag: True or False (numpy's too).
Flag = Union[bool, numpy.bool_]

_INT_MIN, _INT_MAX = -2**31, 2**31 - 1  # the bindings' C int


def input_error(message: str, key: str = "", where: str = "python") -> _emnet.InputError:
    """An emnet.InputError raised by the package itself, with .where and .key as the library's,
    worded as the library words its own: "WHERE: key 'KEY': message" (no WHERE for "python")."""
    prefix = "" if where == "python" else f"{where}: "
    error = _emnet.InputError(prefix + (f"key '{key}': " if key else "") + message)
    error.where, error.key = where, key
    return error


def _shown(value: object) -> str:
    """`value` in a message: its type and a short repr."""
    if isinstance(value, (str, bytes)):
        return f"the text {value!r}"[:60]
    text = repr(value)
    return f"{type(value).__name__} {text if len(text) <= 40 else text[:39] + '…'}"


def _real(value: object, key: str, where: str) -> Union[int, float]:
    """One number as Python's int or float: a bool, a text, a complex number, a NaN or an
    infinity, any other object, raise an InputError."""
    if hasattr(value, "tolist"):  # numpy scalars (and 0-d arrays) as Python's
        value = value.tolist()
    if isinstance(value, bool) or not isinstance(value, Real):
        raise input_error(f"a number is wanted, got {_shown(value)}", key, where)
    if isinstance(value, Integral):
        return int(value)
    number = float(value)
    if not math.isfinite(number):
        raise input_error(f"a finite number is wanted, got {number!r}", key, where)
    return number


def _one(value: object, key: str, where: str) -> object:
    """The element of a one-element array, Series, list or tuple; `value` itself otherwise."""
    if hasattr(value, "tolist"):
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        if len(value) != 1:
            raise input_error(f"one number is wanted, got a sequence of {len(value)}", key, where)
        value = value[0]
    return value


def number(value: object, key: str, where: Optional[str] = None) -> float:
    """`value` (see Number) as a float; an InputError naming `key` (at `where`, default the key:
    a keyword argument's name) for anything else."""
    where = where or key
    return float(_real(_one(value, key, where), key, where))


def integer(value: object, key: str, where: Optional[str] = None, low: int = _INT_MIN,
            high: int = _INT_MAX) -> int:
    """`value` (see Integer; a float only with an integral value) as an int within [low, high]
    (default the bindings' C int); an InputError naming `key` for anything else."""
    where = where or key
    whole = _real(_one(value, key, where), key, where)
    if isinstance(whole, float):
        if not whole.is_integer():
            raise input_error(f"a whole number is wanted, got {whole!r}", key, where)
        whole = int(whole)
    if not low <= whole <= high:
        raise input_error(f"{whole} is out of range: from {low} to {high}", key, where)
    return whole


def maybe_number(value: object, key: str) -> Optional[float]:
    """None, or `value` as number() takes it."""
    return None if value is None else number(value, key)


def maybe_integer(value: object, key: str) -> Optional[int]:
    """None, or `value` as integer() takes it."""
    return None if value is None else integer(value, key)


def numbers(values: object, key: str, where: Optional[str] = None) -> list[float]:
    """`values` (None, a number, or any sequence of numbers: list, tuple, range, numpy array,
    pandas Series) as a list of floats; an InputError naming `key` for anything else."""
    where = where or key
    if values is None:
        return []
    if isinstance(values, (str, bytes)):
        raise input_error(f"numbers are wanted, got {_shown(values)}", key, where)
    if hasattr(values, "tolist"):  # numpy arrays and scalars, pandas Series
        values = values.tolist()
    items = list(values) if isinstance(values, Iterable) else [values]
    return [float(_real(item, key, where)) for item in items]


def flag(value: object, key: str) -> bool:
    """`value` (True or False, Python's or numpy's) as a bool; an InputError naming `key` for
    anything else."""
    if hasattr(value, "tolist"):
        value = value.tolist()
    if not isinstance(value, bool):
        raise input_error(f"True or False is wanted, got {_shown(value)}", key, key)
    return value


def maybe_flag(value: object, key: str) -> Optional[bool]:
    """None, or `value` as flag() takes it."""
    return None if value is None else flag(value, key)


def text(value: object, key: str, where: Optional[str] = None) -> str:
    """`value` (a str) itself; an InputError naming `key` for anything else."""
    if not isinstance(value, str):
        raise input_error(f"a text is wanted, got {_shown(value)}", key, where or key)
    return value


def texts(values: object, key: str) -> list[str]:
    """`values` (None, a text, or a sequence of texts) as a list of str; an InputError naming
    `key` for anything else."""
    if values is None:
        return []
    if isinstance(values, str):
        return [values]
    if not isinstance(values, Iterable):
        raise input_error(f"texts are wanted, got {_shown(values)}", key, key)
    return [text(item, key) for item in values]
