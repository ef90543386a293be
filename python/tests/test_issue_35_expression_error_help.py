"""ddirac.ExpressionError carries the help the command line prints for the same fault (`help`, and at
the end of the message): what the Lagrangian, a definition or an exact solution may use."""

import os
import pathlib
import re
import subprocess

import pytest

import ddirac
import command_line

REPO = pathlib.Path(__file__).resolve().parents[2]


def cli_help(tmp_path, system_table, parameters):
    """The `help:` line `ddirac check` prints for a spec with this [system] table and [parameters]."""
    spec = tmp_path / "spec.toml"
    spec.write_text(system_table + "\n[parameters]\n" + "".join(f"{k} = {v}\n" for k, v in parameters.items())
                    + "\n[time]\nstep = 0.01\nsteps = 10\n\n[initial]\nq = [0.1]\np = [0.0]\n", encoding="utf-8")
    done = subprocess.run([command_line.built(), "check", str(spec)], capture_output=True, text=True,
                          env={**os.environ, "NO_COLOR": "1", "COLUMNS": "1000"})
    assert done.returncode == 2, done.stderr
    text = re.sub(r"\x1b\[[0-9;]*m", "", done.stderr)
    found = re.search(r"help: (.*?)\s*$", text, re.S)
    assert found, text
    return " ".join(found.group(1).split())


def python_spelling(cli):
    """Python gives the constants as `parameters={...}` where a spec has its `[parameters]` table."""
    return cli.replace("`[parameters]`", "`parameters={...}`").replace("`[system.exact]`", "`exact`")


def test_an_unknown_name_in_the_lagrangian_gets_the_command_lines_help(tmp_path):
    lagrangian = "0.5*r^2*th_dot^2 - b*th^2 - w"
    expected = cli_help(tmp_path, f'[system]\nlagrangian = "{lagrangian}"\nshape = ["th"]\n'
                        '[system.definitions]\nw = "r*th"\n', {"r": 1.0})
    with pytest.raises(ddirac.ExpressionError) as caught:
        ddirac.System(lagrangian=lagrangian, shape=["th"], parameters={"r": 1.0}, definitions={"w": "r*th"})
    error = caught.value
    assert error.help == python_spelling(expected)
    assert "the parameters (r)" in error.help and "`parameters={...}`" in error.help
    assert str(error).endswith("help: " + error.help)
    assert "did you mean `r`?" in str(error) and error.origin == "the Lagrangian"


def test_an_unknown_name_in_an_exact_solution_gets_the_command_lines_help(tmp_path):
    expected = cli_help(tmp_path, '[system]\nlagrangian = "0.5*th_dot^2"\nshape = ["th"]\n'
                        '[system.exact]\nth = "a*t"\n', {"r": 1.0})
    with pytest.raises(ddirac.ExpressionError) as caught:
        ddirac.System(lagrangian="0.5*th_dot^2", shape=["th"], parameters={"r": 1.0}, exact={"th": "a*t"})
    assert caught.value.help == python_spelling(expected)
    assert str(caught.value).endswith("help: " + caught.value.help)


def test_an_error_without_help_has_none():
    with pytest.raises(ddirac.ExpressionError) as caught:
        ddirac.System(lagrangian="0.5*th_dot^2 +", shape=["th"])
    assert caught.value.help is None and "help:" not in str(caught.value)
