"""The built command line for tests that compare Python with it: `$DDIRAC_BIN`, else
`target/release/ddirac` (under `$CARGO_TARGET_DIR` when set), which the test command builds first."""

import os
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]


def binary() -> Path:
    """Where the command line is, built or not."""
    if os.environ.get("DDIRAC_BIN"):
        return Path(os.environ["DDIRAC_BIN"])
    target = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
    return (target if target.is_absolute() else REPO / target) / "release" / "ddirac"


def built() -> str:
    """The command line's path; the test is skipped when it is not built."""
    path = binary()
    if not path.is_file():
        pytest.skip(f"the command line is not built ({path}, or $DDIRAC_BIN)")
    return str(path)
