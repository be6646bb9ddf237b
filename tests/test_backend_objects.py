"""Backends as objects as well as names: ``backend=bd.CVODE(rtol=1e-12)`` runs the very
backend ``backend="cvode", rtol=1e-12`` runs (bit-identical results); each class lists
its own options; a backend registers under a new name without editing the package."""

import ast
import dataclasses
import inspect
import re
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import blockdae as bd
from blockdae.core import _registry
from blockdae.backends import BUILT_IN, available, backend_class, make_backend, register_backend

#: public name -> registered name
PUBLIC = {"Exact": "exact", "ExactJax": "exact-jax", "CVODE": "cvode", "IDA": "ida", "JaxTwin": "jax",
          "Compiled": "compiled"}
BLOCK, PULSE = bd.SlidingBlock(0.3, 0.2), bd.SinePulse(6.0, 0.5)


@pytest.fixture
def registry():
    """The registry as it was, after the test."""
    saved = dict(_registry._REGISTRY)
    yield
    _registry._REGISTRY.clear()
    _registry._REGISTRY.update(saved)
    backend_class.cache_clear()
    _registry._default_backend.cache_clear()


def documented_options(cls) -> dict:
    """option -> documented default, from the ``name=default: meaning [unit]`` lines of
    the class's Args section (every line must state a unit in brackets)."""
    doc = inspect.getdoc(cls)
    section = doc[doc.index("Args:"):]
    options = {}
    for line in section.splitlines()[1:]:
        match = re.match(r" {4}(\w+)=(.+?): (.*)", line)
        if match:
            assert re.search(r"\[[^\]]*\]", match.group(3)), (cls.__name__, line)
            options[match.group(1)] = ast.literal_eval(match.group(2))
    return options


def test_the_public_names_are_the_registered_classes():
    assert set(PUBLIC) <= set(bd.__all__) and set(PUBLIC.values()) == set(BUILT_IN)
    for public, name in PUBLIC.items():
        cls = getattr(bd, public)
        assert cls is backend_class(name) and cls.__name__ == public and cls.name == name
        assert issubclass(cls, bd.backends.AbstractBackend) and make_backend(name) == cls()


@pytest.mark.parametrize("name", BUILT_IN)
def test_each_backend_class_documents_its_own_options_with_default_and_unit(name):
    cls = backend_class(name)
    assert documented_options(cls) == {f.name: f.default for f in dataclasses.fields(cls)}


def test_simulate_points_to_the_classes_and_lists_no_options():
    doc = inspect.getdoc(bd.simulate)
    for public in PUBLIC:
        assert f":class:`{public}`" in doc
    assert not re.search(r"^ +\w+=\S+: ", doc, re.MULTILINE)  # no "name=default: meaning" lines


def test_import_loads_neither_jax_nor_sundials():
    code = ("import sys, blockdae as bd; loaded = lambda: sorted({'jax', 'sksundae'} & set(sys.modules)); "
            "print(loaded()); bd.CVODE; print(loaded())")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.splitlines() == ["[]", "['sksundae']"]


@pytest.mark.parametrize("name, options", [
    ("exact", {}), ("exact", dict(window=8)), ("cvode", dict(rtol=1e-11, max_step=0.05)), ("ida", dict(rtol=1e-9)),
    ("exact-jax", {}), ("jax", dict(rtol=1e-11)),
])
def test_an_object_runs_as_its_name_with_options(name, options):
    """The same backend runs: every knot, event and the final state bit-identical."""
    by_name = bd.simulate(BLOCK, PULSE, backend=name, **options)
    as_object = bd.simulate(BLOCK, PULSE, backend=backend_class(name)(**options))
    assert as_object.backend == by_name.backend == name
    for field in ("t", "u", "v", "mode", "t_events"):
        assert np.array_equal(getattr(as_object, field), getattr(by_name, field)), field
    assert as_object.displacement == by_name.displacement


def test_a_batch_runs_on_an_object():
    grid = bd.SlidingBlock(np.array([0.2, 0.3]))
    by_name = bd.simulate(grid, PULSE, backend="cvode", rtol=1e-11)
    as_object = bd.simulate(grid, PULSE, backend=bd.CVODE(rtol=1e-11))
    assert np.array_equal(as_object.displacement, by_name.displacement)


def test_options_beside_an_object_and_other_types_are_type_errors():
    with pytest.raises(TypeError, match=r"carries its own settings: give rtol to it \(CVODE\(rtol=\.\.\.\)\)"):
        bd.simulate(BLOCK, PULSE, backend=bd.CVODE(), rtol=1e-9)
    with pytest.raises(TypeError, match="backend must be a name from .* or a backend object .* got int"):
        bd.simulate(BLOCK, PULSE, backend=3)
    with pytest.raises(ValueError, match=r"backend='compiled' does not run a SlidingBlock"):
        bd.simulate(BLOCK, PULSE, backend=bd.Compiled())
    with pytest.raises(ValueError, match="rtol"):
        bd.CVODE(rtol=1.0)


