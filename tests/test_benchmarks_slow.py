"""The benchmark scripts that docs/verification.md quotes precision figures from, run in
full: each asserts its bars (a decade above what it measured, written in the script) and
returns 1 where one is not met. Slow: minutes each."""

import pytest

from conftest import load_benchmark

pytestmark = pytest.mark.slow


def test_jax_twin_meets_its_bars(monkeypatch, capsys):
    """18 records x 2 blocks: u within 1.2e-13 relative, events within 3.6e-14 s of exact."""
    assert load_benchmark("jax_twin", monkeypatch).main() == 0
    assert "NOT met" not in capsys.readouterr().out


@pytest.mark.parametrize("backend", ["cvode", "ida"])
def test_sundials_on_every_record_meet_their_bars(backend, monkeypatch, capsys):
    """18 records, rtol 1e-10: CVODE within 1e-8 and 4.8e-11 s, IDA within 2.1e-7 and 7.5e-10 s."""
    assert load_benchmark("cvode_records", monkeypatch).main(backend) == 0
    assert "bars: " in capsys.readouterr().out


def test_floor_refinement_meets_its_bars(monkeypatch, capsys):
    """At refine = 4: median error of max |u| within 7.9e-4, largest within 3.2e-2."""
    assert load_benchmark("floor_refinement", monkeypatch).main([]) == 0
    assert "at m = 4: " in capsys.readouterr().out


def test_upthrow_backends_meet_their_bars(monkeypatch, capsys):
    """19 flying record cases and two synthetic ones: CVODE within 1e-9 s and 1e-7 of the
    speeds, IDA within 3.6e-7 s and 2.5e-6 (its undamped bouncing), JAX within 2.1e-12 s
    and 3.6e-11."""
    assert load_benchmark("upthrow", monkeypatch).main([]) == 0
    assert "NOT met" not in capsys.readouterr().out
