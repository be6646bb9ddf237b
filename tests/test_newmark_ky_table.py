"""Newmark's rigid block with ky against the sliding displacement (bd.newmark(ky=KyTable)):
against the closed forms of a rectangular pulse on a hardening and a softening piece,
across breakpoints, against the constant-ky engine, and its refusals."""

import math

import numpy as np
import pytest

import blockdae as bd
from blockdae.cli import main
from conftest import load_sample_record, sample_record_paths

G = bd.STANDARD_GRAVITY
A, T0 = 0.5, 0.2  # a pulse of 0.5 g for 0.2 s [g, s]


def hardening(k0, k1):
    """D after the pulse for ky = k0 + k1 D (closed form): D'' = g (A - k0) - g k1 D from
    t = 0 (a harmonic arc), then D'' = -g (k0 + k1 D) until D' = 0."""
    w, c, q = math.sqrt(G * k1), (A - k0) / k1, k0 / k1
    d1, v1 = c * (1 - math.cos(w * T0)), c * w * math.sin(w * T0)
    return -q + math.hypot(d1 + q, v1 / w)


def softening(k0, k1):
    """D after the pulse for ky = k0 - k1 D (closed form): a hyperbolic arc, then
    D'' = g (k1 D - k0) until D' = 0, at q - sqrt((q - D1)² - (V1 / l)²), q = k0 / k1."""
    lam, c, q = math.sqrt(G * k1), (A - k0) / k1, k0 / k1
    d1, v1 = c * (math.cosh(lam * T0) - 1), c * lam * math.sinh(lam * T0)
    return q - math.sqrt((q - d1) ** 2 - (v1 / lam) ** 2)


@pytest.mark.parametrize("rows, closed_form", [
    (([0.0, 10.0], [0.1, 0.1 + 2.0 * 10.0]), hardening(0.1, 2.0)),
    (([0.0, 0.4], [0.2, 0.0]), softening(0.2, 0.5)),
    (([0.0, 0.05, 0.1, 0.4], [0.2, 0.175, 0.15, 0.0]), softening(0.2, 0.5)),  # the same line, two breakpoints
], ids=["hardening", "softening", "softening-across-breakpoints"])
def test_a_rectangular_pulse_slides_as_the_closed_form(rows, closed_form):
    result = bd.newmark(bd.RectangularPulse(A * G, T0), ky=bd.KyTable(*rows))
    assert result.normal == pytest.approx(closed_form, rel=1e-13)
    assert result.inverse == 0.0 and result.ky == rows[1][0]


def test_a_flat_table_is_the_constant_ky_engine():
    """A one-row table and a flat two-row one give the constant-ky engine's D on a record
    (two different exact engines: within 1e-13 relative)."""
    record = load_sample_record("Kobe_1995_TAK-090")
    constant = bd.newmark(record, ky=0.1)
    for table in (bd.KyTable([0.0, 1.0], [0.1, 0.1]), bd.KyTable([0.0], [0.1])):
        result = bd.newmark(record, ky=table)
        assert (result.normal, result.inverse) == pytest.approx((constant.normal, constant.inverse), rel=1e-13)


def test_a_softening_table_on_records_and_pgas():
    """Softening slides farther than its ky at D = 0 would and less than its residual ky."""
    record = load_sample_record("Kobe_1995_TAK-090")
    softer = bd.newmark([record], ky=bd.KyTable([0.0, 0.5], [0.15, 0.05]), pga=[0.3, 0.5]).maximum
    assert np.all(bd.newmark([record], ky=0.15, pga=[0.3, 0.5]).maximum < softer)
    assert np.all(softer < bd.newmark([record], ky=0.05, pga=[0.3, 0.5]).maximum)


def test_refusals():
    pulse = bd.RectangularPulse(A * G, T0)
    with pytest.raises(ValueError, match="never stops; give t_end"):
        bd.newmark(bd.RectangularPulse(A * G, 1.0), ky=bd.KyTable([0.0, 0.1], [0.2, 0.0]))
    stopped = bd.newmark(bd.RectangularPulse(A * G, 1.0), ky=bd.KyTable([0.0, 0.1], [0.2, 0.0]), t_end=1.0)
    assert stopped.normal > 0.1
    with pytest.raises(ValueError, match="without derivatives"):
        bd.newmark(pulse, ky=bd.KyTable([0.0, 1.0], [0.1, 0.2]), derivative=True)


def test_the_command_line_takes_a_ky_table(capsys):
    path = next(p for p in sample_record_paths() if "Kobe" in str(p))
    assert main(["--no-cache", "newmark", str(path), "--ky-table", "0:0.15", "0.5:0.05", "--json"]) == 0
    import json
    row = json.loads(capsys.readouterr().out)["results"][0]
    api = bd.newmark(load_sample_record("Kobe_1995_TAK-090"), ky=bd.KyTable([0.0, 0.5], [0.15, 0.05]))
    assert (row["ky_g"], row["normal_m"], row["inverse_m"]) == (0.15, api.normal, api.inverse)
    assert main(["--no-cache", "newmark", str(path), "--ky-table", "0:0.15", "0.5:0.05", "--history", "h.csv"]) == 2
