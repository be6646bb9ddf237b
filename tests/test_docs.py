"""The documentation site builds offline with no warning, and its reference covers every
public name and every command. Runs where the `docs` extra is installed (CI installs it);
the build takes about 40 s on 2 cores."""

import argparse
import os
import pathlib
import re
import subprocess
import sys

import pytest

import blockdae
from blockdae.cli._main import _parser

for module in ("sphinx", "myst_nb", "furo", "sphinxarg"):
    pytest.importorskip(module, reason="the docs extra is not installed")

ROOT = pathlib.Path(__file__).parents[1]
#: a script or stylesheet fetched from the network when a page opens (the footer's
#: plain links to the tools' home pages are not fetched)
REMOTE_ASSET = re.compile(r"<(?:script|link|img)\b[^>]*\b(?:src|href)=\"(?:https?:)?//[^\"]+\"")


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """The site, built from scratch with warnings as errors: (output folder, build log)."""
    out = tmp_path_factory.mktemp("html")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path), MPLBACKEND="Agg")
    done = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html",
                           "-d", str(out / ".doctrees"), str(ROOT / "docs"), str(out)],
                          env=env, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, f"the docs build failed or warned:\n{done.stderr[-6000:]}"
    return out, done.stderr


def test_the_site_builds_with_no_warning(site):
    out, log = site
    assert "WARNING" not in log and "ERROR" not in log, log
    assert (out / "index.html").is_file()


def test_every_public_name_has_a_reference_entry(site):
    """Each name of ``blockdae.__all__`` is described on the API page (its anchor exists)."""
    api = (site[0] / "reference" / "api.html").read_text()
    missing = [name for name in blockdae.__all__ if f'id="blockdae.{name}"' not in api]
    assert not missing, f"names without a reference entry: {missing}"


def _subcommands(parser):
    """The names of every command of ``parser``, nested ones as "a b"."""
    names = []
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                names.append(name)
                names += [f"{name} {inner}" for inner in _subcommands(sub)]
    return names


def test_every_cli_command_has_a_reference_entry(site):
    """Each subcommand of the parser has its section on the command-line page."""
    cli = (site[0] / "reference" / "cli.html").read_text()
    commands = _subcommands(_parser())
    assert len(commands) >= 12, commands
    missing = [name for name in commands if f'id="blockdae-{name.replace(" ", "-")}"' not in cli]
    assert not missing, f"commands without a reference entry: {missing}"


def test_every_notebook_is_in_the_gallery(site):
    stems = sorted(path.stem for path in (ROOT / "notebooks").glob("*.ipynb"))
    built = sorted(path.stem for path in (site[0] / "notebooks").glob("*.html"))
    assert stems == built


def test_pages_fetch_nothing_from_the_network(site):
    """Scripts, styles, fonts and MathJax come from the site's own files."""
    remote = {path.relative_to(site[0]).as_posix(): REMOTE_ASSET.findall(path.read_text())
              for path in site[0].rglob("*.html")}
    assert not {page: found for page, found in remote.items() if found}
    assert (site[0] / "_static" / "mathjax" / "tex-chtml.js").is_file()
