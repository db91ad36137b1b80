"""Shared fixtures: the repository's scenes, the command line program to compare against."""

import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(os.environ.get("EMNET_ROOT", pathlib.Path(__file__).resolve().parents[2]))
PROGRAM = os.environ.get("EMNET_PROGRAM", str(ROOT / "build" / "emnet"))
FISHFIN = str(ROOT / "netlists" / "fishfin.toml")
CANTILEVER = str(ROOT / "netlists" / "cantilever.toml")


def cli_json(*arguments):
    """The command line's --json output of `emnet ARGUMENTS --json` (exit 0 or 5 accepted)."""
    run = subprocess.run([PROGRAM, *arguments, "--json", "--quiet"], capture_output=True,
                         text=True, check=False)
    assert run.returncode in (0, 5), run.stderr
    return json.loads(run.stdout)


@pytest.fixture(scope="session")
def fishfin():
    import emnet
    return emnet.Scene(FISHFIN)


@pytest.fixture(scope="session")
def cantilever():
    import emnet
    return emnet.Scene(CANTILEVER)
