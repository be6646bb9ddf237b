"""Every result's repr is one short line: arrays by range and shape, with a summary."""

import numpy as np
import pytest

import blockdae as bd


#: the deprecated many-motion functions keep their tests for the release they stay
pytestmark = [pytest.mark.filterwarnings("ignore:blockdae.sliding.simulate_many is deprecated:DeprecationWarning"),
              pytest.mark.filterwarnings("ignore:blockdae.sliding.simulate_final is deprecated:DeprecationWarning")]


#: the longest repr allowed [characters]
LONGEST = 400


@pytest.fixture(scope="module")
def record():
    t = np.arange(0.0, 20.0, 0.01)
    return bd.Record(0.3 * np.sin(2 * np.pi * t) * np.exp(-((t - 5.0) / 3.0) ** 2), 0.01, name="synthetic",
                     units="g")


def _short(result):
    text = repr(result)
    assert len(text) < LONGEST and "\n" not in text and "array(" not in text, text
    return text


def test_solutions_and_batches(record):
    block = bd.SlidingBlock(mu=0.1, direction="negative")
    solution = bd.simulate(block, record)
    assert f"u(t_end) = {solution.displacement:.6g} m (signed" in _short(solution)
    assert "30 parameter sets" in _short(bd.simulate(block.replace(mu=np.linspace(0.05, 0.2, 30)), record))
    _short(bd.sliding.simulate_final(block.replace(mu=np.linspace(0.05, 0.2, 30)), record))
    _short(bd.sliding.simulate_many(block, [record, record.scaled(0.5)]))
    flexible = bd.simulate(bd.FlexibleSlidingMass(bd.ShearColumn(10.0, 200.0), ky=0.1), record, t_end=20.0)
    assert f"D = {flexible.sliding_displacement:.6g} m" in _short(flexible)


def test_tables_and_spectra(record):
    result = bd.flexible([record, record.scaled(0.5)], ky=np.linspace(0.02, 0.2, 10), height=10.0, vs=200.0)
    assert "20 rows" in _short(result) and "rows=<20 dict>" in repr(result)
    _short(bd.motions.response_spectrum(record, np.linspace(0.1, 3.0, 50)))
    _short(bd.motions.intensity_measures(record))


def test_a_fragility_shows_its_parameters_not_its_bootstrap_array():
    rng = np.random.default_rng(3)
    records = np.repeat([f"r{i}" for i in range(12)], 5)
    pga = np.tile([0.1, 0.2, 0.3, 0.5, 0.8], 12)
    d = 0.05 * pga ** 1.5 * np.exp(0.4 * rng.standard_normal(pga.size))
    import pandas as pd

    fit = bd.hazard.fit_fragility(pd.DataFrame({"record": records, "pga_g": pga, "max_abs_displacement_m": d}),
                                  n_boot=200)
    text = _short(fit)
    assert fit.boot.shape == (200, 5) and "200 bootstrap refits" in text and "shape (200, 5)" in text
    assert f"sigma ln D = {fit.sigma:.3g}" in text and f"c1={fit.c1:.6g}" in text
