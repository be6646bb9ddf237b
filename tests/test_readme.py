"""Every code block of the README runs as written (the set-up block's install is the one
exception: CI has just run it). Python blocks run in one namespace, in order; bash blocks
run in a shell, in a scratch folder."""

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


def test_python_blocks_run_as_written(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    namespace = {}
    for code in _blocks("python"):
        exec(compile(code, str(README), "exec"), namespace)


@pytest.mark.parametrize("index", range(len([b for b in _blocks("bash") if not _is_setup(b)])))
def test_bash_blocks_run_as_written(index, tmp_path, jax_cache_dir):
    code = [b for b in _blocks("bash") if not _is_setup(b)][index]
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path), MPLBACKEND="Agg",
               BLOCKDAE_CACHE_DIR=str(jax_cache_dir), PATH=os.pathsep.join(
                   [str(pathlib.Path(sys.executable).parent), os.environ.get("PATH", "")]))
    repo = README.parent
    in_repo = "benchmarks/" in code or "examples/" in code
    script = f"set -euo pipefail\ncd {repo}\n" + code if in_repo else "set -euo pipefail\n" + code
    done = subprocess.run(["bash", "-c", script], cwd=tmp_path, env=env, capture_output=True, text=True,
                          timeout=900)
    assert done.returncode == 0, f"README block failed:\n{code}\n--- stderr:\n{done.stderr[-3000:]}"
