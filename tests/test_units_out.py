"""--units-out: the displacements of blockdae newmark and blockdae flexible in cm, mm, in or
ft, named so, equal to the metres' row by row (one inch is 0.0254 m, one foot 0.3048 m)."""

import csv
import json

import pytest

from blockdae.cli import main
from conftest import sample_record_paths

KOBE = next(p for p in sample_record_paths() if "Kobe" in str(p))


def _newmark_csv(tmp_path, unit):
    out = tmp_path / f"{unit}.csv"
    assert main(["--no-cache", "newmark", str(KOBE), "--ky", "0.1", "0.2", "--derivative", "--units-out", unit,
                 "--csv", str(out)]) == 0
    with open(out) as stream:
        return list(csv.DictReader(stream))


@pytest.mark.parametrize("unit, metres", [("cm", 0.01), ("mm", 0.001), ("in", 0.0254), ("ft", 0.3048)])
def test_newmark_rows_in_another_length_unit(tmp_path, capsys, unit, metres):
    base, other = _newmark_csv(tmp_path, "m"), _newmark_csv(tmp_path, unit)
    assert f"downslope displacement D >= 0 [{unit}]" in capsys.readouterr().out
    for row_m, row in zip(base, other):
        assert row["ky_g"] == row_m["ky_g"]
        for name in ("normal", "inverse", "mean", "max"):
            assert float(row[f"{name}_{unit}"]) == pytest.approx(float(row_m[f"{name}_m"]) / metres, rel=1e-14)
        assert float(row[f"dD_dky_normal_{unit}_per_g"]) == \
            pytest.approx(float(row_m["dD_dky_normal_m_per_g"]) / metres, rel=1e-14)
        assert not any(key.endswith("_m") for key in row)


def test_flexible_rows_in_cm(capsys):
    arguments = ["--no-cache", "flexible", str(KOBE), "--ky", "0.1", "--height", "20", "--vs", "300", "--json"]
    assert main(arguments) == 0
    metres = json.loads(capsys.readouterr().out)["rows"][0]
    assert main([*arguments, "--units-out", "cm"]) == 0
    cm = json.loads(capsys.readouterr().out)["rows"][0]
    assert cm["normal_cm"] == pytest.approx(100 * metres["normal_m"], rel=1e-14)
    assert cm["inverse_cm"] == pytest.approx(100 * metres["inverse_m"], rel=1e-14)
    assert "normal_m" not in cm and cm["vs_final_m_s"] == metres["vs_final_m_s"]
