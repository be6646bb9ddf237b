"""Progress bars of long runs (tqdm on stderr, shown only on a terminal unless asked
for) and the one-line notice before the first JAX compilation in a process."""

import io
import json
import math
import os
import subprocess
import sys
import warnings

import pytest

import blockdae as bd
from blockdae.core import _compile_notice
from blockdae.core._progress import progress_bar, show_progress


class _Terminal(io.StringIO):
    def isatty(self):
        return True


def test_bars_are_shown_on_a_terminal_only_unless_asked_for(monkeypatch):
    monkeypatch.setattr(sys, "stderr", _Terminal())
    assert show_progress() and show_progress(True) and not show_progress(False)
    monkeypatch.setattr(sys, "stderr", io.StringIO())
    assert not show_progress() and show_progress(True) and not show_progress(False)


def test_the_bar_writes_to_a_terminals_stderr_and_nothing_elsewhere(monkeypatch):
    terminal = _Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    with progress_bar(3, "newmark", "record") as bar:
        bar.update(3)
    assert "newmark" in terminal.getvalue() and "3/3" in terminal.getvalue()
    plain = io.StringIO()
    monkeypatch.setattr(sys, "stderr", plain)
    with progress_bar(3, "newmark", "record") as bar:
        bar.update(3)
    assert plain.getvalue() == ""


