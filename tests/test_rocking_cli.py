"""``blockdae rocking``: the command prints what ``bd.simulate`` gives on the same record
(the API's numbers), for a block that rocks and one that slides."""

import json

import blockdae as bd
from blockdae.cli._main import main
from conftest import sample_record_paths

G = bd.STANDARD_GRAVITY


def _kobe_path():
    return next(p for p in sample_record_paths() if p.name.startswith("Kobe_1995_TAK-090"))


def _run(argv, capsys, status=0):
    assert main(["--no-cache", "rocking", "--units", "g", *map(str, argv)]) == status
    return capsys.readouterr()


def test_rocking_block_json_is_the_api(capsys):
    """The linearised block under Kobe TAK-090 at 0.4 g: the same impacts, max |theta|/alpha
    and rest or overturn as bd.simulate on the compiled closed form."""
    path = _kobe_path()
    found = json.loads(_run([path, "--b", 0.2, "--h", 0.8, "--mu", 0.6, "--linearised", "--pga", 0.4, "--json"],
                            capsys).out)
    record = bd.read_record(path, units="g")
    record = record.scaled(0.4 * G / record.peak_acceleration)
    block = bd.RockingBlock(b=0.2, h=0.8, mu=0.6, linearised=True)
    solution = bd.simulate(block, record, backend="exact")
    assert found["backend"] == "exact" and found["regime"] == "rock"
    assert found["max_theta_over_alpha"] == solution.max_theta_over_alpha > 0
    assert found["overturned"] == solution.overturned
    assert [i["t_s"] for i in found["impacts"]] == list(solution.impact_times)
    text = _run([path, "--b", 0.2, "--h", 0.8, "--mu", 0.6, "--linearised", "--pga", 0.4], capsys).out
    assert f"max |theta| / alpha = {solution.max_theta_over_alpha:.6f} [-]" in text


def test_exact_equation_runs_compiled(capsys):
    """Housner's block (--contact housner) with the exact equation under Kobe TAK-090 at
    0.4 g runs on the compiled engine by default: the impacts of bd.simulate there."""
    path = _kobe_path()
    found = json.loads(_run([path, "--b", 0.2, "--h", 0.8, "--mu", 0.6, "--pga", 0.4, "--contact", "housner", "--json"],
                            capsys).out)
    record = bd.read_record(path, units="g")
    solution = bd.simulate(bd.RockingBlock(b=0.2, h=0.8, mu=0.6), record.scaled(0.4 * G / record.peak_acceleration),
                           backend="compiled")
    assert found["backend"] == "compiled" and len(found["impacts"]) >= 2
    assert [i["t_s"] for i in found["impacts"]] == list(solution.impact_times)


def test_sliding_block_says_it_slides(capsys):
    """Housner's block with mu < b/h slides, and u(t_end) is the SlidingBlock's."""
    path = _kobe_path()
    text = _run([path, "--b", 0.5, "--h", 0.6, "--mu", 0.3, "--t-end", 10, "--contact", "housner"], capsys).out
    sliding = bd.simulate(bd.SlidingBlock(mu=0.3), bd.read_record(path, units="g"), t_end=10.0, backend="cvode")
    assert "slides: mu < b/h" in text
    assert f"u(t_end) = {sliding.displacement:+.6f} m" in text


def test_bad_geometry_is_a_usage_error(capsys):
    """A negative half-width is refused by its flag, with the usage status 2."""
    assert main(["--no-cache", "rocking", str(_kobe_path()), "--units", "g", "--b", "-1", "--h", "1",
                 "--mu", "0.5"]) == 2
    assert "--b" in capsys.readouterr().err


def test_housners_contact_limits_are_printed_and_in_the_json(capsys):
    """Where Housner's assumption breaks (the linearised block under Kobe TAK-090 at 0.4 g:
    a slip limit, then a lift limit, before it overturns) the command lists each limit as
    bd.simulate locates it, in the text and the JSON, without a warning."""
    path = _kobe_path()
    argv = [path, "--b", 0.2, "--h", 0.8, "--mu", 0.6, "--linearised", "--pga", 0.4]
    record = bd.read_record(path, units="g")
    record = record.scaled(0.4 * G / record.peak_acceleration)
    limits = bd.simulate(bd.FreeStandingBlock(b=0.2, h=0.8, mu=0.6, contact="housner", linearised=True), record,
                         backend="exact").contact_events
    assert [limit.kind for limit in limits] == ["slip_limit", "lift_limit"]
    found = _run([*argv, "--json"], capsys)
    assert [(c["t_s"], c["kind"], c["F_m_s2"], c["N_m_s2"]) for c in json.loads(found.out)["contact_limits"]] == \
        [(c.t, c.kind, c.force, c.normal) for c in limits]
    text = _run(argv, capsys)
    assert "warning" not in text.out + text.err
    assert f"contact limits: {len(limits)} (Housner's pivot holds through them" in text.out
    assert all(f"  {limit}" in text.out.splitlines() for limit in limits)
