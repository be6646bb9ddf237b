"""docs/benchmarks.md's summary agrees with its details, and docs/verification.md lists
a guard for each figure it quotes."""

import pathlib
import re

DOCS = pathlib.Path(__file__).parents[1] / "docs"
#: a figure as the pages write it: a number (digits, a decimal point, thousands commas,
#: an exponent, a range) and, where it has one, its unit
FIGURE = re.compile(r"\d[\d,]*(?:\.\d+)?(?:e-?\d+)?(?:[-–]\d[\d,]*(?:\.\d+)?)? ?(?:×|x\b|%|ms|µs|s\b|cm)")
NUMBER = re.compile(r"\d[\d,]*(?:\.\d+)?(?:e-?\d+)?")


def _summary_and_details():
    text = (DOCS / "benchmarks.md").read_text(encoding="utf-8")
    head, rest = text.split("## In short", 1)
    summary, details = rest.split("\n## ", 1)
    rows = [line for line in summary.splitlines() if line.startswith("| ") and "---" not in line][1:]
    return rows, details


def test_the_summary_has_rows():
    rows, _ = _summary_and_details()
    assert len(rows) >= 5


def test_every_figure_of_the_summary_is_in_the_details():
    """Each number with a unit in the summary's result column appears, as written, in the
    sections below it (which paste what the scripts printed)."""
    rows, details = _summary_and_details()
    missing = []
    for row in rows:
        result = row.split("|")[2]
        for figure in FIGURE.findall(result):
            missing += [(row.split("|")[1].strip(), number) for number in NUMBER.findall(figure)
                        if number not in details]
    assert not missing, missing


def test_every_quoted_figure_of_verification_has_a_guard():
    """The list at the end of docs/verification.md names a guard (a test or a benchmark
    script) on every row, with the measured value and the bar."""
    text = (DOCS / "verification.md").read_text(encoding="utf-8")
    listing = text.split("## Every figure and its guard", 1)[1]
    rows = [line for line in listing.splitlines() if line.startswith("| ") and "---" not in line][1:]
    rows = [row for row in rows if not row.startswith("| **")]  # section headings
    assert len(rows) >= 40
    for row in rows:
        figure, measured, bar, guard, _why = (cell.strip() for cell in re.split(r"(?<!\\)\|", row.strip("|")))
        assert figure and measured and bar, row
        assert re.search(r"`(tests|benchmarks)/\w+\.py", guard), row
