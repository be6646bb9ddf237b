"""The web app without a browser: the form's checks (each message names the field and the
value), the records' rules (a file that does not state its units asks for them, with its
peak in each unit; a bad file is named with its line), the analyses against the library's
own calls (the reference: bd.newmark and bd.flexible on the same inputs), the design
page's form and studies against blockdae.design called directly, a cancelled run,
and ``blockdae app`` serving the page on 127.0.0.1; through HTTP as a browser's pages
call it: two pages of one app each with its own records and results, a session ended and
its files removed, forged Host and Origin headers and a missing token refused, odd file
names and a file above the size limit refused by name while the rest of the batch loads,
the temporary folder removed on SIGTERM as on Ctrl+C. Skipped without the app extra."""

import io
import os
import re
import signal
import socket
import subprocess
import sys
import threading
import time
import urllib.request

import numpy as np
import pandas as pd
import pytest

import blockdae as bd
from blockdae import design
from app_pages import Page, data_url, request
from conftest import load_sample_record, sample_record_paths

pytest.importorskip("dash", reason="the app extra is not installed: pip install 'blockdae[app]'")

from blockdae.app._analysis import FieldError, Settings, analyse, case_solution, parse_settings  # noqa: E402
from blockdae.app._records import load, unit_choices  # noqa: E402
from blockdae.app._design import DesignJob, parse_design, parse_inverse  # noqa: E402
from blockdae.app._session import FILE_LIMIT_BYTES, Job, SessionEnded, Sessions  # noqa: E402
from blockdae.app import LocalApp  # noqa: E402

FORM = {"method": "coupled", "ky_mode": "direct", "ky": "0.1", "height": "20", "vs": "300", "damping": "0.05",
        "reference_strain": "0.0005", "pga": "", "polarity": "both"}


@pytest.mark.parametrize("change, message", [
    ({"height": "abc"}, "slope height H [m]: 'abc' is not a number"),
    ({"vs": "-300"}, "shear-wave velocity Vs [m/s]: '-300' must be > 0"),
    ({"ky": "0.1, 9.81"}, "ky [g]: '9.81' is above 1 g: a ky in m/s²? (0.05 g is 0.49 m/s²)"),
    ({"ky": ""}, "ky [g]: '' is empty: give one or more yield accelerations in g"),
    ({"pga": "2.94"}, "target PGA [g]: '2.94' is above 2 g: a PGA in m/s²? (0.3 g is 2.94 m/s²)"),
    ({"ky_mode": "safety", "factor_of_safety": "0.9", "thrust_angle": "25"},
     "factor of safety [-]: '0.9' must be > 1"),
    ({"ky_mode": "safety", "factor_of_safety": "1.2", "thrust_angle": "95"}, "thrust angle [°]: '95' must be < 90"),
    ({"ky_mode": "table", "ky_table": "0, 0.15\n0.5, 0.05\n0.5, 0.02"},
     "ky(D) table: '0, 0.15\\n0.5, 0.05\\n0.5, 0.02' is refused: KyTable: displacement_m must be strictly "
     "increasing; displacement_m[1] = 0.5 m, displacement_m[2] = 0.5 m"),
    ({"method": "equivalent-linear", "reference_strain": "0"}, "reference strain [-]: '0' must be > 0"),
])
def test_a_bad_field_is_named_with_its_value(change, message):
    with pytest.raises(FieldError) as err:
        parse_settings({**FORM, **change})
    assert str(err.value) == message


def test_the_form_gives_the_settings():
    """ky from a factor of safety and a thrust angle is (FS - 1) sin(alpha) (Jibson 1993);
    the rigid block takes no slope properties."""
    settings = parse_settings({**FORM, "method": "rigid", "ky_mode": "safety", "factor_of_safety": "1.2",
                               "thrust_angle": "30", "pga": "0.3", "polarity": "inverse"})
    assert settings == Settings("rigid", (pytest.approx(0.1, rel=1e-12),), pga=0.3, polarity="inverse")
    table = parse_settings({**FORM, "ky_mode": "table", "ky_table": "0, 0.15\n0.5: 0.05"}).ky
    assert table == bd.KyTable((0.0, 0.5), (0.15, 0.05))


