"""Scenes: read from a file, a TOML string or a dict; changed by key, without reading again."""

import json
import math
import os
import re
from typing import Any, Mapping, Optional, Union

from . import _emnet
from ._convert import Number, input_error, number, text

#: Overrides: {key: value}, a number in the key's SI unit or a text that may carry a unit.
Overrides = Mapping[str, Any]


def _plain(value: Any) -> Any:
    """numpy scalars and arrays as Python numbers and lists (TOML and the bindings take those)."""
    if type(value).__module__ == "numpy" and hasattr(value, "tolist"):
        return value.tolist()
    return value


_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")


def _toml_key(name: object, key: str) -> str:
    """A TOML key for `name`: bare when TOML allows it, otherwise a quoted basic string, so a
    name holding '#', '=', ']', quotes or a newline is one key and never a line of its own."""
    if not isinstance(name, str):
        raise input_error(f"a scene key is a string, got {type(name).__name__} {name!r}", key)
    if _BARE_KEY.fullmatch(name):
        return name
    return json.dumps(name, ensure_ascii=False)


def _toml_value(value: Any, key: str) -> str:
    value = _plain(value)
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise input_error(f"{value!r} is not a finite number", key)
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(item, key) for item in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{_toml_key(name, key)} = {_toml_value(item, f'{key}.{name}')}"
                               for name, item in value.items()) + "}"
    raise input_error(f"a {type(value).__name__} is not a scene value (numbers, strings, "
                      "booleans, lists and dicts are)", key)


def dict_to_toml(data: Mapping[str, Any]) -> str:
    """The TOML text of a scene given as a dict: {"beam": {...}, "dea": [{...}, {...}], ...}."""
    if not isinstance(data, dict):
        raise input_error("a scene dict maps table names to tables, e.g. "
                                "{'beam': {'length': '120 mm', ...}, 'dea': [{...}]}")
    lines = []
    for table, content in data.items():
        if isinstance(content, dict):
            lines.append(f"[{_toml_key(table, table)}]")
            lines += [f"{_toml_key(key, f'{table}.{key}')} = "
                      f"{_toml_value(value, f'{table}.{key}')}"
                      for key, value in content.items()]
        elif isinstance(content, (list, tuple)) and all(isinstance(e, dict) for e in content):
            for index, entry in enumerate(content):
                lines.append(f"[[{_toml_key(table, table)}]]")
                lines += [f"{_toml_key(key, f'{table}[{index}].{key}')} = "
                          f"{_toml_value(value, f'{table}[{index}].{key}')}"
                          for key, value in entry.items()]
        else:
            raise input_error(f"a table (dict) or a list of tables is "
                              f"expected, got {type(content).__name__}", table)
        lines.append("")
    return "\n".join(lines)


def _override_texts(overrides: Optional[Overrides]) -> list[str]:
    if overrides is None:
        return []
    if not isinstance(overrides, dict):
        raise input_error("overrides are a dict {key: value}, e.g. "
                                "{'beam.length': '0.2 m', 'drive.voltage': 3000}")
    texts = []
    for key, value in overrides.items():
        text = value if isinstance(value, str) else _toml_value(value, key)
        texts.append(f"{key}={text}")
    return texts


