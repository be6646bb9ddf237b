"""Every code block of the README runs as written (the set-up block's install is the one
exception: CI has just run it). Each block runs alone, as a reader may copy it: a python
block in a fresh interpreter, a bash block in a shell, each in a scratch folder."""

import os
import pathlib
import re
import subprocess
import sys

import pytest

README = pathlib.Path(__file__).parents[1] / "README.md"
BLOCK = re.compile(r"```(python|bash)\n(.*?)```", re.DOTALL)


def _blocks(language):
    return [code for lang, code in BLOCK.findall(README.read_text()) if lang == language]


def _is_setup(code):
    return "pip install" in code


def test_readme_has_code_blocks():
    assert len(_blocks("python")) >= 1 and len(_blocks("bash")) >= 3


def _environment(jax_cache_dir):
    """The test's interpreter and path, a headless matplotlib and the shared JAX cache."""
    return dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path), MPLBACKEND="Agg",
                BLOCKDAE_CACHE_DIR=str(jax_cache_dir), PATH=os.pathsep.join(
                    [str(pathlib.Path(sys.executable).parent), os.environ.get("PATH", "")]))


@pytest.mark.parametrize("index", range(len(_blocks("python"))))
def test_python_blocks_run_alone_as_written(index, tmp_path, jax_cache_dir):
    """Issue 23 item 6: no block leans on names an earlier block defined (a NameError here)."""
    code = _blocks("python")[index]
    done = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=_environment(jax_cache_dir),
                          capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, f"README block failed alone:\n{code}\n--- stderr:\n{done.stderr[-3000:]}"


def _only_benchmarks(block) -> bool:
    """A block of ``python benchmarks/NAME.py --quick`` lines only."""
    lines = [line for line in block.splitlines() if line.strip() and not line.lstrip().startswith("#")]
    return all(line.startswith("python benchmarks/") for line in lines)


# the block of benchmark smoke runs is slow (about 100 s); each of its commands also runs fast
# in tests/test_benchmarks.py or tests/test_hazard.py
@pytest.mark.parametrize("index", [pytest.param(i, marks=pytest.mark.slow) if _only_benchmarks(b) else i
                                   for i, b in enumerate(b for b in _blocks("bash") if not _is_setup(b))])
def test_bash_blocks_run_as_written(index, tmp_path, jax_cache_dir):
    code = [b for b in _blocks("bash") if not _is_setup(b)][index]
    env = _environment(jax_cache_dir)
    repo = README.parent
    in_repo = "benchmarks/" in code or "examples/" in code
    script = f"set -euo pipefail\ncd {repo}\n" + code if in_repo else "set -euo pipefail\n" + code
    done = subprocess.run(["bash", "-c", script], cwd=tmp_path, env=env, capture_output=True, text=True,
                          timeout=900)
    assert done.returncode == 0, f"README block failed:\n{code}\n--- stderr:\n{done.stderr[-3000:]}"
