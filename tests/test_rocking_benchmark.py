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
    assert out.count("bar 100x: smoke run, not a measurement") == 2 and "NOT met" not in out
    parts = out.split("\n\n")
    assert parts[0].startswith("linearised block, backend 'exact'")
    assert parts[3].startswith("exact equation, backend 'compiled'")
    for table in (parts[1].splitlines(), parts[4].splitlines()):
        assert len(table) == 3 and "speed-up [-]" in table[0]  # header + the 2 shortest records
