"""Results as pandas DataFrames and xarray Datasets: the table each analysis's result has, and its
arrays over outputs and frequency or time. pandas and xarray are imported when first asked for."""

from typing import TYPE_CHECKING, Any, Callable, Mapping, Optional, Sequence

import numpy

from ._tables import rows, unit_of

if TYPE_CHECKING:
    import pandas
    import xarray

    from ._results import Result

# The analyses whose result has a table of its own, and which (for messages).
_FRAME_TABLES = ("static, modes, ac, tran, sweep_switching, sensitivity, mismatch and "
                 "crosscheck")


def _is_scalar(value: Any) -> bool:
    return value is None or isinstance(value, (str, bool, int, float, complex, numpy.generic))


def columns_frame(table: Mapping[str, Any], index: Optional[Sequence[Any]] = None
                  ) -> "pandas.DataFrame":
    """A DataFrame of a table's columns, units by their names in df.attrs["units"]. A column of
    [re, im] pairs (pole) becomes <name>_real and <name>_imag; columns of per-record arrays or
    records (mode shapes, per-mode probes) are left out."""
    import pandas

    data: dict[str, Any] = {}
    units: dict[str, str] = {}
    for name, column in table.items():
        if isinstance(column, numpy.ndarray) and column.ndim == 2 and column.shape[1] == 2 \
                and "pole" in name:
            for part, values in (("real", column[:, 0]), ("imag", column[:, 1])):
                data[f"{name}_{part}"], units[f"{name}_{part}"] = values, unit_of(name)
        elif (isinstance(column, numpy.ndarray) and column.ndim == 1) or \
                (isinstance(column, list) and all(map(_is_scalar, column))):
            data[name], units[name] = column, unit_of(name)
    frame = pandas.DataFrame(data, index=index)
    frame.attrs["units"] = units
    return frame


def _indexed(data: dict[str, Any], units: dict[str, str], index: Any, name: str
             ) -> "pandas.DataFrame":
    """A DataFrame of `data` over `index` (named `name`), units in df.attrs["units"]."""
    import pandas

    frame = pandas.DataFrame(data, index=pandas.Index(index, name=name))
    frame.attrs["units"] = {name: unit_of(name), **units}
    return frame


def _over(table: Mapping[str, Any], parts: Sequence[tuple[str, str, Optional[str]]], index: Any,
          name: str) -> "pandas.DataFrame":
    """A DataFrame over `index` (named `name`) of columns <output>_<suffix> (<output> for no
    suffix), each a row of table[key] [output, index] in `unit` (None: the output's), for each
    (suffix, key, unit) of `parts`."""
    data, units = {}, {}
    for k, (output, output_unit) in enumerate(zip(table["name"], table["unit"])):
        for suffix, key, unit in parts:
            column = f"{output}_{suffix}" if suffix else output
            data[column], units[column] = table[key][k], unit or output_unit
    return _indexed(data, units, index, name)


def _ac_frame(result: "Result") -> "pandas.DataFrame":
    parts = [("magnitude", "magnitude", None), ("phase_deg", "phase_deg", "deg")]
    return _over(result.probes, parts, result.frequencies_hz, "frequency_hz")


def _tran_frame(result: "Result") -> "pandas.DataFrame":
    return _over(result.outputs, [("", "values", None)], result.times_s, "times_s")


def _sweep_frame(result: "Result") -> "pandas.DataFrame":
    parts = [("min", "left", None), ("max", "right", None)]
    return _over(result.outputs, parts, result.frequencies_hz, "frequency_hz")


def _sensitivity_unit(column: str) -> str:
    if "pole_derivative" in column:
        return "1/s per unit of the parameter"
    if column.endswith("frequency_derivative"):
        return "Hz per unit of the parameter"
    return unit_of(column)


def _sensitivity_frame(result: "Result") -> "pandas.DataFrame":
    import pandas

    parameters = result.parameters
    parts = []
    for k, key in enumerate(parameters["key"]):
        part = columns_frame(parameters["modes"][k])
        count = len(part)
        part.insert(0, "frequency_hz", result.modes["frequency_hz"][:count])
        part.insert(0, "mode", numpy.arange(1, count + 1))
        part.insert(0, "value", parameters["value"][k])
        part.insert(0, "unit", parameters["unit"][k])
        part.insert(0, "parameter", key)
        parts.append(part)
    frame = pandas.concat(parts, ignore_index=True)
    frame.attrs["units"] = {column: _sensitivity_unit(column) for column in frame.columns}
    return frame


def _modes_frame(result: "Result") -> "pandas.DataFrame":
    import pandas

    count = rows(result.modes) or 0
    return columns_frame(result.modes, pandas.RangeIndex(1, count + 1, name="mode"))


