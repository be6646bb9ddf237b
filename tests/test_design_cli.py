"""``blockdae design``: its printed numbers are those of blockdae.design called on the same
record files (read by bd.read_record), and bad input ends with a usage error."""

import re

import numpy as np
import pytest

import blockdae as bd
import blockdae.design as dz
from blockdae.cli import main
from test_design import RECORDS


@pytest.fixture
def folder(tmp_path):
    for name, record in RECORDS.items():
        t = np.arange(record.acceleration_samples.size) * record.dt
        np.savetxt(tmp_path / f"{name.replace(' ', '_')}.csv", np.c_[t, record.acceleration_samples / 9.80665],
                   delimiter=",", header="time (s), acc (g)", comments="")
    return tmp_path


def test_design_prints_the_study_of_the_files(folder, capsys):
    assert main(["design", str(folder), "--param", "ky=lognormal:0.15:0.3", "--pga", "0.4", "--threshold", "0.1",
                 "--runs", "16", "--allowable", "0.05", "--target", "0.1", "--csv", str(folder / "out.csv")]) == 0
    out = capsys.readouterr().out
    records = {path.stem: bd.read_record(path) for path in sorted(folder.glob("*.csv")) if path.stem != "out"}
    parameters = {"ky": dz.LogNormal(mean=0.15, cov=0.3)}
    study = dz.exceedance(records, dz.Rigid(), parameters, pga=0.4, threshold=0.1, runs=16)
    assert f"P(D > 0.1 m) = {study.probability:.4f}" in out
    design = dz.mean_ky_for_probability(records, dz.Rigid(), parameters, 0.05, 0.1, pga=0.4, runs=64)
    assert re.search(rf"<= 0.1: {design.mean_ky_g:.4f} g", out)
    assert (folder / "out.csv").read_text().startswith("run,record,pga_g,ky_g,D_m")


def test_design_runs_the_block_on_a_plane(folder, capsys):
    assert main(["design", str(folder), "--model", "planar", "--param", "mu=lognormal:0.15:0.3", "--param",
                 "bias_x=-0.03", "--pga", "0.4", "--threshold", "0.05", "--runs", "8", "--allowable", "0.05",
                 "--target", "0.2"]) == 0
    out = capsys.readouterr().out
    records = {path.stem: bd.read_record(path) for path in sorted(folder.glob("*.csv"))}
    parameters = {"mu": dz.LogNormal(mean=0.15, cov=0.3), "bias_x": -0.03}
    study = dz.exceedance(records, dz.Planar(), parameters, pga=0.4, threshold=0.05, runs=8)
    assert f"P(D > 0.05 m) = {study.probability:.4f}" in out
    design = dz.mean_ky_for_probability(records, dz.Planar(), parameters, 0.05, 0.2, pga=0.4, runs=64)
    assert re.search(rf"mean mu for P\(D > 0.05 m\) <= 0.2: {design.mean:.4f} \[-\]", out)


@pytest.mark.parametrize("argument, message", [("ky=gamma:1:2", "KIND one of"), ("ky=lognormal:0.1", "KIND one of")])
def test_a_bad_parameter_is_a_usage_error(folder, capsys, argument, message):
    assert main(["design", str(folder), "--param", argument, "--threshold", "0.1"]) == 2
    assert message in capsys.readouterr().err


def test_a_missing_parameter_is_named(folder, capsys):
    assert main(["design", str(folder), "--model", "flexible", "--param", "ky=0.1", "--threshold", "0.1",
                 "--runs", "2"]) == 2
    assert "needs the parameters ['height', 'vs']" in capsys.readouterr().err


def test_design_resumes_from_its_checkpoint(folder, capsys):
    arguments = ["design", str(folder), "--param", "ky=lognormal:0.15:0.3", "--pga", "0.4", "--threshold", "0.1",
                 "--runs", "8", "--checkpoint", str(folder.parent / "saved")]
    assert main(arguments) == 0
    first = capsys.readouterr().out.splitlines()[1:]
    assert len(list((folder.parent / "saved").glob("block-*.csv"))) == 1
    assert main(arguments) == 0
    assert capsys.readouterr().out.splitlines()[1:] == first  # the timing line aside
    assert main(arguments[:-1] + [str(folder)]) == 2  # a folder of record files is no checkpoint
    assert "not a new or an empty folder" in capsys.readouterr().err
