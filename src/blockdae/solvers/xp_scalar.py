"""The array namespace ``xp`` of the shared closed forms, for scalars inside numba.

:mod:`._closed_form`, :mod:`blockdae.sliding` and :mod:`blockdae.excitation.pieces`
call ``xp.where``, ``xp.sin``, ...; the numba engine passes this module as ``xp``.
"""

import math

import numba
import numpy as np

abs = np.abs
cos = math.cos
maximum = np.maximum
minimum = np.minimum
sign = np.sign
sin = math.sin
sqrt = math.sqrt


@numba.njit(inline="always")
def where(condition, x, y):
    """``x`` if ``condition`` else ``y`` (scalars)."""
    return x if condition else y
