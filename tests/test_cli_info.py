"""``blockdae info FILE...`` (issue 24): what the readers understood of each file; bad files
listed at the end with their errors, exit status 1."""

import numpy as np
from record_formats import SAMPLES, cosmos_block, esm, knet

from blockdae.cli._main import main
from blockdae.excitation import STANDARD_GRAVITY


def test_info_prints_what_was_read_and_lists_bad_files_at_the_end(tmp_path, capsys):
    good = tmp_path / "IT.NRC.HNE.ASC"
    good.write_text(esm())
    three = tmp_path / "three.v2"
    three.write_text(cosmos_block(orientation=90) + cosmos_block(orientation=400))
    bad = tmp_path / "bad.NS"
    bad.write_text(knet(frequency="50Hz"))
    status = main(["info", str(bad), str(good), str(three), str(tmp_path / "missing.csv")])
    out, err = capsys.readouterr()
    assert status == 1
    peak = float(np.max(np.abs(SAMPLES))) * 0.01  # the fixtures' peak [m/s²]
    block = out.split(str(good))[1].split(str(three))[0]
    for label, value in (("format", "ESM"), ("units as read", "cm/s2"), ("time step [s]", "0.01"), ("samples", "200"),
                         ("duration [s]", "1.99"), ("component", "HNE"), ("station", "IT.NRC"),
                         ("event", "EMSC-20161030_0000029"),
                         ("peak", f"{peak / STANDARD_GRAVITY:.4g} g = {peak:.4g} m/s²")):
        assert f"  {label:<14} {value}\n" in block
    assert out.count(str(three)) == 2 and "component      090" in out and "component      Up" in out
    assert str(bad) not in out
    lines = err.splitlines()
    assert lines[0] == "blockdae: 2 of 4 files failed:"
    assert lines[1].startswith(f"  {bad}, line 12: 'Duration Time(s)  2': 200 samples at 50Hz")
    assert lines[2] == f"  {tmp_path / 'missing.csv'}: no such file"


def test_info_all_good_exits_zero(tmp_path, capsys):
    path = tmp_path / "r.csv"
    path.write_text("time (s), acc (g)\n0, 0.1\n0.02, -0.2\n")
    assert main(["info", str(path)]) == 0
    out = capsys.readouterr().out
    assert "  format         table\n" in out and "  time step [s]  0.02\n" in out and "  units as read  g\n" in out
