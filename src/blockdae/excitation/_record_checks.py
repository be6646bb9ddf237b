"""The rules on a record file's sample step and offset, one each for every reader and command:
a step above :data:`MAX_STEP_S` is refused unless confirmed, one above :data:`RESOLVING_STEP_S`
warned about; a mean above :data:`OFFSET_FRACTION` of the peak is warned about."""

import sys
import warnings

import numpy as np

#: sample steps [s] above this are refused unless confirmed: times in ms, or a sample index
MAX_STEP_S = 0.1
#: sample steps [s] above this give fewer than 4 samples per 0.1 s period: warned about
RESOLVING_STEP_S = 0.025
#: a record whose |mean| is above this fraction of its peak |a| is warned about (an offset)
OFFSET_FRACTION = 0.05
#: how a caller confirms a step above :data:`MAX_STEP_S` (Python; the command line's flag)
CONFIRM_STEP = "check_step=False (command line: --accept-step)"
#: how a caller removes an offset (Python; the command line's flags)
REMOVE_OFFSET = ("remove_mean=True or bd.motions.baseline_corrected(record) (command line: --remove-mean or "
                 "--baseline polynomial)")


class RecordWarning(UserWarning):
    """A record that reads but may mislead: a step too coarse to resolve it, or an offset
    (a mean that is a sizeable fraction of its peak)."""


def check_step(dt: float, source: str, check_step: bool = True, time_column: bool = False):
    """The step rule: ValueError naming ``source`` (the file, line or field that sets the step)
    if ``dt`` [s] is above :data:`MAX_STEP_S`, unless ``check_step`` is False, naming the likely
    cause where the step comes from a ``time_column`` (milliseconds, sample numbers); a
    :class:`RecordWarning` if it is above :data:`RESOLVING_STEP_S`."""
    if check_step and dt > MAX_STEP_S:
        in_ms, numbered = f"times in milliseconds ({dt:g} ms = {dt / 1000:g} s)", "a column of sample numbers"
        causes = [numbered, in_ms] if dt == 1 else [in_ms, numbered] if float(dt).is_integer() else [in_ms]
        fix = (f"{' or '.join(causes)}? Give the times in seconds, or {CONFIRM_STEP} to accept it" if time_column
               else f"is the file an accelerogram? {CONFIRM_STEP} accepts it")
        raise ValueError(f"{source}: sample step dt = {dt:g} s is implausible for an accelerogram (above "
                         f"{MAX_STEP_S:g} s): {fix}")
    if dt > RESOLVING_STEP_S:
        warnings.warn(f"{source}: sample step dt = {dt:g} s resolves periods down to {4 * dt:g} s only (4 samples "
                      f"a period), not the periods of 0.1 s an accelerogram holds (dt <= {RESOLVING_STEP_S:g} s)",
                      RecordWarning, stacklevel=outside_blockdae())


def offset_fraction(samples) -> float:
    """|mean| / peak |a| of ``samples`` [-], shape (n,) or (n, k) (the largest column's); 0 for zeros."""
    samples = np.asarray(samples, dtype=float).reshape(len(samples), -1)
    peak = np.max(np.abs(samples), axis=0)
    mean = np.abs(samples.mean(axis=0))
    return float(np.max(np.divide(mean, peak, out=np.zeros_like(mean), where=peak > 0)))


def check_offset(samples, source: str):
    """The offset rule: a :class:`RecordWarning` naming ``source`` and the fix if the mean of
    ``samples`` is above :data:`OFFSET_FRACTION` of their peak."""
    fraction = offset_fraction(samples)
    if fraction > OFFSET_FRACTION:
        warnings.warn(f"{source}: the samples' mean is {100 * fraction:.3g} % of their peak (above "
                      f"{100 * OFFSET_FRACTION:g} %): an offset that slides a block one way; remove it with "
                      f"{REMOVE_OFFSET}", RecordWarning, stacklevel=outside_blockdae())


def outside_blockdae() -> int:
    """The ``stacklevel`` of a warning that names the first caller outside blockdae."""
    frame, level = sys._getframe(1), 1
    while frame is not None and frame.f_globals.get("__name__", "").startswith("blockdae."):
        frame, level = frame.f_back, level + 1
    return level
