"""The first run after an install, each in a fresh process with empty numba and JAX caches
(then again with the caches that run filled): ``blockdae examples`` (the README's first
command), ``blockdae newmark`` on a record, the app's first analysis (the page's default,
the coupled flexible mass at ky 0.1 g, H 20 m, Vs 300 m/s, of one record, with its table,
D-ky and history figures: what the Run button's callbacks call, without a browser) and the
first ``bd.sensitivities`` of a flexible sliding mass.

    python benchmarks/cold_start.py [--repeat N] [--quick]

Wall times depend on what else the machine runs; CPU times (user + system of the process)
do much less, and on an idle machine a single-threaded compile's wall time is its CPU time.
The bars are on CPU time: ``blockdae examples`` and the app's first analysis once the page
says its solvers are ready, each well under 10 s. Exits 1 if a bar is not met. ``--quick``
runs ``blockdae examples`` only (no compile: a smoke run of the script).
"""

import argparse
import importlib.resources
import json
import os
import resource
import subprocess
import sys
import tempfile
import time

from _common import print_table, verdict

#: the bars [CPU s] (the first run after an install)
EXAMPLES_BAR_S = 5.0
APP_ANALYSIS_BAR_S = 5.0

RECORD = importlib.resources.files("pyslammer") / "sample_ground_motions" / "Kobe_1995_TAK-090.csv"

#: the app: launched (the page can be served), then the default analysis of one record and
#: its figures, clicked at once or once the warm-up has finished (the page says "Solvers ready")
APP = """
import json, sys, threading, time
start = time.perf_counter()
from blockdae.app import LocalApp
from blockdae.app._analysis import displacement_figure, history_figure, parse_settings
from blockdae.app._session import Job
import blockdae as bd
app = LocalApp().start()
page = time.perf_counter() - start
warm_up = next(t for t in threading.enumerate() if t.name == "blockdae-app-warm-up")
if sys.argv[1] == "after warm-up":
    warm_up.join()
ready = time.perf_counter() - start
record = bd.read_record(sys.argv[2], units="g")
form = dict(method="coupled", ky_mode="direct", ky="0.1", height="20", vs="300", damping="0.05", pga="",
            polarity="both")
clicked, cpu = time.perf_counter(), time.process_time()
settings = parse_settings(form)
job = Job({"Kobe": record}, settings)  # the Run button's analysis, on its thread
job.finished.wait()
assert not job.errors, job.errors
displacement_figure(job.rows).savefig(sys.argv[3] + "/d.png")
history_figure(record, settings, job.rows[0], "normal").savefig(sys.argv[3] + "/h.png")
analysis = time.perf_counter() - clicked
warm_up.join()
app.stop()
print(json.dumps(dict(page=page, ready=ready, analysis=analysis, total=time.perf_counter() - start,
                      analysis_cpu=time.process_time() - cpu)))
"""

#: d s / d (omega, ky, A) of a flexible sliding mass under a sine pulse (JAX)
SENSITIVITIES = """
import json, time
start = time.perf_counter()
import blockdae as bd
model = bd.FlexibleSlidingMass(bd.ShearColumn(10.0, 250.0, 800.0, 0.05), ky=0.1)
called, cpu = time.perf_counter(), time.process_time()
bd.sensitivities(model, bd.SinePulse(0.4 * 9.80665, 0.5), 1.5, wrt=("omega", "ky", "A"))
print(json.dumps(dict(call=time.perf_counter() - called, call_cpu=time.process_time() - cpu,
                      total=time.perf_counter() - start)))
"""


