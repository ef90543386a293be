"""The test command installed pytest, pandas, Dask and the package into whatever ``python3`` came first
on PATH — a user's global Python. It now installs into a virtual environment of its own (or the active
one), and runs the tests with that environment's interpreter."""

import os
import sys
from pathlib import Path

import pytest

import ddirac

USED = os.environ.get("DDIRAC_TEST_VENV_USED")


@pytest.mark.skipif(USED is None, reason="run by scripts/test.sh only")
def test_the_test_command_runs_in_a_virtual_environment():
    # A virtual environment's interpreter has a prefix of its own, apart from the base installation.
    assert sys.prefix != sys.base_prefix, f"pytest runs in the base interpreter {sys.prefix}"
    assert Path(sys.prefix).resolve() == Path(USED).resolve()
    # The package under test is the one installed there, not a copy elsewhere on the path.
    assert Path(ddirac.__file__).resolve().is_relative_to(Path(sys.prefix).resolve())
