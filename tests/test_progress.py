"""Progress bars of long runs: tqdm on stderr, shown only on a terminal unless asked for."""

import io
import sys

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