def run(command, cache):
    """Run ``command`` (argv after the interpreter) with the caches under ``cache``:
    (wall [s], CPU of the process [s], its last line of output parsed as JSON or None)."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache), BLOCKDAE_CACHE_DIR=os.path.join(cache, "jax"),
               PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run([sys.executable, *command], capture_output=True, text=True, env=env, timeout=900)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode:
        raise RuntimeError(f"{command} failed:\n{done.stderr}")
    cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
    last = done.stdout.strip().splitlines()[-1]
    return wall, cpu, json.loads(last) if last.startswith("{") else None


def measure(repeat, quick=False):
    """{case: [(wall [s], CPU [s], inner figures), ...] over ``repeat`` fresh installs};
    with ``quick`` only ``blockdae examples``."""
    cases = {}

    def add(name, result):
        cases.setdefault(name, []).append(result)

    for _ in range(repeat):
        with tempfile.TemporaryDirectory(prefix="blockdae-cold-") as cache:
            add("blockdae examples, first", run(["-m", "blockdae.cli", "examples"], cache))
            add("blockdae examples, second", run(["-m", "blockdae.cli", "examples"], cache))
            if quick:
                continue
            newmark = ["-m", "blockdae.cli", "newmark", str(RECORD), "--units", "g", "--ky", "0.05", "0.1", "0.2"]
            add("blockdae newmark FILE, first", run(newmark, cache))
            add("blockdae newmark FILE, second", run(newmark, cache))
        if quick:
            continue
        for when in ("after warm-up", "at once"):
            with tempfile.TemporaryDirectory(prefix="blockdae-cold-") as cache:
                add(f"app, first start, clicked {when}", run(["-c", APP, when, str(RECORD), cache], cache))
                if when == "after warm-up":
                    add(f"app, second start, clicked {when}", run(["-c", APP, when, str(RECORD), cache], cache))
        with tempfile.TemporaryDirectory(prefix="blockdae-cold-") as cache:
            add("flexible bd.sensitivities, first", run(["-c", SENSITIVITIES], cache))
            add("flexible bd.sensitivities, second", run(["-c", SENSITIVITIES], cache))
    return cases


def spread(values, digits=1):
    """"min (max)" of ``values`` [s], or the one value."""
    low, high = min(values), max(values)
    return f"{low:.{digits}f}" if len(values) == 1 else f"{low:.{digits}f} ({high:.{digits}f})"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=1, help="fresh installs measured (min and max shown)")
    parser.add_argument("--quick", action="store_true", help="blockdae examples only")
    args = parser.parse_args(argv)
    print(f"load average before: {', '.join(f'{x:.1f}' for x in os.getloadavg())} on {os.cpu_count()} cores")
    cases = measure(args.repeat, args.quick)
    rows = []
    for name, results in cases.items():
        inner = [r[2] or {} for r in results]
        part = ""
        if "analysis" in inner[0]:
            part = (f"page served {spread([x['page'] for x in inner])} s; clicked at "
                    f"{spread([x['ready'] for x in inner])} s; analysis {spread([x['analysis'] for x in inner])} s "
                    f"wall, {spread([x['analysis_cpu'] for x in inner])} s CPU")
        elif "call" in inner[0]:
            part = (f"the call {spread([x['call'] for x in inner])} s wall, "
                    f"{spread([x['call_cpu'] for x in inner])} s CPU")
        rows.append((name, spread([r[0] for r in results]), spread([r[1] for r in results]), part))
    print(f"\nfresh processes, {args.repeat} fresh install(s): min (max)")
    print_table(("case", "wall [s]", "CPU [s]", "inside the process"), rows)
    print(f"load average after: {', '.join(f'{x:.1f}' for x in os.getloadavg())}")
    examples = min(r[1] for r in cases["blockdae examples, first"])
    bars = [(f"blockdae examples, first run: {examples:.1f} s CPU < {EXAMPLES_BAR_S:g} s", examples < EXAMPLES_BAR_S)]
    if not args.quick:
        analysis = min(r[2]["analysis_cpu"] for r in cases["app, first start, clicked after warm-up"])
        bars.append((f"the app's first analysis once its solvers are ready: {analysis:.1f} s CPU < "
                     f"{APP_ANALYSIS_BAR_S:g} s", analysis < APP_ANALYSIS_BAR_S))
    for text, ok in bars:
        print(f"bar {text}: {verdict(ok, args.quick)}")
    return 0 if all(ok for _, ok in bars) else 1


if __name__ == "__main__":
    sys.exit(main())
