"""Physical constants shared by every model and reader."""

#: standard gravity [m/s²]: the default g of every model and the value of the unit "g"
STANDARD_GRAVITY = 9.80665


def length_units(g) -> tuple[str, str]:
    """The units (length, velocity) of a set-up whose gravity is ``g`` [m/s²]: ("m", "m/s"),
    or ("g s²", "g s") where g = 1 (a dimensionless set-up, as Elms's: accelerations are
    coefficients of g, so lengths are in g × s² and velocities in g × s)."""
    return ("g s²", "g s") if g == 1 else ("m", "m/s")


def column_suffixes(g) -> tuple[str, str, str]:
    """The column-name suffixes (length, velocity, acceleration) of a table of a set-up whose
    gravity is ``g`` [m/s²]: ("m", "m_s", "m_s2"), or ("g_s2", "g_s", "g") where g = 1 (see
    :func:`length_units`)."""
    return ("g_s2", "g_s", "g") if g == 1 else ("m", "m_s", "m_s2")