class Scene:
    """A scene: the device (beam, DEAs, drive, loads, probes) emnet analyses.

    Scene(path) reads a TOML scene file; Scene.from_text(text) and Scene.from_dict(dict) read
    one held in memory. scene.get(key) gives a numeric key's value in SI;
    scene.with_values({key: value}) a new scene with those values changed directly (no file read
    again: what a study does per variant). Scenes pickle (as their text, overrides, changed values
    and the pwl files they read, as data), so they travel to Dask workers and compute there what
    they compute here.

    Parameters
    ----------
    path : str or os.PathLike
        The scene file.
    set : dict, optional
        Overrides, as the command line's --set: {"beam.length": "0.2 m", "dea.A.lever_arm":
        "1.6 mm", "drive.voltage": 3000} (a number is in the key's SI unit; a text may carry a
        unit).

    Raises
    ------
    InputError
        An unreadable file, a bad value or key (.where: file and line, or "set"; .key).
    """

    def __init__(self, path: Union[str, "os.PathLike[str]", None] = None,
                 set: Optional[Overrides] = None, *,
                 _handle: Optional[_emnet.SceneHandle] = None) -> None:
        if _handle is not None:
            self._handle = _handle
            return
        if path is None:
            raise input_error("Scene(path): give a scene file's path (or use "
                                    "Scene.from_text / Scene.from_dict)")
        if not isinstance(path, (str, os.PathLike)):
            raise input_error(f"a scene file's path is a str or a pathlib.Path, got "
                              f"{type(path).__name__}", "path", "path")
        self._handle = _emnet.SceneHandle.read(os.fspath(path), _override_texts(set))

    @classmethod
    def from_text(cls, text: str, name: str = "<text>",
                  set: Optional[Overrides] = None) -> "Scene":
        """A scene from TOML text.

        Parameters
        ----------
        text : str
            The scene's TOML.
        name : str, default "<text>"
            What stands for the file in messages.
        set : dict, optional
            Overrides, as Scene's.

        Returns
        -------
        Scene
        """
        return cls(_handle=_emnet.SceneHandle.parse(text, name, _override_texts(set)))

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], name: str = "<dict>",
                  set: Optional[Overrides] = None) -> "Scene":
        """A scene from a dict of tables.

        Parameters
        ----------
        data : dict
            {"scene": {"name": "x"}, "beam": {...}, "dea": [{...}, {...}], ...}: a table per key, a
            list of tables for an array of tables; numbers in SI, or texts with a unit.
        name : str, default "<dict>"
            What stands for the file in messages.
        set : dict, optional
            Overrides, as Scene's.

        Returns
        -------
        Scene
        """
        return cls.from_text(dict_to_toml(data), name, set)

    @property
    def name(self) -> str:
        """The scene's name ([scene] name)."""
        return self._handle.name

    @property
    def title(self) -> str:
        """The scene's title ("" when it has none)."""
        return self._handle.title

    @property
    def file(self) -> str:
        """The file it was read from ("<text>", "<dict>" for one held in memory)."""
        return self._handle.file

    def get(self, key: str) -> float:
        """The value of a numeric key.

        Parameters
        ----------
        key : str
            A numeric key: "beam.bending_stiffness", "dea.A.lever_arm".

        Returns
        -------
        float
            Its value [the key's SI unit: Scene.unit(key)].
        """
        return self._handle.get(text(key, "key"))

    def unit(self, key: str) -> str:
        """The SI unit of a numeric key.

        Parameters
        ----------
        key : str
            A numeric key.

        Returns
        -------
        str
            "N*m^2", "m"; "" when dimensionless.
        """
        return self._handle.unit(text(key, "key"))

    def keys(self) -> list[str]:
        """Every numeric key the scene uses.

        Returns
        -------
        list of str
            Canonical keys ("dea[A].lever_arm").
        """
        return self._handle.numeric_keys()

    def with_values(self, values: Mapping[str, Number]) -> "Scene":
        """A copy with numeric keys set to new values, without reading the scene again.

        Parameters
        ----------
        values : dict or pandas.Series
            {key: value} [the key's SI unit]; any number (numpy's and pandas' too).

        Returns
        -------
        Scene
            The copy; the scene itself is unchanged.

        Raises
        ------
        InputError
            A value out of its key's range, as the reader checks it, or not a number (.key names
            the key; .where is "values" for a value that is not a number).
        """
        if not hasattr(values, "items"):
            raise input_error("values are a dict {key: value in SI} (or a pandas Series by key), "
                              f"got {type(values).__name__}", "values", "values")
        handle = self._handle.copy()
        for key, value in values.items():
            handle.set(text(key, "values"), number(value, key, "values"))
        return Scene(_handle=handle)

    def with_overrides(self, overrides: Overrides) -> "Scene":
        """A copy read again with more overrides.

        Parameters
        ----------
        overrides : dict
            {key: value}, as Scene's `set`: a number in SI, or a text with a unit.

        Returns
        -------
        Scene
        """
        handle = self._handle
        fresh = _emnet.SceneHandle.parse(handle.text, handle.file,
                                         list(handle.overrides) + _override_texts(overrides),
                                         handle.files)
        for key, value in handle.sets:
            fresh.set(key, value)
        return Scene(_handle=fresh)

    def __getstate__(self) -> dict[str, Any]:
        # The pwl files it read travel as data: a worker in another directory, or after the file
        # changed, rebuilds the very scene that was read here.
        h = self._handle
        return {"text": h.text, "file": h.file, "overrides": list(h.overrides),
                "sets": list(h.sets), "files": dict(h.files)}

    def __setstate__(self, state: Mapping[str, Any]) -> None:
        handle = _emnet.SceneHandle.parse(state["text"], state["file"], state["overrides"],
                                          state.get("files", {}))
        for key, value in state["sets"]:
            handle.set(key, value)
        self._handle = handle

    def __repr__(self) -> str:
        return f"Scene({self.name!r} from {self.file!r})"


#: A scene, or a scene file's path.
SceneLike = Union[Scene, str, "os.PathLike[str]"]


def as_scene(scene: SceneLike) -> Scene:
    """A Scene from a Scene or a scene file's path."""
    if isinstance(scene, Scene):
        return scene
    if isinstance(scene, (str, os.PathLike)):
        return Scene(scene)
    raise input_error(f"expected a Scene or a scene file's path, got {type(scene).__name__}")
