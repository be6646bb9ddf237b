"""The documentation site builds offline with no warning, and its reference covers every
public name and every command. Runs where the `docs` extra is installed (CI installs it);
the build takes about 40 s on 2 cores, of which the getting-started tutorial, run by the
build, takes about 2 s of CPU (its code alone; numba's cache warm)."""

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


#: what the kernel that runs the tutorial logs of its own transport as it starts (no
#: warning of the build's)
KERNEL_NOTICE = re.compile(r"^\[IPKernelApp\] WARNING \| Kernel is running over TCP without encryption\..*$",
                           re.MULTILINE)


def test_the_site_builds_with_no_warning(site):
    out, log = site
    log = KERNEL_NOTICE.sub("", log)
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


def _entry(html, anchor):
    """The HTML of the reference entry ``anchor`` (up to the next entry)."""
    start = html.index(f'id="{anchor}"')
    end = html.find('<dt class="sig sig-object', start + 1)
    return html[start:end if end > 0 else None]


def test_the_tutorial_shows_what_its_code_prints_and_draws(site):
    """The getting-started tutorial showed code only: the build runs it, and the page holds
    its printed table and line and the figure it draws."""
    page = (site[0] / "getting-started" / "first-analysis.html").read_text()
    assert re.search(r"D = 0\.\d{4} m at PGA 0\.3 g, ky 0\.1 g \(larger polarity\)", page)
    assert "ky_g" in page and "episodes_normal" in page  # the printed tables
    assert re.search(r'<img[^>]+src="\.\./_images/[0-9a-f]+\.png"', page)


@pytest.mark.parametrize("page, diagram", [("rigid-block", "sliding-block"), ("flexible-mass", "flexible-mass"),
                                           ("rocking-block", "rocking-block")])
def test_each_theory_page_draws_its_model(site, page, diagram):
    html = (site[0] / "theory" / f"{page}.html").read_text()
    assert f'src="../_images/{diagram}.svg"' in html
    assert (site[0] / "_images" / f"{diagram}.svg").stat().st_size > 1000


def test_empirical_references_list_each_parameter_once(site):
    """The entries of bray_macedo_2019 and bray_travasarou_2007 listed "(0", "[g]" and
    "warning" as parameters: each function's parameters are its signature's, and its
    return value no type cut at a colon."""
    import inspect

    from blockdae import empirical

    html = (site[0] / "reference" / "subpackages.html").read_text()
    functions = [name for name in empirical.__all__ if inspect.isfunction(getattr(empirical, name))]
    assert {"bray_macedo_2019", "bray_travasarou_2007", "jibson_2007"} <= set(functions)
    for name in functions:
        entry = _entry(html, f"blockdae.empirical.{name}")
        listed = re.search(r'Parameters<span class="colon">:</span></dt>\s*<dd[^>]*>(.*?)</dd>', entry, re.S)
        assert listed, name
        names = re.findall(r"<strong>(.*?)</strong>", listed.group(1))
        assert names == list(inspect.signature(getattr(empirical, name)).parameters), (name, names)
        assert "Return type" not in entry and "(p_negligible</p>" not in entry, name


def test_simulate_returns_no_sentence_as_its_type(site):
    entry = _entry((site[0] / "reference" / "api.html").read_text(), "blockdae.simulate")
    returned = re.search(r'Returns<span class="colon">:</span></dt>\s*<dd[^>]*>(.*?)</dd>', entry, re.S).group(1)
    assert "One motion at one scale" not in entry and "Return type" not in entry
    assert "The model’s solution where one motion runs" in returned
