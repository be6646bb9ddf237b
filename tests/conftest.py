"""Shared test data: the 18 accelerograms that pySLAMMER ships (a test-only extra)."""

import importlib.resources
import importlib.util
import pathlib

import numpy as np
import pytest

import blockdae as bd


def sample_record_paths():
    """Paths of pySLAMMER's sample records (CSV: time [s], acceleration [g])."""
    folder = importlib.resources.files("pyslammer") / "sample_ground_motions"
    return sorted(p for p in folder.iterdir() if p.name.endswith(".csv"))


def load_sample_record(stem: str) -> bd.Record:
    """One sample record by file stem, e.g. "Kobe_1995_TAK-090"."""
    folder = importlib.resources.files("pyslammer") / "sample_ground_motions"
    return bd.read_record(folder / f"{stem}.csv", units="g")


#: the repository's benchmark scripts
BENCHMARKS = pathlib.Path(__file__).parents[1] / "benchmarks"


def load_benchmark(name, monkeypatch):
    """The benchmark script ``benchmarks/<name>.py`` as a module (its folder on sys.path
    for its ``_common`` import)."""
    monkeypatch.syspath_prepend(str(BENCHMARKS))
    spec = importlib.util.spec_from_file_location(f"benchmark_{name}", BENCHMARKS / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def assert_same_events(sol, ref, dt_max):
    """The same sequence of mode changes as ``ref``, each event within ``dt_max`` [s]."""
    assert [(e.mode_before, e.mode_after) for e in sol.events] == \
        [(e.mode_before, e.mode_after) for e in ref.events]
    np.testing.assert_allclose(sol.t_events, ref.t_events, rtol=0, atol=dt_max)


@pytest.fixture(scope="session")
def kobe() -> bd.Record:
    return load_sample_record("Kobe_1995_TAK-090")


@pytest.fixture(scope="session")
def sample_records() -> list[bd.Record]:
    return [bd.read_record(p, units="g") for p in sample_record_paths()]


@pytest.fixture(scope="session")
def jax_cache_dir(tmp_path_factory):
    """A JAX compilation cache shared by the subprocesses of one test session."""
    return tmp_path_factory.mktemp("jax_cache")
