"""The observed order's stability in `ddirac.convergence` is the rule of `ddirac convergence`, from the
same code: consecutive observed orders within 10 % of the larger, the finest such stretch of rows."""

import math

import ddirac
from ddirac import _ddirac
from ddirac.convergence import STABLE, stability


def test_the_python_package_judges_stability_with_the_command_line_s_rule():
    assert STABLE == _ddirac.STABLE == 0.1
    # Rows 0…4; the orders of rows 1…4 (row 0 has none). Rows 2–4 agree (2.0, 2.1, 1.95), row 1 does not.
    orders = [None, 1.2, 2.0, 2.1, 1.95]
    first, last, mean = stability(orders)
    assert (first, last) == (1, 4) and math.isclose(mean, (2.0 + 2.1 + 1.95) / 3)
    # Round-off in the finest rows: the finest stable stretch is the coarser one.
    assert stability([None, 2.0, 1.98, 2.02, 0.3])[:2] == (0, 3)
    # Exactly at the margin agrees; just beyond it does not.
    assert stability([None, 2.0, 1.8]) is not None and stability([None, 2.0, 1.79]) is None
    # Negative, zero, missing and lone orders are never stable.
    for orders in ([None], [None, 2.0], [None, -2.0, -2.0], [None, 0.0, 0.0], [None, None, 2.0, None]):
        assert stability(orders) is None, orders
    assert stability([None, float("nan"), float("nan")]) is None
    assert _ddirac.orders_agree(2.0, 1.8) and not _ddirac.orders_agree(2.0, 1.79) and not _ddirac.orders_agree(0.0, 0.0)


def test_a_study_s_verdict_uses_the_rule():
    table = ddirac.convergence(ddirac.System.builtin("kepler"), [250, 500, 1000, 2000], 2.0,
                               q0={"r": 1.0, "phi": 0.0}, p0={"r": 0.0, "phi": 0.8}, rule="midpoint")
    found = stability(table.order)
    assert found is not None and table.stable_steps == (table.steps[found[0]], table.steps[found[1]])
    assert math.isclose(table.observed_order, found[2])