def test_crosscheck_takes_objects_labelled_by_their_settings():
    tight = bd.CVODE(rtol=1e-12)
    table = bd.crosscheck(BLOCK, PULSE, backends=("exact", tight, "cvode"), rtol=1e-11)
    assert [row["backend"] for row in table.rows] == ["exact", "cvode(rtol=1e-12)", "cvode"]
    assert table.row(tight) is table.rows[1] and table.row("cvode(rtol=1e-12)") is table.rows[1]
    assert table.rows[1]["rtol"] == 1e-12 and table.rows[2]["rtol"] == 1e-11  # options go to names only
    reference = bd.crosscheck(BLOCK, PULSE, backends=("exact", "cvode"), rtol=1e-12)
    assert table.rows[1]["displacement"] == reference.rows[1]["displacement"]
    assert "cvode(rtol=1e-12)" in str(table)
    with pytest.raises(TypeError, match=r"no backend given by name in \('exact', 'cvode\(rtol=1e-12\)'\)"):
        bd.crosscheck(BLOCK, PULSE, backends=("exact", tight), rtol=1e-9)


def test_sensitivities_take_objects():
    """An Exact object is differentiated through ExactJax at its window (which changes
    speed, never results); options beside it are an error, as in simulate."""
    by_name = bd.sensitivities(BLOCK, PULSE, wrt=("mu", "A"))
    assert bd.sensitivities(BLOCK, PULSE, wrt=("mu", "A"), backend=bd.Exact()) == by_name
    assert bd.sensitivities(BLOCK, PULSE, wrt=("mu", "A"), backend=bd.ExactJax()) == by_name
    with pytest.raises(ValueError, match="has no derivatives"):
        bd.sensitivities(BLOCK, PULSE, backend=bd.CVODE())
    with pytest.raises(TypeError, match="carries its own settings"):
        bd.sensitivities(BLOCK, PULSE, backend=bd.Exact(), window=8)


@dataclasses.dataclass(frozen=True)
class TightCVODE(bd.CVODE):
    """CVODE at a tighter default tolerance.

    Args:
        rtol=1e-12: relative tolerance [-].
    """

    rtol: float = 1e-12
    name = "cvode-tight"


@dataclasses.dataclass(frozen=True)
class EnginesOnlyCVODE(bd.CVODE):
    """CVODE for the models whose ``engines`` name it, no other."""

    name = "cvode-engines-only"
    generic = False


def test_a_registered_backend_runs_by_name_and_as_an_object(registry):
    register_backend("cvode-tight", TightCVODE)
    register_backend("cvode-engines-only", EnginesOnlyCVODE)
    assert available()[-2:] == ("cvode-tight", "cvode-engines-only")
    assert "cvode-tight" in available(BLOCK) and "cvode-engines-only" not in available(BLOCK)
    reference = bd.simulate(BLOCK, PULSE, backend="cvode", rtol=1e-12)
    for backend, options in (("cvode-tight", {}), (TightCVODE(), {}), ("cvode-tight", dict(rtol=1e-12))):
        sol = bd.simulate(BLOCK, PULSE, backend=backend, **options)
        assert sol.backend == "cvode-tight"
        assert np.array_equal(sol.t, reference.t) and np.array_equal(sol.u, reference.u)
    with pytest.raises(ValueError, match="backend='cvode-engines-only' does not run a SlidingBlock"):
        bd.simulate(BLOCK, PULSE, backend="cvode-engines-only")
    table = bd.crosscheck(BLOCK, PULSE, backends=("exact", "cvode-tight"))
    assert table.rows[1]["backend"] == "cvode-tight" and table.rows[1]["rtol"] == 1e-12


def test_a_backend_registered_as_a_path_loads_on_first_use(registry, tmp_path, monkeypatch):
    (tmp_path / "site_backends.py").write_text(textwrap.dedent('''
        import dataclasses
        import blockdae as bd

        @dataclasses.dataclass(frozen=True)
        class Coarse(bd.CVODE):
            """CVODE at rtol 1e-6 by default."""
            rtol: float = 1e-6
            name = "cvode-coarse"
    '''))
    monkeypatch.syspath_prepend(tmp_path)
    register_backend("cvode-coarse", "site_backends:Coarse")
    assert "site_backends" not in sys.modules and "cvode-coarse" in available()
    sol = bd.simulate(BLOCK, PULSE, backend="cvode-coarse")
    assert sol.backend == "cvode-coarse" and sol.displacement == bd.simulate(BLOCK, PULSE, backend="cvode",
                                                                             rtol=1e-6).displacement
    monkeypatch.delitem(sys.modules, "site_backends")


def test_bad_registrations_are_named(registry):
    with pytest.raises(ValueError, match="'cvode' is built in"):
        register_backend("cvode", TightCVODE)
    with pytest.raises(ValueError, match=r"TightCVODE.name is 'cvode-tight'; set it to 'mine'"):
        register_backend("mine", TightCVODE)
    with pytest.raises(TypeError, match="not a subclass of blockdae.backends.AbstractBackend"):
        register_backend("mine", dict)
    with pytest.raises(ValueError, match="'module:Class'"):
        register_backend("mine", "no_colon_here")
    register_backend("mine", "blockdae.solvers._cvode:CVODE")  # checked when first used
    with pytest.raises(ValueError, match=r"CVODE.name is 'cvode'; set it to 'mine'"):
        bd.simulate(BLOCK, PULSE, backend="mine")
