"""examples/python/double_spherical_pendulum.py writes its figure into an output directory (`out/` by
default, or `--out DIR`) and prints where, never into the working directory.

Matplotlib is replaced by a stand-in whose savefig writes the file it is given, so the test needs no
Matplotlib and sees exactly where the script saves."""

import os
import pathlib
import runpy
import sys
import types

import pytest

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "examples" / "python" / "double_spherical_pendulum.py"


class _Anything:
    """Accepts any call and attribute (axes, their plots, labels, ...)."""

    def __getattr__(self, name):
        return _Anything()

    def __call__(self, *args, **kwargs):
        return _Anything()

    def __getitem__(self, key):
        return _Anything()


class _Figure(_Anything):
    def savefig(self, path, *args, **kwargs):
        pathlib.Path(path).write_bytes(b"\x89PNG stand-in")


def fake_matplotlib(monkeypatch):
    matplotlib = types.ModuleType("matplotlib")
    matplotlib.use = lambda backend: None
    pyplot = types.ModuleType("matplotlib.pyplot")
    pyplot.subplots = lambda *args, **kwargs: (_Figure(), _Anything())
    matplotlib.pyplot = pyplot
    monkeypatch.setitem(sys.modules, "matplotlib", matplotlib)
    monkeypatch.setitem(sys.modules, "matplotlib.pyplot", pyplot)


def run_script(monkeypatch, tmp_path, argv):
    fake_matplotlib(monkeypatch)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(sys, "argv", [str(SCRIPT)] + argv)
    runpy.run_path(str(SCRIPT), run_name="__main__")


@pytest.mark.parametrize("argv, directory", [([], "out"), (["--out", "figures/dsp"], "figures/dsp")])
def test_the_figure_goes_into_the_output_directory(monkeypatch, tmp_path, capsys, argv, directory):
    run_script(monkeypatch, tmp_path, argv)
    figure = pathlib.Path(directory) / "double_spherical_pendulum.png"
    assert (tmp_path / figure).is_file()
    assert not (tmp_path / "double_spherical_pendulum.png").exists()
    assert [p.name for p in tmp_path.iterdir()] == [pathlib.Path(directory).parts[0]]
    assert f"wrote {figure}" in capsys.readouterr().out