def test_a_file_without_units_asks_for_them(tmp_path):
    """The peak is given in each unit; the file reads once the units are given; a one-column
    file asks for its step first; a bad file is named as the user named it, with its line."""
    path = tmp_path / "x"
    path.mkdir()
    path = path / "plain.csv"
    path.write_text("0.0, 0.01\n0.01, 0.2\n0.02, -0.15\n0.03, 0.02\n")
    waiting = load("plain.csv", path)
    assert (waiting.needs, waiting.record, waiting.raw_peak) == ("units", None, 0.2)
    assert unit_choices(0.2) == [("g", "g: peak 0.2 g"), ("m/s2", "m/s²: peak 0.2 m/s² = 0.02039 g"),
                                 ("cm/s2", "cm/s²: peak 0.2 cm/s² = 0.0002039 g")]
    read = load("plain.csv", path, units="cm/s2")
    assert read.needs is None and read.record.peak_acceleration == pytest.approx(0.002, rel=1e-12)
    column = tmp_path / "column.txt"
    column.write_text("0.01\n0.2\n-0.15\n")
    assert load("column.txt", column).needs == "step"
    assert load("column.txt", column, dt=0.01).needs == "units"
    bad = tmp_path / "x" / "bad.csv"
    bad.write_text("time (s), acceleration (g)\n0, 0.1\n0.01, abc\n")
    with pytest.raises(ValueError, match=r"^bad.csv, line 3: not a number in '0.01, abc'$"):
        load("bad.csv", bad)


def test_the_analyses_are_the_librarys():
    """Rigid: bd.newmark's D, mean and max; equivalent-linear: bd.flexible's row; the
    history drawn of a case ends at the table's D (for the equivalent-linear mass: the
    converged column is drawn)."""
    kobe = load_sample_record("Kobe_1995_TAK-090")
    rows, notes = analyse("kobe", kobe, Settings("rigid", (0.1, 0.2), pga=0.4))
    expected = bd.newmark({"kobe": kobe}, [0.1, 0.2], pga=0.4).to_dataframe()
    for column in ("pga_g", "ky_g", "normal_m", "inverse_m", "mean_m", "max_m"):
        np.testing.assert_array_equal([row[column] for row in rows], expected[column], err_msg=column)
    assert notes == []
    solution, _ = case_solution(kobe, Settings("rigid", (0.1, 0.2), pga=0.4), rows[1], "inverse")
    assert 0.0 - solution.displacement == pytest.approx(rows[1]["inverse_m"], rel=1e-12)
    settings = Settings("equivalent-linear", (0.1,), 20.0, 300.0, 0.05, 0.0005, polarity="normal")
    (row,), _ = analyse("kobe", kobe, settings)
    library = bd.flexible(kobe, 0.1, 20.0, 300.0, damping=0.05, equivalent_linear=True, reference_strain=0.0005,
                          polarity="normal").rows[0]
    assert row["normal_m"] == library["normal_m"] and np.isnan(row["inverse_m"])
    assert row["mean_m"] == row["max_m"] == row["normal_m"]
    solution, _ = case_solution(kobe, settings, row, "normal")
    assert solution.sliding_displacement == pytest.approx(row["normal_m"], rel=1e-9)


def test_a_ky_above_the_peak_is_noted():
    """The library's rule, against kmax (what drives the mass's slide): ky = 0.6 g above the
    PGA 0.5 g but below kmax slides, with no note; ky = 0.7 g above kmax does not, noted."""
    kobe = load_sample_record("Kobe_1995_TAK-090")
    (row,), notes = analyse("kobe", kobe, Settings("decoupled", (0.7,), 20.0, 300.0, 0.05, pga=0.5))
    assert row["max_m"] == 0.0
    assert notes == ["ky=0.7 g >= kmax = 0.6845 g: the mass does not slide, D = 0 m"]
    (row,), notes = analyse("kobe", kobe, Settings("decoupled", (0.6,), 20.0, 300.0, 0.05, pga=0.5))
    assert row["max_m"] > 0 and notes == []