def test_the_first_jax_call_in_a_process_says_it_compiles_once_naming_the_callers_line(monkeypatch):
    """A run on the exact (numba) backend, compiled already, says nothing; the first JAX
    call warns once (bd.CompileNotice, naming this file), the next ones do not; the
    filter silences it."""
    block, motion = bd.SlidingBlock(mu=0.2), bd.Harmonic(amplitude=5.0, period=1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", bd.CompileNotice)
        bd.simulate(block, motion, t_end=1.0)  # compiled or loaded in this process
    monkeypatch.setattr(_compile_notice, "_noticed", set())  # as in a fresh process
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        bd.simulate(block, motion, t_end=1.0)
    assert not [w for w in caught if w.category is bd.CompileNotice]
    notice = (r"^blockdae: compiling its JAX kernels \(the first JAX call in this process: up to about 15 s after an "
              r"install, about 5 s once JAX's disk cache holds them\)\. Silence: warnings\.filterwarnings")
    with pytest.warns(bd.CompileNotice, match=notice) as first:
        bd.simulate(block, motion, t_end=1.0, backend="jax")
    assert len(first) == 1 and first[0].filename == __file__
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        bd.simulate(block, motion, t_end=2.0, backend="jax")
    assert not [w for w in caught if w.category is bd.CompileNotice]
    monkeypatch.setattr(_compile_notice, "_noticed", set())
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        warnings.filterwarnings("ignore", category=bd.CompileNotice)
        bd.simulate(block, motion, t_end=1.0, backend="jax")
    assert not [w for w in caught if w.category is bd.CompileNotice]


_FIRST_NUMBA_CALLS = """
import json, warnings
import numpy as np
import blockdae as bd
from blockdae.flexible_mass._column import ShearColumn
from blockdae.flexible_mass._slammer import slammer_flexible

def run():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        slammer_flexible(0.3 * np.sin(0.05 * np.arange(200)), 0.01, scale=1.0, ky=0.1,
                         column=ShearColumn(height=10.0, vs=200.0), method="decoupled")
    return [[str(w.message), w.filename] for w in caught if w.category is bd.CompileNotice]

print(json.dumps([run(), run()]))
"""


def test_a_numba_engine_says_it_compiles_only_when_its_disk_cache_is_empty(tmp_path):
    """In a fresh process on an empty NUMBA_CACHE_DIR the first call of a numba kernel
    (SLAMMER's, the smallest) warns once, naming the caller's line; the second call does
    not; a second process on the now populated cache loads it and says nothing."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path))
    runs = [json.loads(subprocess.run([sys.executable, "-c", _FIRST_NUMBA_CALLS], env=env, capture_output=True,
                                      text=True, check=True).stdout) for _ in range(2)]
    (first, second), (after_cache, _) = runs
    assert len(first) == 1 and not second and not after_cache and list(tmp_path.rglob("*.nbi"))
    message, filename = first[0]
    assert message.startswith("blockdae: compiling SLAMMER's flexible analyses with numba (its first run after an "
                              "install or upgrade; about 1 s, then loaded from numba's disk cache). Silence: ")
    assert filename == "<string>"


def test_the_numba_check_says_nothing_when_numbas_cache_object_is_not_as_expected():
    class Compiled:
        signatures = [("float64",)]

    class Unknown:
        signatures = []

    class Empty(Unknown):
        class _cache:
            class _cache_file:
                _load_index = staticmethod(dict)

    assert not _compile_notice._will_compile(Compiled()) and not _compile_notice._will_compile(Unknown())
    assert _compile_notice._will_compile(Empty())


def test_the_command_line_prints_a_compile_notice_as_one_line_before_the_run(tmp_path, monkeypatch, capsys):
    """``blockdae newmark`` on an engine that must compile: the notice alone on stderr
    (no file and line, no "warning:" prefix), before the table on stdout."""
    from blockdae.cli._main import main

    monkeypatch.setattr(_compile_notice, "_noticed", set())
    monkeypatch.setattr(_compile_notice, "_will_compile", lambda dispatcher: True)
    record = tmp_path / "pulse.csv"
    record.write_text("time [s], acceleration [m/s2]\n" + "".join(f"{k / 100}, {3 * math.sin(math.pi * k / 25)}\n"
                                                                for k in range(51)))  # one sine wave, 0.01 s steps
    assert main(["newmark", str(record), "--ky", "0.1", "--units", "m/s2"]) == 0
    captured = capsys.readouterr()
    assert captured.err == ("blockdae: compiling the exact engine with numba (its first run after an install or "
                            "upgrade; about 8 s, then loaded from numba's disk cache). Silence: "
                            "warnings.filterwarnings('ignore', category=blockdae.CompileNotice)\n")
    assert "  ky [g]   normal [m]  inverse [m]" in captured.out


def test_flexible_and_overturning_fragility_show_a_bar_and_the_same_numbers(monkeypatch):
    """bd.flexible over many records and overturning_fragility had no bar: both show one on
    a terminal's stderr (or with progress=True), and give the numbers they give without it
    (flexible then runs the records in parts)."""
    import numpy as np

    from blockdae.rocking import RockingBlock, overturning_fragility

    t = np.arange(600) * 0.01
    records = [bd.Record(0.3 * bd.STANDARD_GRAVITY * np.sin(2 * math.pi * f * t) * np.exp(-0.3 * t), 0.01,
                         name=f"decaying {f:g} Hz", units="m/s2") for f in (0.8, 1.0, 1.5, 2.0, 3.0)]
    quiet = bd.flexible(records, ky=0.05, height=20.0, vs=300.0, progress=False).to_dataframe()
    block = RockingBlock(b=0.1, h=0.5, mu=0.6)
    fragile = overturning_fragility(block, records, [0.2, 0.8], progress=False)
    terminal = _Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    shown = bd.flexible(records, ky=0.05, height=20.0, vs=300.0).to_dataframe()
    assert "flexible" in terminal.getvalue() and "5/5" in terminal.getvalue()
    assert shown.equals(quiet) and (quiet["max_m"] > 0).any()
    again = overturning_fragility(block, records, [0.2, 0.8])
    assert "overturning fragility" in terminal.getvalue()
    np.testing.assert_array_equal(again.overturned, fragile.overturned)
    plain = io.StringIO()
    monkeypatch.setattr(sys, "stderr", plain)
    bd.flexible(records, ky=0.05, height=20.0, vs=300.0)
    overturning_fragility(block, records, [0.2])
    assert plain.getvalue() == ""
