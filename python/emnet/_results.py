"""Results: dicts whose keys are also attributes (result.modes, result.cost.total_seconds).

A result is the JSON the command of the same name prints with --json (its keys, in its order),
converted once: objects to Results, arrays of numbers to numpy arrays, arrays of records
(outputs, probes, modes, ...) to a Result of columns, one per key.
"""

from typing import TYPE_CHECKING, Any, Optional

from ._tables import counted, lines, rows

if TYPE_CHECKING:
    import pandas
    import xarray


class Result(dict[str, Any]):
    """A result of an emnet analysis: a dict whose keys read as attributes too.

    Its keys are those of the command's --json. Nested dicts are Results as well. Arrays are numpy
    arrays; their units are in the keys' names (frequency_hz, x_m, times_s) or in a "unit" entry
    beside them. A table of records is a Result of columns (result.outputs["name"],
    result.outputs["right"][k]); row(name) picks one record. A key that is also a dict method
    (values, items, keys) reads with brackets: result.outputs["values"].

    repr(result) shows a line per key: numbers with their units, arrays with their shape and
    first values, tables with their rows and columns. to_frame() gives a result's table as a
    pandas DataFrame, to_xarray() the arrays over outputs of ac, sweep_switching and tran as an
    xarray Dataset.
    """

    _kind: Optional[str] = None  # the function that made it ("ac"), None for a nested Result

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        for key, value in self.items():
            if isinstance(value, dict) and not isinstance(value, Result):
                self[key] = Result(value)

    def row(self, name: Any, key: str = "name") -> "Result":
        """One record of a table by its name: result.outputs.row("dx4").right.

        A table (an array of records in the command's --json, such as outputs, probes, modes) is a
        Result of columns, one per key; row gives the record whose `key` column equals `name`.

        Parameters
        ----------
        name
            The record's name (its entry in the `key` column).
        key : str, default "name"
            The column that names the records ("probe", "key", "label" in some tables).

        Returns
        -------
        Result
            Each column's entry for that record.

        Raises
        ------
        KeyError
            No record has that name (the message lists the names).
        """
        names = list(self[key])
        if name not in names:
            raise KeyError(f"no {key} '{name}'; there are: {', '.join(map(str, names))}")
        index = names.index(name)
        return Result({column: values[index] for column, values in self.items()})

    def to_frame(self, table: Optional[str] = None) -> "pandas.DataFrame":
        """The result's table as a pandas DataFrame.

        Parameters
        ----------
        table : str, optional
            A table inside the result by its key ("nodes", "cases", "unknowns"): its columns.
            Default: the table of the analysis that made the result:

            - static: its probes (name, description, unit, value);
            - modes: a row per mode (index mode, from 1): frequency_hz, damping_ratio, ...; pole as
              pole_real and pole_imag [1/s];
            - ac: a row per frequency (index frequency_hz): <probe>_magnitude and <probe>_phase_deg;
            - tran: a row per output time (index times_s): a column per output;
            - sweep_switching: a row per frequency (index frequency_hz): <output>_min and
              <output>_max, the periodic minimum (left) and maximum (right);
            - sensitivity: a row per parameter and mode: parameter, unit, value, mode, frequency_hz
              and the derivatives;
            - mismatch: its cases; crosscheck: its rows;
            - a table itself (result.nodes.to_frame()): its columns.

            Columns of per-record arrays (mode shapes, per-mode probes) stay in the result.

        Returns
        -------
        pandas.DataFrame
            df.attrs["units"]: {column: unit} ("" where none, or where the rows' units differ: the
            unit column holds them).

        Raises
        ------
        TypeError
            The result has no table of its own (identify; netlist, whose tables read by name): the
            message says which results have one, and names the tables inside this one.
        ValueError
            `table` is not a table of the result.
        """
        from ._frames import frame
        return frame(self, table)

    def to_xarray(self) -> "xarray.Dataset":
        """The arrays over outputs of an ac, sweep_switching or tran result as an xarray Dataset.

        Returns
        -------
        xarray.Dataset
            ac: magnitude, phase_deg [deg] and phasor (complex) over dims (output, frequency);
            sweep_switching: minimum (left) and maximum (right) over (output, frequency); tran:
            value over (output, time). Coordinates: output (the names: ds.sel(output="dx4")), unit
            and description per output, frequency_hz [Hz] or times_s [s] along frequency or time
            (indexed: ds.sel(frequency_hz=5.0)). A variable's attrs["units"] is the outputs' unit
            when they share one; the result's scalars are the Dataset's attrs.

        Raises
        ------
        TypeError
            The result is not of ac, sweep_switching or tran.
        """
        from ._frames import dataset
        return dataset(self)

    def __getattr__(self, name: str) -> Any:
        try:
            return self[name]
        except KeyError:
            raise AttributeError(
                f"this result has no '{name}'; it has: {', '.join(self.keys())}") from None

    def __dir__(self) -> list[str]:
        return list(self.keys()) + list(super().__dir__())

    def __repr__(self) -> str:
        count = rows(self)
        title = (f"emnet.{self._kind} result:" if self._kind
                 else f"Result, a table of {counted(count, 'row')}:" if count else "Result:")
        return "\n".join(lines(self, title))