def test_a_cancelled_run_stops_between_records(monkeypatch):
    """The first record blocks until the run is cancelled: the others are not run."""
    release = threading.Event()

    def analyse_slowly(name, record, settings):
        release.wait(10)
        return [{"record": name}], []

    monkeypatch.setattr("blockdae.app._session.analyse", analyse_slowly)
    kobe = load_sample_record("Kobe_1995_TAK-090")
    job = Job({"a": kobe, "b": kobe, "c": kobe}, Settings("rigid", (0.1,)))
    job.cancelled.set()
    release.set()
    assert job.finished.wait(10)
    assert (job.done, job.total, job.rows, job.errors) == (1, 3, [{"record": "a"}], [])


def test_the_command_serves_the_page_on_this_computer():
    """``blockdae app --no-browser`` prints its address on 127.0.0.1 with its token and serves
    the page (its cookie kept) and Dash's scripts from the installed wheel."""
    process = subprocess.Popen([sys.executable, "-m", "blockdae.cli", "app", "--no-browser"], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True)
    try:
        line = process.stdout.readline()
        url = re.fullmatch(r"blockdae app: ((http://127\.0\.0\.1:\d+/)\?token=[\w-]{40,}) \(Ctrl\+C stops it\)\n",
                           line)
        assert url, (line, process.stderr.read() if process.poll() is not None else "")
        browser = urllib.request.build_opener(urllib.request.HTTPCookieProcessor())
        page = browser.open(url[1], timeout=30).read().decode()
        assert "<title>blockdae</title>" in page
        scripts = re.findall(r'<script src="([^"]+)"', page)
        assert scripts and all(src.startswith("/") for src in scripts), scripts
        assert browser.open(url[2] + scripts[-1].lstrip("/"), timeout=30).status == 200
    finally:
        process.terminate()
        process.wait(30)


def test_a_port_in_use_is_named():
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        done = subprocess.run([sys.executable, "-m", "blockdae.cli", "app", "--no-browser", "--port", str(port)],
                              capture_output=True, text=True, timeout=120)
    assert done.returncode == 2
    assert done.stderr.startswith(f"blockdae: error: --port: port {port} on 127.0.0.1 is not free"), done.stderr


DESIGN = {"method": "rigid", "polarity": "normal", "ky_mean": "0.1", "ky_cov": "0.3", "height_mean": "20",
          "height_cov": "0", "vs_mean": "300", "vs_cov": "0.15", "damping": "0.05", "reference_strain": "0.0005",
          "pga": "0.3", "sampling": "sobol", "seed": "7", "rse": "", "halfwidth": "", "runs_per_block": "8",
          "max_runs": "16", "threshold": "0.05", "allowable": "0.05", "target": "0.2", "inverse_runs": "8"}


@pytest.mark.parametrize("change, message", [
    ({"ky_mean": "0.98x"}, "mean ky [g]: '0.98x' is not a number"),
    ({"ky_mean": "1.5"}, "mean ky [g]: '1.5' is above 1 g: a ky in m/s²? (0.05 g is 0.49 m/s²)"),
    ({"method": "coupled", "vs_cov": "-0.1"}, "cov of shear-wave velocity Vs [-]: '-0.1' must be >= 0"),
    ({"seed": "1.5"}, "seed: '1.5' is not an integer"),
    ({"runs_per_block": "12"}, "runs per block: '12' must be a power of 2 for Sobol samples (e.g. 16)"),
    ({"max_runs": "4"}, "at most runs: '4' must be >= 8"),
    ({"max_runs": "20"}, "at most runs: '20' must be a multiple of the runs per block (8) for Sobol samples"),
    ({"threshold": "0"}, "threshold displacement [m]: '0' must be > 0"),
])
def test_a_bad_design_field_is_named_with_its_value(change, message):
    with pytest.raises(FieldError) as err:
        parse_design({**DESIGN, **change})
    assert str(err.value) == message


def test_a_bad_inverse_field_is_named_with_its_value():
    settings = parse_design(DESIGN)
    for change, message in (({"target": "1"}, "target probability [-]: '1' must be < 1"),
                            ({"inverse_runs": "6"}, "samples per record: '6' must be a power of 2 for Sobol samples "
                                                    "(e.g. 64)")):
        with pytest.raises(FieldError) as err:
            parse_inverse({**DESIGN, **change}, settings)
        assert str(err.value) == message
    with pytest.raises(FieldError, match=r"^cov of ky \[-\]: '0' must be > 0 for the design inverse"):
        parse_inverse({**DESIGN, "ky_cov": "0"}, parse_design({**DESIGN, "ky_cov": "0"}))


