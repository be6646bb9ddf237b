"""What a model's ``engines`` hold: an engine runs the model on one backend with that
backend's settings. The contract of an engine:

- ``solve(model, excitation, horizon, backend) -> solution`` (one parameter set);
- optionally ``solve_batch(model, excitation, horizon, backend) -> BatchSolution`` (a
  batch of parameter sets) and ``solve_final(model, excitations, horizons, scale, backend)
  -> array`` (final numbers of many motions at many factors on a(t), in one call), with
  ``final_numbers(rows) -> (displacement (n, d), max |displacement| (n,), events (n,),
  t_end (n,) [s])`` reading n rows of that array (displacements in the model's
  ``displacement_unit``).

``backend`` is the backend object: the engine reads the settings it documents from it (its
``name``, ``window``, ``rtol``, ...)."""

import functools
import importlib


class LazyEngine:
    """An engine whose module is imported on its first run (kernels that load JAX or compile
    with numba cost nothing until used): ``LazyEngine("blockdae.sliding._twin", "TwinEngine")``."""

    def __init__(self, module: str, name: str):
        self.module, self.name = module, name

    def __repr__(self):
        return f"LazyEngine({self.module!r}, {self.name!r})"

    @functools.cached_property
    def engine(self):
        return getattr(importlib.import_module(self.module), self.name)()

    def solve(self, model, excitation, horizon, backend):
        return self.engine.solve(model, excitation, horizon, backend)

    def solve_batch(self, model, excitation, horizon, backend):
        return self.engine.solve_batch(model, excitation, horizon, backend)

    def solve_final(self, model, excitations, horizons, scale, backend):
        return self.engine.solve_final(model, excitations, horizons, scale, backend)

    def final_numbers(self, rows):
        return self.engine.final_numbers(rows)
