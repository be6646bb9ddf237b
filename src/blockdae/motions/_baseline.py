"""Baseline correction of records: a new Record, the original untouched."""

import numpy as np

from ..excitation import Record
from . import _checks

METHODS = ("polynomial", "mean", "none")


def baseline_corrected(record, method="polynomial", degree=6, pre_event=None) -> Record:
    """The record with its baseline removed, as a new :class:`~blockdae.Record`.

    Methods:
      * ``"polynomial"`` (default, Ancheta et al. 2013, NGA-West2 database, PEER Report
        2013/03; the ``correct_baseline`` step of USGS gmprocess): fit the displacement
        d(t) of the record by a polynomial c_2 t² + ... + c_degree t^degree (constant and
        linear terms fixed at zero) in the least-squares sense over the samples, and
        subtract its second derivative from the acceleration samples. The fit uses the
        exact displacement of the sampled (piecewise-linear) second derivative, which
        equals c_k t^k up to O(dt²); with it the correction is exactly consistent with
        the record's closed forms: the corrected displacement is the residual of the fit
        (orthogonal to t², ..., t^degree at the samples), correcting twice changes
        nothing, and an added trend c_2 t² + ... + c_degree t^degree in displacement is
        removed to rounding.
      * ``"mean"``: subtract the mean acceleration of the pre-event window [0, pre_event]
        [s] (all samples when ``pre_event`` is None), as Boore & Bommer (2005) recommend
        for records with pre-event memory.
      * ``"none"``: the record unchanged (a copy).

    Args:
        record: a :class:`~blockdae.Record`.
        method: "polynomial", "mean" or "none".
        degree: highest power of t in the displacement fit, 2..12 [-] (polynomial only).
        pre_event: length of the pre-event window [s] (mean only).

    Returns:
        A new Record with the same dt, name, start time and metadata (which gains
        ``baseline``: the method).
    """
    if not isinstance(record, Record):
        raise TypeError(f"record must be a bd.Record, got {type(record).__name__}")
    if method not in METHODS:
        raise ValueError(f"method = {method!r}; method must be one of {METHODS}")
    a = np.array(record.acceleration_samples, dtype=float)

    def corrected(samples):
        return Record(samples, record.dt, record.name, record.start_time, units="m/s2", check_peak=False,
                      metadata={**record.metadata, "baseline": method})
    if method == "none":
        return corrected(a)
    if method == "mean":
        if pre_event is None:
            window = a
        else:
            pre_event = float(_checks.array("pre_event", pre_event, "s", low=0.0, low_open=True))
            window = a[: int(np.floor(pre_event / record.dt + 1e-9)) + 1]
        return corrected(a - window.mean())
    if not (isinstance(degree, (int, np.integer)) and 2 <= degree <= 12):
        raise ValueError(f"degree = {degree!r}; degree must be an integer from 2 to 12 [-]")
    return corrected(a - polynomial_trend(record, degree)[0])


def polynomial_trend(record, degree=6):
    """(acceleration trend at the samples [m/s²], its exact displacement [m], coefficients).

    The least-squares fit of the record's displacement at the samples by the exact
    displacements of the sampled accelerations k (k - 1) c_k t^(k-2), k = 2..degree
    (Ancheta et al. 2013 with the constant and linear terms fixed at zero). Times are
    scaled by the duration for conditioning; ``coefficients[k - 2]`` is c_k [m/s^k].
    """
    t = record.times
    scale = max(record.duration, record.dt)
    x = t / scale
    d = record.displacement(t)
    powers = np.arange(2, degree + 1)
    # sampled second derivatives of (t/scale)^k and the displacement of their linear interpolant
    acc = powers * (powers - 1) * x[:, None] ** (powers - 2) / scale**2
    basis = np.stack([_displacement_samples(acc[:, j], record.dt) for j in range(powers.size)], axis=1)
    coeffs, *_ = np.linalg.lstsq(basis, d, rcond=None)
    return acc @ coeffs, basis @ coeffs, coeffs / scale**powers


def _displacement_samples(a, dt):
    """Displacement at the samples of the piecewise-linear acceleration ``a`` from rest [m]."""
    dv = 0.5 * dt * (a[:-1] + a[1:])
    v = np.concatenate([[0.0], np.cumsum(dv)])
    dx = dt * v[:-1] + dt**2 * (a[:-1] / 3.0 + a[1:] / 6.0)
    return np.concatenate([[0.0], np.cumsum(dx)])
