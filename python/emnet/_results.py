"""Results: dicts whose keys are also attributes (result.modes, result.cost.total_seconds)."""


class Result(dict):
    """A result of an emnet analysis: a dict whose keys read as attributes too.

    Nested dicts are Results as well. Arrays are numpy arrays; their units are in the keys'
    names (frequency_hz, x_m, times_s) or in a "unit" entry beside them. A key that is also a
    dict method (values, items, keys) reads with brackets: result.outputs["values"].
    """

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        for key, value in self.items():
            if isinstance(value, dict) and not isinstance(value, Result):
                self[key] = Result(value)

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError:
            raise AttributeError(
                f"this result has no '{name}'; it has: {', '.join(self.keys())}") from None

    def __dir__(self):
        return list(self.keys()) + list(super().__dir__())

    def __repr__(self):
        return "Result(" + ", ".join(self.keys()) + ")"
