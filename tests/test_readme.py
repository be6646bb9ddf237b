"""Every code block of the README and of the pages of the documentation site (docs/ and
its folders) runs as written (the set-up
block's install is the one exception: CI has just run it). Each block runs alone, as a
reader may copy it: a python block in a fresh interpreter, a bash block in a shell, each in
a scratch folder. Blocks meant only to be read are fenced as ```text."""

import os
import pathlib
import re
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).parents[1]
README = ROOT / "README.md"
DOCS = sorted(path for path in (ROOT / "docs").rglob("*.md") if "_build" not in path.parts)
PAGES = [README, *DOCS]
#: a page the docs build executes (a MyST notebook) fences its Python as code cells
CODE_CELL = "{code-cell} ipython3"
BLOCK = re.compile(r"```(python|bash|\{code-cell\} ipython3)\n(.*?)```", re.DOTALL)
FENCE_LANGUAGES = {"python", "bash", "text", CODE_CELL}


def _blocks(language, pages=PAGES):
    """(page, code) of every ```language block of ``pages`` (code cells as python), in order."""
    return [(page, code) for page in pages for lang, code in BLOCK.findall(page.read_text())
            if (("python" if lang == CODE_CELL else lang) == language)]


def _name(page):
    return page.relative_to(ROOT).as_posix()


def _is_setup(code):
    return "pip install" in code


def _opening_fences(page):
    """(line number, language) of every opening ``` fence of ``page``."""
    fences, inside = [], False
    for number, line in enumerate(page.read_text().splitlines(), start=1):
        if line.startswith("```"):
            if not inside:
                fences.append((number, line[3:].strip()))
            inside = not inside
    assert not inside, f"{_name(page)}: a ``` fence is never closed"
    return fences


def test_readme_and_docs_have_code_blocks():
    """The README shows the set-up and one analysis; the docs pages hold the examples:
    the getting-started pages a rigid, a flexible and an own-record analysis and the
    command line, the guides the rest."""
    assert len(_blocks("python", [README])) >= 1 and len(_blocks("bash", [README])) >= 1
    started = sorted((ROOT / "docs" / "getting-started").glob("*.md"))
    assert len(_blocks("python", started)) >= 3 and len(_blocks("bash", started)) >= 1
    assert len(_blocks("python", DOCS)) >= 18 and len(_blocks("bash", DOCS)) >= 5
    runnable = {_name(page) for page, _ in _blocks("python", DOCS) + _blocks("bash", DOCS)}
    assert len(runnable) >= 12, runnable


@pytest.mark.parametrize("page", PAGES, ids=_name)
def test_every_fence_says_its_language(page):
    """A fence without python, bash or text would escape the runs below."""
    odd = [(number, lang) for number, lang in _opening_fences(page) if lang not in FENCE_LANGUAGES]
    assert not odd, f"{_name(page)}: fences without a known language at (line, language) {odd}"


def test_readme_links_the_docs_and_every_link_resolves():
    """The README links the site's front page (every page is in its table of contents:
    tests/test_docs.py builds it with warnings as errors), and no page links to a missing
    file."""
    assert "(docs/index.md)" in README.read_text()
    for page in PAGES:
        for target in re.findall(r"\]\(([^)#\s]+)(?:#[^)]*)?\)", page.read_text()):
            if "://" not in target:
                assert (page.parent / target).exists(), f"{_name(page)} links to missing {target}"


def _environment(jax_cache_dir):
    """The test's interpreter and path, a headless matplotlib and the shared JAX cache."""
    return dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path), MPLBACKEND="Agg",
                BLOCKDAE_CACHE_DIR=str(jax_cache_dir), PATH=os.pathsep.join(
                    [str(pathlib.Path(sys.executable).parent), os.environ.get("PATH", "")]))


PYTHON_BLOCKS = _blocks("python")


@pytest.mark.parametrize("index", range(len(PYTHON_BLOCKS)),
                         ids=[f"{_name(page)}-{i}" for i, (page, _) in enumerate(PYTHON_BLOCKS)])
def test_python_blocks_run_alone_as_written(index, tmp_path, jax_cache_dir):
    """No block leans on names an earlier block defined (a NameError here)."""
    page, code = PYTHON_BLOCKS[index]
    done = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=_environment(jax_cache_dir),
                          capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, f"{_name(page)} block failed alone:\n{code}\n--- stderr:\n{done.stderr[-3000:]}"


def _only_benchmarks(block) -> bool:
    """A block of ``python benchmarks/NAME.py --quick`` lines only."""
    lines = [line for line in block.splitlines() if line.strip() and not line.lstrip().startswith("#")]
    return all(line.startswith("python benchmarks/") for line in lines)


BASH_BLOCKS = [(page, code) for page, code in _blocks("bash") if not _is_setup(code)]


# the block of benchmark smoke runs is slow (about 100 s); each of its commands also runs fast
# in tests/test_benchmarks.py or tests/test_hazard.py
@pytest.mark.parametrize("index", [pytest.param(i, marks=pytest.mark.slow) if _only_benchmarks(code) else i
                                   for i, (_, code) in enumerate(BASH_BLOCKS)],
                         ids=[f"{_name(page)}-{i}" for i, (page, _) in enumerate(BASH_BLOCKS)])
def test_bash_blocks_run_as_written(index, tmp_path, jax_cache_dir):
    page, code = BASH_BLOCKS[index]
    env = _environment(jax_cache_dir)
    in_repo = "benchmarks/" in code or "examples/" in code
    script = f"set -euo pipefail\ncd {ROOT}\n" + code if in_repo else "set -euo pipefail\n" + code
    done = subprocess.run(["bash", "-c", script], cwd=tmp_path, env=env, capture_output=True, text=True,
                          timeout=900)
    assert done.returncode == 0, f"{_name(page)} block failed:\n{code}\n--- stderr:\n{done.stderr[-3000:]}"