_FRAMES: dict[str, Callable[["Result"], "pandas.DataFrame"]] = {
    "static": lambda result: columns_frame(result.probes),
    "modes": _modes_frame,
    "ac": _ac_frame,
    "tran": _tran_frame,
    "sweep_switching": _sweep_frame,
    "sensitivity": _sensitivity_frame,
    "mismatch": lambda result: columns_frame(result.cases),
    "crosscheck": lambda result: columns_frame(result.rows),
}


def _tables_of(result: Mapping[str, Any]) -> list[str]:
    return [key for key, value in result.items() if isinstance(value, dict) and rows(value)]


def frame(result: "Result", table: Optional[str] = None) -> "pandas.DataFrame":
    """result.to_frame(table): see Result.to_frame."""
    tables = _tables_of(result)
    if table is not None:
        if table not in tables:
            raise ValueError(f"this result has no table '{table}'; its tables are: "
                             f"{', '.join(tables) or 'none'}")
        return columns_frame(result[table])
    if result._kind in _FRAMES:
        return _FRAMES[result._kind](result)
    if rows(result):
        return columns_frame(result)
    what = f"an emnet.{result._kind} result" if result._kind else "this result"
    named = (f"name a table inside it: {' or '.join(f'to_frame({t!r})' for t in tables)}"
             if tables else "it holds no table to name either")
    raise TypeError(f"to_frame(): {what} has no table of its own (the results of {_FRAME_TABLES} "
                    f"have one); {named}")


def _scalars(result: Mapping[str, Any]) -> dict[str, Any]:
    """A result's top-level numbers and texts (a Dataset's attrs)."""
    return {key: value for key, value in result.items()
            if isinstance(value, (str, int, float)) and not isinstance(value, bool)}


def _over_outputs(result: "Result", table: Mapping[str, Any],
                  variables: Mapping[str, tuple[Any, Optional[str], str]], dim: str, axis: str,
                  values: Any) -> "xarray.Dataset":
    """A Dataset of `variables` ({name: (array [output, dim], unit or None for the outputs',
    description)}) over the table's outputs and `dim`, whose coordinate `axis` holds `values`
    (an index: ds.sel(frequency_hz=5.0))."""
    import xarray

    units = list(table["unit"])
    common = units[0] if len(set(units)) == 1 else None
    data = {}
    for name, (array, unit, description) in variables.items():
        attrs = {"long_name": description}
        if unit or common:
            attrs["units"] = unit or common
        data[name] = (("output", dim), array, attrs)
    coords = {"output": list(table["name"]), "unit": ("output", units),
              "description": ("output", list(table["description"])),
              axis: (dim, values, {"units": unit_of(axis)})}
    attrs = {"analysis": f"emnet.{result._kind}", **_scalars(result)}
    return xarray.Dataset(data, coords=coords, attrs=attrs).set_xindex(axis)


def _ac_dataset(result: "Result") -> "xarray.Dataset":
    probes = result.probes
    variables = {"magnitude": (probes["magnitude"], None, "magnitude per unit input"),
                 "phase_deg": (probes["phase_deg"], "deg", "phase")}
    if "phasors" in result:
        variables["phasor"] = (result.phasors, None, "complex response per unit input")
    return _over_outputs(result, probes, variables, "frequency", "frequency_hz",
                         result.frequencies_hz)


def _sweep_dataset(result: "Result") -> "xarray.Dataset":
    outputs = result.outputs
    variables = {"minimum": (outputs["left"], None, "periodic minimum (left)"),
                 "maximum": (outputs["right"], None, "periodic maximum (right)")}
    return _over_outputs(result, outputs, variables, "frequency", "frequency_hz",
                         result.frequencies_hz)


def _tran_dataset(result: "Result") -> "xarray.Dataset":
    outputs = result.outputs
    variables = {"value": (outputs["values"], None, "output value")}
    return _over_outputs(result, outputs, variables, "time", "times_s", result.times_s)


_DATASETS: dict[str, Callable[["Result"], "xarray.Dataset"]] = {
    "ac": _ac_dataset, "sweep_switching": _sweep_dataset, "tran": _tran_dataset}


def dataset(result: "Result") -> "xarray.Dataset":
    """result.to_xarray(): see Result.to_xarray."""
    if result._kind not in _DATASETS:
        what = f"an emnet.{result._kind} result" if result._kind else "this result"
        raise TypeError(f"to_xarray(): {what} has no arrays over outputs; the results of ac, "
                        "sweep_switching and tran have (their tables read with to_frame())")
    return _DATASETS[result._kind](result)
