"""Empirical regressions of sliding displacement (Jibson 2007; Saygili & Rathje 2008;
Rathje & Saygili 2009; Bray & Travasarou 2007; Bray & Macedo 2019), vectorised, with
units in the argument names; each returns an :class:`EmpiricalDisplacement` (median [m],
σ of ln D and the probability of negligible displacement) and warns
(:class:`ValidityWarning`) outside the range of the data it was fitted to, where that
range is known."""

from ._bray import bray_travasarou_2007
from ._bray_macedo import bray_macedo_2019
from ._common import EmpiricalDisplacement, ValidityWarning
from ._jibson import jibson_2007, jibson_2007_arias, jibson_2007_arias_pga, jibson_2007_m
from ._saygili_rathje import (rathje_saygili_2009_pga_m, saygili_rathje_2008_pga, saygili_rathje_2008_pga_arias,
                              saygili_rathje_2008_pga_pgv)

__all__ = ["EmpiricalDisplacement", "ValidityWarning", "bray_macedo_2019", "bray_travasarou_2007", "jibson_2007",
           "jibson_2007_arias", "jibson_2007_arias_pga", "jibson_2007_m", "rathje_saygili_2009_pga_m",
           "saygili_rathje_2008_pga", "saygili_rathje_2008_pga_arias", "saygili_rathje_2008_pga_pgv"]