def _finished(job):
    assert job.finished.wait(300)
    assert job.error is None, job.error
    return job.result


def test_the_design_form_gives_the_librarys_model_and_parameters():
    """Equivalent-linear: the coupled flexible mass with its iteration; a cov of 0 keeps the value fixed."""
    settings = parse_design({**DESIGN, "method": "equivalent-linear", "height_cov": "0", "polarity": "larger"})
    assert settings.model == design.Flexible("coupled", True, 0.0005, "larger")
    assert settings.parameters == {"ky": design.LogNormal(mean=0.1, cov=0.3), "height": 20.0,
                                   "vs": design.LogNormal(mean=300.0, cov=0.15), "damping": 0.05}


def test_the_design_is_the_librarys():
    """P(D > threshold), its interval and every sample of the page's study are those of
    design.exceedance called directly on the same records, parameters and seed; the
    design inverse's mean ky and each record's ky those of mean_ky_for_probability and
    ky_for_displacement; the analyses counted are the library's (2 records x 16 runs)."""
    records = {"kobe": load_sample_record("Kobe_1995_TAK-090"),
               "cape": load_sample_record("Cape_Mendocino_1992_PET-090")}
    settings = parse_design(DESIGN)
    result = _finished(job := DesignJob(records, settings, "exceedance"))
    expected = design.exceedance(records, design.Rigid(), {"ky": design.LogNormal(mean=0.1, cov=0.3)}, pga=0.3,
                                 threshold=0.05, seed=7, runs=16, runs_per_block=8, max_runs=16)
    pd.testing.assert_frame_equal(result.table, expected.table)
    assert (result.probability, result.probability_interval) == (expected.probability, expected.probability_interval)
    assert 0 < expected.probability < 1 and job.analyses == 32
    inverse = parse_inverse(DESIGN, settings)
    found = _finished(DesignJob(records, settings, "inverse", inverse))
    need = design.mean_ky_for_probability(records, design.Rigid(), {"ky": design.LogNormal(mean=0.1, cov=0.3)},
                                          0.05, 0.2, pga=0.3, runs=8, seed=7)
    assert found.design.mean_ky_g == need.mean_ky_g
    assert found.per_record == [(name, 0.3, design.ky_for_displacement(record, design.Rigid(), {}, 0.05, pga=0.3))
                                for name, record in records.items()]


def test_a_cancelled_design_stops_at_its_next_batch():
    """A fixed 4096 runs on one record, cancelled once analyses are counted: it stops with no result."""
    settings = parse_design({**DESIGN, "max_runs": "4096", "runs_per_block": "8"})
    job = DesignJob({"kobe": load_sample_record("Kobe_1995_TAK-090")}, settings, "exceedance")
    while job.analyses == 0 and not job.finished.is_set():
        job.finished.wait(0.01)
    job.cancelled.set()
    assert job.finished.wait(60)
    assert job.result is None and job.error is None and 0 < job.analyses < 4096


def test_the_d_ky_plot_has_log_axes_and_states_the_points_it_leaves_out():
    """D against ky had linear axes: each is log where its values span a decade (as the
    library's Newmark figure), points with D = 0 (no sliding) are then left out and counted
    in the title, the others drawn as given; values within a decade keep a linear axis."""
    from blockdae.app._analysis import displacement_figure

    rows = [{"record": "A", "pga_g": 0.3, "ky_g": ky, "max_m": d}
            for ky, d in ((0.02, 0.31), (0.1, 0.042), (0.2, 0.0031), (0.4, 0.0))]
    rows += [{"record": "B", "pga_g": 0.3, "ky_g": ky, "max_m": d} for ky, d in ((0.02, 0.12), (0.1, 0.0))]
    ax = displacement_figure(rows).axes[0]
    assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
    assert "2 points at D = 0 or ky = 0 not shown on the log axes" in ax.get_title()
    first, second = ax.get_lines()
    assert first.get_xdata().tolist() == [0.02, 0.1, 0.2] and first.get_ydata().tolist() == [0.31, 0.042, 0.0031]
    assert second.get_xdata().tolist() == [0.02] and second.get_ydata().tolist() == [0.12]
    whole = displacement_figure(rows[:3]).axes[0]
    assert whole.get_title() == "D against ky" and whole.get_yscale() == "log"
    narrow = displacement_figure([{"record": "A", "pga_g": 0.3, "ky_g": ky, "max_m": d}
                                  for ky, d in ((0.1, 0.05), (0.15, 0.02), (0.2, 0.0))]).axes[0]
    assert narrow.get_xscale() == "linear" and narrow.get_yscale() == "linear"
    assert narrow.get_lines()[0].get_ydata().tolist() == [0.05, 0.02, 0.0]


