"""The package is typed (PEP 561: py.typed, its functions' hints, a stub _emnet.pyi for the
compiled module): mypy finds no error in the package, as it is imported here, nor in the
examples, which use it as a user's script does; and the stub is the compiled module's."""

import ast
import importlib.util
import os
import pathlib
import re
import subprocess
import sys

import pytest

import emnet
from emnet import _emnet
from conftest import ROOT

PYTHON = pathlib.Path(__file__).resolve().parents[1]  # python/: mypy.ini, the allowlist
PACKAGE = pathlib.Path(emnet.__file__).resolve().parent


def mypy(module, *arguments, cwd):
    """`python -m MODULE ARGUMENTS` (mypy or mypy.stubtest) with python/mypy.ini, run in `cwd`
    (where mypy keeps its cache), emnet imported from where this test imported it (mypy reads
    the Python's sys.path): (exit status, what mypy printed)."""
    if importlib.util.find_spec("mypy") is None:
        pytest.skip("mypy is not installed (Debian: python3-mypy)")
    config = "--mypy-config-file" if module == "mypy.stubtest" else "--config-file"
    path = os.pathsep.join(filter(None, [str(PACKAGE.parent), os.environ.get("PYTHONPATH")]))
    run = subprocess.run([sys.executable, "-m", module, *arguments, config,
                          str(PYTHON / "mypy.ini")], capture_output=True, text=True, check=False,
                         cwd=cwd, env=dict(os.environ, PYTHONPATH=path))
    return run.returncode, run.stdout + run.stderr


def test_the_package_is_marked_typed():
    assert (PACKAGE / "py.typed").is_file()
    assert (PACKAGE / "_emnet.pyi").is_file()


def test_the_package_type_checks(tmp_path):
    status, output = mypy("mypy", str(PACKAGE), cwd=tmp_path)
    assert status == 0, output
    assert "Success: no issues found" in output


def test_the_examples_type_check(tmp_path):
    examples = sorted(str(path) for path in (ROOT / "examples").glob("*.py"))
    assert len(examples) >= 2
    status, output = mypy("mypy", *examples, cwd=tmp_path)
    assert status == 0, output
    assert f"Success: no issues found in {len(examples)} source files" in output


def test_the_stub_has_what_the_compiled_module_has(tmp_path):
    # Every name of the compiled module in the stub and no other (pybind11's own differences
    # are in python/stubtest-allowlist.txt).
    status, output = mypy("mypy.stubtest", "emnet._emnet", "--allowlist",
                          str(PYTHON / "stubtest-allowlist.txt"), cwd=tmp_path)
    assert status == 0, output


def _stub_parameters():
    """{"static": ["scene", "probes"], "SceneHandle.get": ["key"], ...} from _emnet.pyi."""
    tree = ast.parse((PACKAGE / "_emnet.pyi").read_text())
    found = {}
    for node in tree.body:
        members = node.body if isinstance(node, ast.ClassDef) else [node]
        prefix = f"{node.name}." if isinstance(node, ast.ClassDef) else ""
        for member in members:
            if isinstance(member, ast.FunctionDef) and not any(
                    isinstance(d, ast.Name) and d.id == "property" for d in member.decorator_list):
                # pybind11 names a parameter it was not given a name for arg0, arg1, ...: the
                # stub's positional-only ones.
                unnamed = [a for a in member.args.posonlyargs if a.arg != "self"]
                found[prefix + member.name] = [f"arg{k}" for k in range(len(unnamed))] + \
                    [a.arg for a in member.args.args if a.arg != "self"]
    return found


def test_the_stub_names_the_parameters_the_bindings_name():
    # pybind11 writes each function's signature as its docstring's first line:
    # "static(scene: emnet._emnet.SceneHandle, probes: List[str] = []) -> dict".
    stub = _stub_parameters()
    assert "run_study" in stub and "SceneHandle.get" in stub
    for name, parameters in stub.items():
        function = _emnet
        for part in name.split("."):
            function = getattr(function, part)
        signature = function.__doc__.splitlines()[0]
        runtime = [p for p in re.findall(r"[(,] ?(\w+): ", signature) if p != "self"]
        assert parameters == runtime, f"{name}: stub {parameters}, bindings {signature}"
