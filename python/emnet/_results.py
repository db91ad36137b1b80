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

    Its keys are those of the command's --json. Nested dicts are Results as well. Arrays are
    numpy arrays; their units are in the keys' names (frequency_hz, x_m, times_s) or in a "unit"
    entry beside them. A table of records is a Result of columns (result.outputs["name"],
    result.outputs["right"][k]); row(name) picks one record. A key that is also a dict method
    (values, items, keys) reads with brackets: result.outputs["values"].
    """

    _kind: Optional[str] = None  # the function that made it ("ac"), None for a nested Result

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        for key, value in self.items():
            if isinstance(value, dict) and not isinstance(value, Result):
                self[key] = Result(value)

    def row(self, name: Any, key: str = "name") -> "Result":
        """One record of a table by its name: result.outputs.row("dx4").right.

        A table (an array of records in the command's --json, such as outputs, probes, modes)
        is a Result of columns, one per key; row gives the record whose `key` column equals
        `name`, each column's entry for it.
        """
        names = list(self[key])
        if name not in names:
            raise KeyError(f"no {key} '{name}'; there are: {', '.join(map(str, names))}")
        index = names.index(name)
        return Result({column: values[index] for column, values in self.items()})

    def to_frame(self, table: Optional[str] = None) -> "pandas.DataFrame":
        """The result's table as a pandas DataFrame."""
        from ._frames import frame
        return frame(self, table)

    def to_xarray(self) -> "xarray.Dataset":
        """The result's arrays over outputs as an xarray Dataset."""
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