@pytest.fixture(scope="module")
def served():
    """The app served on a thread (127.0.0.1, a free port)."""
    local = LocalApp().start()
    yield local
    local.stop()


#: pySLAMMER's records (CSV, their header says g) by stem
RECORDS = {path.stem: path for path in sample_record_paths()}
KOBE, CAPE = "Kobe_1995_TAK-090", "Cape_Mendocino_1992_PET-090"
#: the analysis form of the page for a rigid block, both polarities, as recorded
RIGID = {"method.value": "rigid", "ky-mode.value": "direct", "ky.value": "0.1", "pga.value": "",
         "polarity.value": "both"}


def _table(csv_text):
    return pd.read_csv(io.StringIO(csv_text))


def _newmark(stem, ky):
    """bd.newmark's table of one of pySLAMMER's records (the reference: the library's own call)."""
    record = bd.read_record(RECORDS[stem])
    return bd.newmark({record.name: record}, ky).to_dataframe()


def _files(local, page):
    """The names of the files the app keeps for ``page`` (in its session's folder)."""
    return sorted(path.name for path in local.sessions[page.key].folder.rglob("*") if path.is_file())


def test_two_pages_keep_their_own_records_and_results(served):
    """Two pages (tabs) of one app, their clicks interleaved: each page's CSV holds its own
    record at its own ky (those of bd.newmark on the same inputs); a file removed in one page
    leaves the other's next run as it was; each page's files are kept apart."""
    a, b = Page(served.url), Page(served.url)
    assert a.key != b.key
    assert a.upload({f"{KOBE}.csv": data_url(RECORDS[KOBE])}) == ""
    assert b.upload({f"{CAPE}.csv": data_url(RECORDS[CAPE])}) == ""
    assert (_files(served, a), _files(served, b)) == ([f"{KOBE}.csv"], [f"{CAPE}.csv"])
    assert a.run({**RIGID, "ky.value": "0.1"})["progress"]["children"].startswith("done: 1 record")
    assert b.run({**RIGID, "ky.value": "0.2"})["progress"]["children"].startswith("done: 1 record")
    pd.testing.assert_frame_equal(_table(a.csv()), _newmark(KOBE, 0.1), check_exact=True)
    pd.testing.assert_frame_equal(_table(b.csv()), _newmark(CAPE, 0.2), check_exact=True)

    b.remove(f"{CAPE}.csv")
    assert _files(served, b) == [] and _files(served, a) == [f"{KOBE}.csv"]
    assert a.run({**RIGID, "ky.value": "0.15"})["progress"]["children"].startswith("done: 1 record")
    pd.testing.assert_frame_equal(_table(a.csv()), _newmark(KOBE, 0.15), check_exact=True)
    refused = b.call("run.n_clicks", {**RIGID, "run.n_clicks": 1})["response"]["analysis-messages"]["children"]
    assert refused.startswith("no record is loaded")
    pd.testing.assert_frame_equal(_table(b.csv()), _newmark(CAPE, 0.2), check_exact=True)  # its results stay


