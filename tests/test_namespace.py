"""The top-level namespace: at most 50 names in ``blockdae.__all__``, each resolving without
a warning; every name that left the top level still resolves there, for one release, to
the very object of its new home, with a DeprecationWarning that names the new call."""

import importlib
import pathlib
import subprocess
import sys
import warnings

import pytest

import blockdae as bd

#: every name of ``blockdae.__all__`` before the namespace was made small (108 names)
OLD_TOP_LEVEL = [
    "AbstractExcitation", "AbstractHybridModel", "BaseMotion", "BatchSolution", "Event", "EventLog", "Harmonic", "Mode",
    "Record", "RectangularPulse", "SinePulse", "SlidingBlock", "Solution", "TriangularPulse",
    "check_peak_acceleration", "read_motion", "read_record", "read_records", "RecordSet", "simulate",
    "InconsistentStateError", "SolverError", "RecordWarning", "UnitsWarning", "pga_factor", "resample",
    "AbstractEvent", "AbstractSolution", "DriverSolution", "HybridEvent",
    "BatchedModel", "DifferentiableModel", "EngineModel", "LinearModesModel", "StudyBatch", "StudyModel",
    "PlanarBlock", "PlanarEvent", "PlanarMode", "PlanarSolution", "RigidSupport", "SpringSupport",
    "Flight", "SpringSupportedMass", "UpthrowEstimate", "UpthrowEvent", "UpthrowMode", "UpthrowSolution",
    "upthrow_estimate", "SweepSolution", "simulate_many", "FinalNumbers", "simulate_final", "simulate_linear_final",
    "CrossCheck", "crosscheck", "SeedExample", "STANDARD_GRAVITY", "plot", "seed_examples",
    "sensitivities", "set_compilation_cache", "CompileNotice",
    "NewmarkResult", "NewmarkSweep", "newmark", "yield_acceleration",
    "EquivalentLinear", "FlexibleEvent", "FlexibleMode", "FlexibleResult", "FlexibleSlidingMass", "FlexibleSolution",
    "KyTable", "ShearColumn", "flexible",
    "IntensityMeasures", "baseline_corrected", "cumulative_arias", "intensity_measures", "mean_period",
    "motion_histories", "ResponseSpectrum", "response_spectrum", "RelativeMotion", "fourier_amplitude",
    "relative_motion", "AdjustmentFactor", "fit_adjustment_factor", "newmark_rd", "newmark_rd_sd", "pulse_sd",
    "Floor", "ShearFrame", "load_study", "save_study", "study", "study_summary",
    "empirical", "hazard",
    "AbstractBackend", "register_backend", "CVODE", "IDA", "JaxTwin", "Exact", "ExactJax", "Compiled",
]

#: a few moves written out by hand (the rest follow the table in blockdae/__init__.py)
SPOT_CHECKS = {"response_spectrum": "blockdae.motions.response_spectrum",
               "resample": "blockdae.excitation.resample",
               "DifferentiableModel": "blockdae.core.contract.DifferentiableModel",
               "PlanarEvent": "blockdae.planar.PlanarEvent",
               "seed_examples": "blockdae.sliding.seed_examples",
               "register_backend": "blockdae.backends.register_backend",
               "study_summary": "blockdae.studies.summary"}


def test_the_top_level_is_small_and_has_no_duplicates():
    assert len(bd.__all__) <= 50, len(bd.__all__)
    assert len(set(bd.__all__)) == len(bd.__all__)


@pytest.mark.parametrize("name", bd.__all__)
def test_every_public_name_resolves_without_a_warning(name):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert getattr(bd, name) is not None


@pytest.mark.parametrize("name", OLD_TOP_LEVEL)
def test_every_old_name_still_resolves(name):
    """A name still public resolves silently; a moved one warns with its new call and is
    the object of its new home."""
    if name in bd.__all__ or name in ("empirical", "hazard"):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            assert getattr(bd, name) is not None
        return
    module, new_name = bd._MOVED[name]
    with pytest.warns(DeprecationWarning) as caught:
        old = getattr(bd, name)
    message = str(caught[0].message)
    assert message == f"bd.{name} is {module}.{new_name}; the top-level name goes in the next release", message
    assert caught[0].filename == __file__
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert old is getattr(importlib.import_module(module), new_name)
        assert new_name in importlib.import_module(module).__all__


def test_the_moves_are_the_old_names_that_left():
    assert set(bd._MOVED) == set(OLD_TOP_LEVEL) - set(bd.__all__) - {"empirical", "hazard"}
    for name, new_call in SPOT_CHECKS.items():
        assert ".".join(bd._MOVED[name]) == new_call


def test_a_moved_name_is_not_listed_and_an_unknown_one_raises():
    assert not set(bd._MOVED) & set(dir(bd))
    with pytest.raises(AttributeError, match="no_such_name"):
        bd.no_such_name


def test_the_subpackages_are_reached_from_the_top_level():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert bd.motions.response_spectrum is bd.motions.__dict__["response_spectrum"]
        assert bd.hazard.fit_fragility and bd.empirical.jibson_2007 and bd.backends.available
        assert bd.core.contract.DifferentiableModel and bd.sliding.newmark_rd and bd.planar.PlanarEvent


def test_importing_blockdae_loads_no_jax_and_the_old_names_do_not_either():
    """The moved names are resolved from modules ``import blockdae`` already loads (or
    from the solvers), so neither the import nor an old name brings in JAX."""
    code = ("import sys, warnings; warnings.simplefilter('ignore'); import blockdae as bd; "
            "[getattr(bd, n) for n in bd._MOVED]; print('jax' in sys.modules)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.strip() == "False"


def test_the_changelog_tells_where_each_old_name_went():
    """Each moved name is in a row of the CHANGELOG's migration table with its new module."""
    changelog = (pathlib.Path(__file__).parents[1] / "CHANGELOG.md").read_text()
    rows = [line for line in changelog.splitlines() if line.startswith("  | `bd.")]
    for name, (module, new_name) in bd._MOVED.items():
        row = [r for r in rows if f"`bd.{name}`" in r]
        assert len(row) == 1, name
        new_call = row[0].rsplit("|", 2)[1]
        assert f"`{module}.`" in new_call and new_name == name or f"`{module}.{new_name}`" in new_call, (name, row)
