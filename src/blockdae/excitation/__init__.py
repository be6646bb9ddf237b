"""Base excitations a(t), v(t), x(t), their breakpoints and file readers."""

from ._analytic import Harmonic, RectangularPulse, SinePulse, TriangularPulse
from ._base import AbstractExcitation
from ._motion import BaseMotion
from .pieces import Pieces
from ._read_motion import read_motion
from ._read_record import read_record
from ._readers import STANDARD_GRAVITY
from ._record import Record
from ._record_set import RecordSet, read_records
from ._resample import resample
from ._record_checks import MAX_STEP_S, OFFSET_FRACTION, RESOLVING_STEP_S, RecordWarning
from ._plausibility import (AMBIGUOUS_PEAK, MAX_KY_G, MAX_PGA_G, MAX_PLAUSIBLE_DAMPING, PLAUSIBLE_HEIGHT_M,
                            PLAUSIBLE_PEAK_G, PLAUSIBLE_VS_M_S, UnitsWarning, check_peak_acceleration)
from ._scaling import pga_factor

__all__ = ["AMBIGUOUS_PEAK", "AbstractExcitation", "BaseMotion", "Harmonic", "MAX_KY_G", "MAX_PGA_G",
           "MAX_PLAUSIBLE_DAMPING", "MAX_STEP_S", "OFFSET_FRACTION", "PLAUSIBLE_HEIGHT_M", "PLAUSIBLE_PEAK_G",
           "PLAUSIBLE_VS_M_S", "Pieces", "RESOLVING_STEP_S", "Record", "RecordSet", "RecordWarning", "RectangularPulse",
           "STANDARD_GRAVITY", "SinePulse", "TriangularPulse", "UnitsWarning", "check_peak_acceleration", "pga_factor",
           "read_motion", "read_record", "read_records", "resample"]

# what the other packages of blockdae use
from ._fema import SETS
from ._formats import read_channels
from .pieces import accel, accel_int1, accel_int2, accel_rate, evaluate, monotone_rate, piece_direction, rebase
from ._readers import RECORD_SUFFIXES, record_files, record_name, unit_factor
from ._record import check_horizontal
from ._record_checks import offset_fraction, outside_blockdae
from ._record_set import with_metadata
from ._plausibility import check_column, check_finite_result, check_pga, ky_not_reached, warn_not_sliding
from ._scaling import PGA_ROUNDINGS, check_pga_rounding, pga_keyword