def test_a_session_unheard_ends_its_runs_cancelled_and_its_files_removed(tmp_path, monkeypatch):
    """A session not heard from for the expiry is closed: its running analysis cancelled, its
    folder removed, its key refused; another, heard from, stays."""
    release = threading.Event()

    def analyse_slowly(name, record, settings):
        release.wait(10)
        return [{"record": name}], []

    monkeypatch.setattr("blockdae.app._session.analyse", analyse_slowly)
    expiry_s = 600.0  # the sweeping thread then waits a minute: the test sweeps itself
    sessions = Sessions(tmp_path, expiry_s=expiry_s)
    try:
        quiet, heard = sessions.new(), sessions.new()
        session = sessions[quiet]
        for stem in (KOBE, CAPE):
            session.add_upload(f"{stem}.csv", data_url(RECORDS[stem]))
        sessions[heard].add_upload(f"{CAPE}.csv", data_url(RECORDS[CAPE]))
        job = session.start(Settings("rigid", (0.1,)))  # its first record waits for the release
        assert session.folder.is_dir() and not job.cancelled.is_set()
        sessions.sweep()  # both heard from within the expiry: both stay
        assert session.folder.is_dir() and not job.cancelled.is_set()
        for key in (quiet, heard):  # both last heard from longer ago than the expiry ...
            sessions[key].seen -= 2 * expiry_s
        sessions.heard_from(heard)  # ... and one heard from again now (no sleeping: load-proof)
        sessions.sweep()
        release.set()
        assert job.finished.wait(10) and (job.done, job.total) == (1, 2)  # cancelled after its first record
        assert not session.folder.exists()
        with pytest.raises(SessionEnded):
            sessions[quiet]
        assert [p.name for p in sessions[heard].folder.rglob("*.csv")] == [f"{CAPE}.csv"]
    finally:
        sessions.close()
    assert list(tmp_path.iterdir()) == []


def test_a_page_whose_session_ended_says_so():
    """The app's own check ends a page unheard for 3 s: its file goes, its next click
    answers that the session has ended (and stops the page's polling); a new page works."""
    local = LocalApp(session_expiry_s=3.0).start()
    try:
        page = Page(local.url)
        assert page.upload({f"{KOBE}.csv": data_url(RECORDS[KOBE])}) == ""  # kept: loaded without a message
        deadline = time.monotonic() + 30
        while list(local.sessions.folder.rglob("*.csv")):
            assert time.monotonic() < deadline
            time.sleep(0.05)
        answer = page.call("download-csv-button.n_clicks", {"download-csv-button.n_clicks": 1})
        assert answer["response"] == {}
        assert answer["sideUpdate"]["session-ended"]["children"] == (
            "This page's session has ended (the app was restarted, or the page was not heard from for 0.05 "
            "minutes): reload the page to start again.")
        assert all(answer["sideUpdate"][interval] == {"disabled": True} for interval in ("poll", "design-poll"))
        other = Page(local.url)
        assert other.upload({f"{KOBE}.csv": data_url(RECORDS[KOBE])}) == ""
    finally:
        local.stop()


@pytest.mark.parametrize("forged", [{"Host": "evil.example:{port}"}, {"Host": "evil.example"},
                                    {"Host": "127.0.0.1:1"}, {"Host": ""}, {"Origin": "http://evil.example"},
                                    {"Origin": "http://evil.example:{port}"}, {"Origin": "null"},
                                    {"Origin": "http://127.0.0.1:1"}])
def test_a_forged_host_or_origin_is_refused(served, forged):
    """A page of another site that renamed itself to this address (DNS rebinding) sends its
    own name as Host, or its Origin: 403 for the page and for a callback, with the cookie."""
    page = Page(served.url)
    headers = {"Cookie": page.cookie, **{k: v.format(port=page.port) for k, v in forged.items()}}
    status, _, body = request(page.port, "GET", "/", headers)
    assert status == 403 and body.startswith(b"blockdae app: "), body
    status, _, body = request(page.port, "POST", "/_dash-update-component",
                              {**headers, "Content-Type": "application/json"}, "{}")
    assert status == 403, body


