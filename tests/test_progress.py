"""Progress bars of long runs (tqdm on stderr, shown only on a terminal unless asked
for) and the one-line notice before the first JAX compilation in a process."""

import io
import sys
import warnings

import pytest

import blockdae as bd
from blockdae.core import _jax_config
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
    """A run on the exact (numba) backend says nothing; the first JAX call warns once
    (bd.CompileNotice, naming this file), the next ones do not; the filter silences it."""
    monkeypatch.setitem(_jax_config._state, "noticed", False)  # as in a fresh process
    block, motion = bd.SlidingBlock(mu=0.2), bd.Harmonic(amplitude=5.0, period=1.0)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        bd.simulate(block, motion, t_end=1.0)
    assert not [w for w in caught if w.category is bd.CompileNotice]
    with pytest.warns(bd.CompileNotice, match=r"^blockdae: compiling its JAX kernels \(the first JAX call in this "
                                              r"process; a few seconds\)\. Silence: warnings\.filterwarnings") as first:
        bd.simulate(block, motion, t_end=1.0, backend="jax")
    assert len(first) == 1 and first[0].filename == __file__
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        bd.simulate(block, motion, t_end=2.0, backend="jax")
    assert not [w for w in caught if w.category is bd.CompileNotice]
    monkeypatch.setitem(_jax_config._state, "noticed", False)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        warnings.filterwarnings("ignore", category=bd.CompileNotice)
        bd.simulate(block, motion, t_end=1.0, backend="jax")
    assert not [w for w in caught if w.category is bd.CompileNotice]
