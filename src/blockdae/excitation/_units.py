"""Units of acceleration samples: names, factors to m/s², the units a file's header names
(the rules on which values are plausible are :mod:`._plausibility`'s)."""

import re

from ..units import STANDARD_GRAVITY

_UNITS = {"g": "g", "m/s2": "m/s2", "m/s^2": "m/s2", "m/s²": "m/s2",
          "cm/s2": "cm/s2", "cm/s^2": "cm/s2", "cm/s²": "cm/s2", "gal": "cm/s2"}
_FACTORS = {"m/s2": 1.0, "cm/s2": 0.01}
_SYMBOLS = {"g": "g", "m/s2": "m/s²", "cm/s2": "cm/s²"}
# units in a header's words: m/s2, m/s^2, m/s**2, m/s², m/sec2, m/s/s, cm/..., gal(s); g only where
# it cannot be a letter of a name: "(g)", "[g's]", "in g", "units: g", "acc_g"
_NO_LETTER_BEFORE, _NO_LETTER_AFTER = r"(?<![a-z0-9])", r"(?![a-z0-9/*^²])"
_PER_SECOND_SQUARED = r"\s*/\s*s(?:ec)?\s*(?:\^\s*2|\*\*\s*2|²|2|/\s*s(?:ec)?)"
_HEADER_UNIT_WORDS = (
    ("cm/s2", re.compile(_NO_LETTER_BEFORE + r"cm" + _PER_SECOND_SQUARED + _NO_LETTER_AFTER, re.I)),
    ("m/s2", re.compile(_NO_LETTER_BEFORE + r"m" + _PER_SECOND_SQUARED + _NO_LETTER_AFTER, re.I)),
    ("cm/s2", re.compile(_NO_LETTER_BEFORE + r"gals?" + _NO_LETTER_AFTER, re.I)),
    ("g", re.compile(r"(?:[(\[]\s*g(?:'?s)?\s*[)\]]"  # (g), [g's]
                     r"|(?:\bin\s|\bunits?\s*(?:of\s|:|=)?|_)\s*g(?:'?s)?(?![a-z0-9/]))", re.I)))  # in g, units: g, acc_g
_BRACKETED_RATIO = re.compile(r"[(\[]\s*([^()\[\]]*/[^()\[\]]*?)\s*[)\]]")  # "(m/s)", "[cm/s2]"


def canonical_units(units: str) -> str:
    """The name "g", "m/s2" or "cm/s2" of ``units`` (also "gal", "m/s^2", "cm/s²", ...)."""
    key = str(units).strip().lower()
    if key not in _UNITS:
        raise ValueError(f"units={units!r} is unknown; use one of {sorted(_UNITS)}")
    return _UNITS[key]


def unit_factor(units: str, g: float = STANDARD_GRAVITY) -> float:
    """Factor converting ``units`` to m/s² ("g", "m/s2", "cm/s2" or "gal"); one g is ``g`` [m/s²]."""
    return _FACTORS.get(canonical_units(units), g)


def units_named(text: str) -> tuple[list, list]:
    """(the canonical units "g", "m/s2", "cm/s2" that ``text``, a header line, names in words,
    e.g. ``time (s), acceleration (m/s2)``, ``Acceleration in m/s2``, ``acc [cm/sec2]``,
    ``(gal)``, ``(g's)``, in the order they appear; the bracketed ratios in it that are no
    acceleration unit, e.g. "m/s")."""
    found = {}
    for units, pattern in _HEADER_UNIT_WORDS:
        for match in pattern.finditer(text):
            found.setdefault(units, match.start())
        text = pattern.sub(lambda match: " " * len(match.group()), text)  # "cm/s2" not read again as "m/s2"
    others = [ratio for ratio in _BRACKETED_RATIO.findall(text) if ratio.strip()]
    return sorted(found, key=found.get), others


#: the time units a table's header may name, and their factors to seconds
TIME_UNITS = {"s": 1.0, "sec": 1.0, "secs": 1.0, "second": 1.0, "seconds": 1.0,
              "ms": 1e-3, "msec": 1e-3, "millisecond": 1e-3, "milliseconds": 1e-3}
# a time column's name and its units: "time (ms)", "t [s]" (any bracketed word: refused if unknown);
# "time_ms", "time in seconds" (known units only)
_BRACKETED_TIME = re.compile(r"\b(?:time|t)\s*[(\[]\s*([a-zµ]+)\s*[)\]]", re.I)
_WORDED_TIME = re.compile(r"\b(?:time|t)(?:_|\s+in\s+)([a-z]+)\b", re.I)


def time_units_named(text: str) -> tuple[str, float] | None:
    """(the time unit, its factor to seconds) that ``text``, a header line, names for its
    time column ("time (ms)", "t [s]", "time_ms", "Time in seconds"); None if it names none.
    A ValueError where a bracketed unit of time is none of :data:`TIME_UNITS` ("time (min)")."""
    found = _BRACKETED_TIME.search(text)
    if found is None:
        found = _WORDED_TIME.search(text)
        if found is None or found.group(1).lower() not in TIME_UNITS:
            return None
    unit = found.group(1)
    if unit.lower() not in TIME_UNITS:
        raise ValueError(f"the header names the time in {unit!r}, not a unit read here (s or ms): "
                         "convert the time column to seconds")
    return unit, TIME_UNITS[unit.lower()]
