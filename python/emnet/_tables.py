"""What a result's keys and tables mean: units by a key's name, which nested Results are tables
(arrays of records, a column per key), and the lines repr(result) shows."""

from typing import Any, Mapping, Optional

import numpy

# A key's unit by how its name ends (the report layer's convention: x_m, frequency_hz, times_s).
_SUFFIX_UNITS = (("_hz", "Hz"), ("_seconds", "s"), ("_rad", "rad"), ("_deg", "deg"),
                 ("_m", "m"), ("_s", "s"))
# Keys whose name does not end in their unit.
_NAME_UNITS = {"pole": "1/s", "pole_error_bound": "1/s"}
# Keys whose unit is the record's "unit" entry (outputs.row("dx4").right, identify's value).
_VALUE_KEYS = ("value", "values", "left", "right", "magnitude")

LINES = 40   # repr's most lines
WIDTH = 100  # repr's longest line
SHOWN = 4    # an array's first values repr shows


def counted(count: int, noun: str) -> str:
    """"1 row", "3 rows"."""
    return f"{count} {noun}{'' if count == 1 else 's'}"


def unit_of(key: str) -> str:
    """The unit a key's name gives ("frequency_hz" -> "Hz"), "" for none."""
    if key in _NAME_UNITS:
        return _NAME_UNITS[key]
    for suffix, unit in _SUFFIX_UNITS:
        if key.endswith(suffix):
            return unit
    return ""


def rows(table: Mapping[str, Any]) -> Optional[int]:
    """The number of records of a table (a mapping of columns: arrays or lists of one length),
    None when `table` is not one."""
    lengths = {len(column) if isinstance(column, list) or
               (isinstance(column, numpy.ndarray) and column.ndim) else -1
               for column in table.values()}
    if len(lengths) != 1 or -1 in lengths or 0 in lengths:
        return None
    return lengths.pop()


def _scalar(value: Any) -> str:
    if value is None or isinstance(value, (bool, numpy.bool_)):
        return str(value if value is None else bool(value))
    if isinstance(value, (int, numpy.integer)):
        return str(value)
    if isinstance(value, (float, numpy.floating, complex, numpy.complexfloating)):
        return f"{value:.6g}"
    if isinstance(value, str):
        return repr(value if len(value) <= 60 else value[:59] + "…")
    text = repr(value)
    return text if len(text) <= 60 else text[:59] + "…"


def _array(array: numpy.ndarray) -> str:
    flat = array.ravel()
    shown = [_scalar(v) for v in flat[:SHOWN]]
    if flat.size > SHOWN:
        shown += (["…"] if flat.size > SHOWN + 1 else []) + [_scalar(flat[-1])]
    return f"array({'×'.join(map(str, array.shape))}) [{', '.join(shown)}]"


def _list(items: list[Any]) -> str:
    if items and all(isinstance(item, dict) for item in items):
        return f"{len(items)} records of {', '.join(items[0])}"
    shown = ", ".join(_scalar(item) for item in items[:SHOWN])
    return f"[{shown}{', …' if len(items) > SHOWN else ''}]" + \
        (f" ({len(items)})" if len(items) > SHOWN else "")


def _table(table: Mapping[str, Any], count: int) -> str:
    columns = ", ".join(f"{name}({'×'.join(map(str, column.shape))})"
                        if isinstance(column, numpy.ndarray) and column.ndim > 1 else name
                        for name, column in table.items())
    named = ""
    if "unit" in table and "name" in table:
        pairs = [f"{name} [{unit}]" for name, unit in zip(table["name"], table["unit"])]
        named = " (" + ", ".join(pairs[:SHOWN]) + (", …" if count > SHOWN else "") + ")"
    return f"table of {counted(count, 'row')}{named}: {columns}"


def _inline(record: Mapping[str, Any]) -> str:
    return "{" + ", ".join(f"{key}: {describe(key, value, record)}"
                           for key, value in record.items()) + "}"


def describe(key: str, value: Any, owner: Mapping[str, Any]) -> str:
    """One value of `owner` (a result or a record) in a short text, with its unit."""
    if isinstance(value, dict):
        count = rows(value)
        return _table(value, count) if count else _inline(value)
    if isinstance(value, numpy.ndarray):
        text = _array(value)
    elif isinstance(value, list):
        text = _list(value)
    else:
        text = _scalar(value)
    unit = unit_of(key)
    if not unit and key in _VALUE_KEYS and isinstance(owner.get("unit"), str):
        unit = owner["unit"]
    return f"{text} {unit}" if unit and not isinstance(value, (str, list)) else text


def lines(result: Mapping[str, Any], title: str) -> list[str]:
    """repr's lines: the title, then a line per key (at most LINES, each at most WIDTH)."""
    width = min(24, max((len(key) for key in result), default=0))
    out = [title]
    for key, value in result.items():
        line = f"  {key:<{width}}  {describe(key, value, result)}"
        out.append(line if len(line) <= WIDTH else line[:WIDTH - 1] + "…")
    if len(out) > LINES:
        out[LINES - 1:] = [f"  … and {len(out) - LINES + 1} more keys"]
    return out
