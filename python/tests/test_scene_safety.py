"""Scene.from_dict with hostile names: a key or table name is one TOML key, never a line."""

import pytest

import emnet


# The cantilever of netlists/cantilever.toml as a dict. The hostile keys spell `segments`, which
# the dict leaves out, so a smuggled `segments = 3` line is read (not refused as a duplicate).
def _cantilever(**beam_extra):
    beam = {"length": 0.5, "bending_stiffness": 2.0,
            "mass_per_length": 0.3, "left": "clamped", "right": "free"}
    beam.update(beam_extra)
    return {"scene": {"name": "cantilever"}, "beam": beam,
            "load": [{"kind": "force", "at": 0.5, "value": 1.0}],
            "probe": [{"name": "tip", "quantity": "deflection", "at": 0.5}]}


@pytest.mark.parametrize("name", ["#\nsegments", "x = 1\nsegments", "x]\nsegments",
                                  "a\"b", "seg ments", "segments\r"])
def test_a_hostile_key_is_refused_not_smuggled(name):
    # Before the fix "#\nsegments" = 3 wrote a comment line and then `segments = 3`, silently
    # setting beam.segments; now it is one quoted key the reader does not know.
    with pytest.raises(emnet.InputError):
        emnet.Scene.from_dict(_cantilever(**{name: 3}))


def test_a_hostile_key_does_not_set_segments():
    # The exact bug: the smuggled line set beam.segments (required, absent from the dict) to 3.
    try:
        scene = emnet.Scene.from_dict(_cantilever(**{"#\nsegments": 3}))
    except emnet.InputError:
        return
    assert scene.get("beam.segments") != 3


@pytest.mark.parametrize("table", ["beam]\n[beam", "beam\n", "#"])
def test_a_hostile_table_name_is_refused(table):
    data = _cantilever(segments=20)
    data[table] = {"segments": 3}
    with pytest.raises(emnet.InputError):
        emnet.Scene.from_dict(data)


def test_a_non_string_key_is_an_input_error():
    with pytest.raises(emnet.InputError):
        emnet.Scene.from_dict(_cantilever(segments=20) | {"beam": {1: 2}})


def test_ordinary_names_still_read():
    assert emnet.Scene.from_dict(_cantilever(segments=20)).get("beam.length") == 0.5
