"""The public API is annotated: every function, class, method and property that ddirac.__all__ exports
has annotations for its parameters and its return, they resolve (typing.get_type_hints, on Python 3.9
too: `from __future__ import annotations` and typing's generics), the package ships `py.typed`, and mypy
finds no error in the package when it is installed."""

import importlib.util
import inspect
import pathlib
import subprocess
import sys
import types
import typing

import pytest

import ddirac

PACKAGE = pathlib.Path(ddirac.__file__).resolve().parent


def optional_modules():
    """The optional modules annotations name (a DataFrame, a Dataset): the module where installed,
    else a stand-in, so that the annotations resolve without them."""
    names = {}
    for module, attribute in (("pandas", "DataFrame"), ("xarray", "Dataset")):
        try:
            names[module] = __import__(module)
        except ImportError:
            names[module] = types.SimpleNamespace(**{attribute: type(attribute, (), {})})
    return names


def callables():
    """(qualified name, function) of every public function, method and property getter."""
    for name in ddirac.__all__:
        obj = getattr(ddirac, name)
        if inspect.isclass(obj):
            if issubclass(obj, BaseException) and obj.__module__.startswith("ddirac._ddirac"):
                continue  # the extension's exceptions: annotated in _ddirac.pyi
            for member, value in vars(obj).items():
                if member.startswith("_") and member != "__init__":
                    continue
                if isinstance(value, property):
                    yield f"{name}.{member}", value.fget
                elif isinstance(value, (classmethod, staticmethod)):
                    yield f"{name}.{member}", value.__func__
                elif inspect.isfunction(value):
                    yield f"{name}.{member}", value
        elif inspect.isfunction(obj):
            yield name, obj


def test_every_public_function_and_method_is_annotated_and_its_annotations_resolve():
    missing = []
    seen = 0
    for name, function in callables():
        seen += 1
        hints = typing.get_type_hints(function, localns=optional_modules())
        signature = inspect.signature(function)
        parameters = [p for p in signature.parameters.values() if p.name not in ("self", "cls")]
        missing += [f"{name}({p.name})" for p in parameters if p.name not in hints]
        if "return" not in hints:
            missing.append(f"{name} -> ?")
    assert seen > 30 and not missing, missing


def test_the_package_ships_py_typed():
    assert (PACKAGE / "py.typed").is_file()


@pytest.mark.skipif(importlib.util.find_spec("mypy") is None, reason="mypy is not installed")
def test_mypy_finds_no_error_in_the_package(tmp_path):
    # The installed package by name (`-p`), from a directory of its own: run on a path inside
    # site-packages, mypy would take every module there for one of the user's.
    done = subprocess.run([sys.executable, "-m", "mypy", "--ignore-missing-imports", "--disallow-untyped-defs",
                           "--disallow-incomplete-defs", "--no-incremental", "-p", "ddirac"],
                          capture_output=True, text=True, cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
