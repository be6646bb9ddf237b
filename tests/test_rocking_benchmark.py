"""A smoke run of benchmarks/rocking.py with --quick, so that it never rots."""

import importlib.util
import pathlib

BENCHMARKS = pathlib.Path(__file__).parents[1] / "benchmarks"


def test_rocking_benchmark_quick(monkeypatch, capsys):
    monkeypatch.syspath_prepend(str(BENCHMARKS))
    spec = importlib.util.spec_from_file_location("benchmark_rocking", BENCHMARKS / "rocking.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert module.main(["--quick", "--repeat", "1"]) == 0
    out = capsys.readouterr().out
    assert "bar 100x: smoke run, not a measurement" in out and "NOT met" not in out
    table = out.split("\n\n")[1].splitlines()
    assert len(table) == 3 and "speed-up [-]" in table[0]  # header + the 2 shortest records
