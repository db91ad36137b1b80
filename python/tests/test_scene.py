"""Scenes from files, text and dicts; changes by key; pickling (what Dask workers receive)."""

import pickle

import emnet
from conftest import CANTILEVER, ROOT


def test_text_and_dict_give_the_file_scene(cantilever):
    text = open(CANTILEVER).read()
    from_text = emnet.Scene.from_text(text)
    data = {
        "scene": {"name": "cantilever"},
        "beam": {"length": 0.5, "segments": 20, "bending_stiffness": 2.0,
                 "mass_per_length": 0.3, "left": "clamped", "right": "free"},
        "load": [{"kind": "force", "at": 0.5, "value": 1.0}],
        "probe": [{"name": "tip", "quantity": "deflection", "at": 0.5},
                  {"name": "mid", "quantity": "deflection", "at": 0.25}],
    }
    from_dict = emnet.Scene.from_dict(data)
    reference = emnet.static(cantilever).probes["value"]
    assert list(emnet.static(from_text).probes["value"]) == list(reference)
    assert list(emnet.static(from_dict).probes["value"]) == list(reference)


def test_with_values_changes_only_that_key(cantilever):
    stiffer = cantilever.with_values({"beam.bending_stiffness": 4.0})
    assert stiffer.get("beam.bending_stiffness") == 4.0
    assert cantilever.get("beam.bending_stiffness") == 2.0
    # Static tip deflection F*L^3/(3*EI): half at twice the stiffness (exact nodal statics).
    tip = dict(zip(emnet.static(stiffer).probes["name"], emnet.static(stiffer).probes["value"]))
    assert abs(tip["tip"] - 0.5**3 / (3 * 4.0)) < 1e-13


def test_overrides_with_units(cantilever):
    shorter = cantilever.with_overrides({"beam.length": "400 mm", "load.0.at": "400 mm",
                                         "probe.tip.at": "0.4 m", "probe.mid.at": 0.2})
    assert shorter.get("beam.length") == 0.4


def test_pickle_round_trip(cantilever):
    changed = cantilever.with_values({"beam.mass_per_length": 0.4})
    again = pickle.loads(pickle.dumps(changed))
    assert again.get("beam.mass_per_length") == 0.4
    assert list(emnet.modes(again).modes["frequency_hz"]) == \
        list(emnet.modes(changed).modes["frequency_hz"])


def test_help_is_useful():
    assert "[Hz]" in emnet.modes.__doc__
    assert "InputError" in emnet.__doc__


def test_pickled_scene_carries_its_pwl_file(tmp_path, monkeypatch):
    """A pickled scene carries the pwl CSV it read as data: unpickled in another directory, with
    the file changed and then gone, it computes what the original computes (bit for bit)."""
    text = open(str(ROOT / "netlists" / "rc-dea.toml")).read()
    square = text[text.index('waveform = "square"'):text.index('ac = "100 V"')]
    text = text.replace(square, 'waveform = "pwl"\nfile = "ramp.csv"\n')
    (tmp_path / "scene").mkdir()
    (tmp_path / "scene" / "device.toml").write_text(text)
    (tmp_path / "scene" / "ramp.csv").write_text("0,0\n0.0123456789,1234.56789\n0.1,3000\n")
    scene = emnet.Scene(tmp_path / "scene" / "device.toml")
    reference = emnet.tran(scene, periods=0.5, points_per_period=20)
    pickled = pickle.dumps(scene)
    (tmp_path / "scene" / "ramp.csv").write_text("0,0\n0.05,10\n")
    (tmp_path / "elsewhere").mkdir()
    monkeypatch.chdir(tmp_path / "elsewhere")
    again = pickle.loads(pickled)
    (tmp_path / "scene" / "ramp.csv").unlink()
    result = emnet.tran(again, periods=0.5, points_per_period=20)
    assert len(reference.outputs["values"]) > 0
    assert list(result.times_s) == list(reference.times_s)
    for mine, theirs in zip(result.outputs["values"], reference.outputs["values"]):
        assert list(mine) == list(theirs)
