"""``blockdae rocking`` with the complete block (the default contact where its backends run
it): the command prints what ``bd.simulate`` gives for a FreeStandingBlock on the same
record (its events, slip, overturning and energy residual), and picks Housner's block only
where an option asks for it."""

import json

import pytest

import blockdae as bd
from blockdae.cli._main import main
from blockdae.rocking import FreeStandingBlock
from conftest import sample_record_paths

G = bd.STANDARD_GRAVITY
BLOCK = ["--b", 0.2, "--h", 0.8, "--mu", 0.3, "--mu-kinetic", 0.25, "--pga", 0.4, "--t-end", 6]


def _kobe_path():
    return next(p for p in sample_record_paths() if p.name.startswith("Kobe_1995_TAK-090"))


def _run(argv, capsys, status=0):
    assert main(["--no-cache", "rocking", "--units", "g", *map(str, argv)]) == status
    return capsys.readouterr()


@pytest.fixture(scope="module")
def api():
    """The API's run: b = 0.2 m, h = 0.8 m, mu_s = 0.3, mu_k = 0.25 under Kobe TAK-090 at
    0.4 g for 6 s on the compiled engine, the default (its pivot slips, it strikes three times
    and overturns)."""
    record = bd.read_record(_kobe_path(), units="g")
    record = record.scaled(0.4 * G / record.peak_acceleration)
    return bd.simulate(FreeStandingBlock(b=0.2, h=0.8, mu=0.3, mu_kinetic=0.25), record, t_end=6.0)


def test_the_complete_block_is_the_default_and_its_json_is_the_api(api, capsys):
    found = json.loads(_run([_kobe_path(), *BLOCK, "--json"], capsys).out)
    assert found["contact"] == "complete" and found["backend"] == "compiled"
    assert [(e["t_s"], e["kind"]) for e in found["events"]] == [(e.t, e.kind) for e in api.events]
    assert {"slip", "impact", "overturn"} <= {e.kind for e in api.events}
    assert found["event_counts"]["impact"] == len(api.impacts) >= 1
    assert found["overturn_time_s"] == api.overturn_time and found["final_slip_m"] == api.final_slip
    assert found["energy_residual_J_kg"] == api.energy_residual <= 1e-8 * found["energy_scale_J_kg"]


def test_the_text_reports_events_slip_overturn_and_energy_with_units(api, capsys):
    text = _run([_kobe_path(), *BLOCK], capsys).out
    assert "block (complete contact): b = 0.2 m, h = 0.8 m" in text and "mu_k = 0.25 [-]" in text
    counts = {kind: len(api.events_of(kind)) for kind in ("slip", "impact", "overturn")}
    assert all(f"{kind} {n}" in text.split("events: ")[1].splitlines()[0] for kind, n in counts.items())
    assert f"slip at t_end = {api.final_slip:+.6f} m" in text
    assert f"overturned at t = {api.overturn_time:.6f} s" in text
    assert f"energy balance: residual {api.energy_residual:.3e} J/kg of a scale {api.energy_scale:.3e} J/kg" in text
    assert sum(line.startswith("  t = ") for line in text.splitlines()) == len(api.events)


@pytest.mark.parametrize("options", [["--linearised"], ["--restitution", 0.8], ["--strict"]])
def test_options_of_housners_block_choose_it_and_refuse_the_complete_one(options, capsys):
    """--linearised, --restitution or --strict choose Housner's block by default; with --contact complete they are a usage error naming them."""
    argv = [_kobe_path(), "--b", 0.2, "--h", 0.8, "--mu", 0.6, "--pga", 0.4, "--t-end", 2, *options]
    assert json.loads(_run([*argv, "--json"], capsys).out)["contact"] == "housner"
    err = _run([*argv, "--contact", "complete"], capsys, status=2).err
    assert f"--contact complete: {options[0]}" in err and "Housner's block only" in err


def test_a_kinetic_friction_above_the_static_is_refused_by_name(capsys):
    err = _run([_kobe_path(), "--b", 0.2, "--h", 0.8, "--mu", 0.3, "--mu-kinetic", 0.4], capsys, status=2).err
    assert "mu_kinetic=0.4" in err