def test_the_token_or_its_cookie_is_needed(served):
    """This computer's names with the app's port pass with the cookie; without it, or with a
    wrong token or cookie, 403 naming what is needed; the token answers with the cookie."""
    page = Page(served.url)
    for host in ("127.0.0.1", "localhost", "LOCALHOST", "[::1]"):
        for origin in ({}, {"Origin": f"http://{host}:{page.port}"}):
            status, _, _ = request(page.port, "GET", "/", {"Host": f"{host}:{page.port}", "Cookie": page.cookie,
                                                           **origin})
            assert status == 200, (host, origin)
    name, token = page.cookie.split("=", 1)
    wrong = ("y" if token[0] == "x" else "x") + token[1:]  # one character changed
    for headers, path in (({}, "/"), ({"Cookie": f"{name}={wrong}"}, "/"), ({}, f"/?token={wrong}"),
                          ({}, "/_dash-layout"), ({"Cookie": f"blockdae-app-1={token}"}, "/")):
        status, _, body = request(page.port, "GET", path, headers)
        assert (status, body) == (403, b"blockdae app: this address needs the app's token: open the whole address "
                                       b"'blockdae app' printed (http://...?token=...)\n"), (headers, path)
    status, headers, _ = request(page.port, "GET", f"/_dash-layout?token={token}")
    assert status == 303 and headers["Location"] == "/_dash-layout"
    assert headers["Set-Cookie"] == f"{name}={token}; HttpOnly; Path=/; SameSite=Strict"


def test_odd_file_names_are_refused_and_the_rest_of_the_batch_loads(served):
    """Names that cannot be a file's ('', '.', '..', 300 characters, a line break, half a
    UTF-16 pair) get a message each, as does an empty file (the browser sends it as 'data:');
    the other files of the batch load (a folder's file by its own name)."""
    page = Page(served.url)
    kobe = data_url(RECORDS[KOBE])
    long = "x" * 296 + ".csv"
    message = page.upload({"": kobe, ".": kobe, "..": kobe, "records/..": kobe, long: kobe, "two\nlines.csv": kobe,
                           "half\ud800.csv": kobe, "empty.csv": "data:", f"station records/{KOBE}.csv": kobe,
                           f"{CAPE}.csv": data_url(RECORDS[CAPE])})
    assert message.splitlines() == [
        "a file named '' is not loaded: that is no file name",
        "a file named '.' is not loaded: that is no file name",
        "a file named '..' is not loaded: that is no file name",
        "a file named '..' is not loaded: that is no file name",
        "a file named 'xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx'... (300 characters) is not loaded: a file name is "
        "at most 255 bytes",
        "a file named 'two\\nlines.csv' is not loaded: its name holds U+000A, which no file name may hold",
        "a file named 'half\\ud800.csv' is not loaded: its name holds U+D800, which no file name may hold",
        "empty.csv: no data rows"]
    assert sorted(served.sessions[page.key].files) == [f"{CAPE}.csv", f"{KOBE}.csv"]


def test_a_file_above_the_size_limit_is_refused_by_name(served):
    """A file one byte above the limit: a message naming it, its size and the limit (as the
    docs state it); the other file of the batch loads."""
    page = Page(served.url)
    big = "data:text/csv;base64," + __import__("base64").b64encode(b"0" * (FILE_LIMIT_BYTES + 1)).decode()
    message = page.upload({"big.csv": big, f"{KOBE}.csv": data_url(RECORDS[KOBE])})
    assert message == "big.csv: 20.0 MB is above the app's limit of 20 MB per file: not loaded"
    assert list(served.sessions[page.key].files) == [f"{KOBE}.csv"]


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
@pytest.mark.parametrize("stop", [signal.SIGTERM, signal.SIGINT, signal.SIGHUP])
def test_a_stopped_app_removes_its_temporary_folder(tmp_path, stop):
    """``blockdae app`` stopped by SIGTERM (a service manager, ``kill``) or SIGHUP (its
    terminal closed) removes its temporary folder with the files uploaded, as Ctrl+C does."""
    process = subprocess.Popen([sys.executable, "-m", "blockdae.cli", "app", "--no-browser"],
                               env={**os.environ, "TMPDIR": str(tmp_path)}, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True)
    try:
        line = process.stdout.readline()
        url = re.search(r"http://\S+", line)
        assert url, (line, process.stderr.read() if process.poll() is not None else "")
        assert Page(url[0]).upload({f"{KOBE}.csv": data_url(RECORDS[KOBE])}) == ""
        (folder,) = tmp_path.glob("blockdae-app-*")
        assert [path.name for path in folder.rglob("*.csv")] == [f"{KOBE}.csv"]
        process.send_signal(stop)
        assert process.wait(60) == 0, process.stderr.read()
    finally:
        process.kill()
        process.wait(30)
    assert list(tmp_path.glob("blockdae-app-*")) == []
