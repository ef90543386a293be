"""ddirac.check examines every chart of an atlas, with the verdict a run applies: a chart whose maps are
not inverse (``atan2``'s arguments swapped in ``to_main``) is refused by both, naming the chart."""

import pathlib

import pytest

import ddirac

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"


def test_the_shipped_atlases_pass_with_maps_inverse_to_round_off():
    spec = ddirac.load(EXAMPLES / "spherical_pendulum.toml")
    report = spec.check()
    assert [c["name"] for c in report["charts"]] == ["lower cap", "upper cap"]
    for chart in report["charts"]:
        assert chart["inverse"] and chart["points"] >= 20 and chart["round_trip"] < 1e-13
        assert chart["singular_where_good"] is None
    assert report["verdict"]["runs"]
    dsp = ddirac.System.builtin("double_spherical_pendulum")
    report = ddirac.check(dsp, q0=[0, 2.25, 2, 3], p0=[0, 0, 1, 1], step=0.01, steps=100, reduced=True)
    assert len(report["charts"]) >= 2 and all(c["inverse"] for c in report["charts"])


def test_a_chart_whose_maps_are_not_inverse_is_refused_by_check_and_run(tmp_path):
    text = (EXAMPLES / "spherical_pendulum.toml").read_text().replace('phi = "atan2(y, x)"', 'phi = "atan2(x, y)"')
    path = tmp_path / "swapped.toml"
    path.write_text(text)
    spec = ddirac.load(path)
    report = spec.check()
    assert not all(c["inverse"] for c in report["charts"])
    assert not report["verdict"]["runs"]
    assert "chart `lower cap` of the atlas: its maps are not inverse" in report["verdict"]["error"]
    with pytest.raises(ddirac.Error, match="its maps are not inverse"):
        spec.run()
