"""Benchmark (not a test): the default simulate in-process against the command line writing
run.csv and pandas reading it, alternating in one sitting; and the import time of wingcheck
against that of numpy (which it imports). CPU time is reported beside wall time because other
load on the machine disturbs wall time; the load average is printed with the numbers.

Usage: python bench_simulate.py [--cli PATH] [--repeats N]
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time


def children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def in_process(wingcheck) -> tuple:
    w, c = time.perf_counter(), time.process_time()
    run = wingcheck.simulate()
    df = run.to_pandas()
    assert len(df) > 0
    return time.perf_counter() - w, time.process_time() - c


def via_cli(cli: str, pd, work: str) -> tuple:
    from wingcheck._results import exact_floats

    path = os.path.join(work, "run.csv")
    w, c, k = time.perf_counter(), time.process_time(), children_cpu()
    subprocess.run([cli, "simulate", "--out", path], check=True, stdout=subprocess.DEVNULL)
    df = pd.read_csv(path, **exact_floats(pd))
    assert len(df) > 0
    return time.perf_counter() - w, (time.process_time() - c) + (children_cpu() - k)


def import_seconds(module: str, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        w = time.perf_counter()
        subprocess.run([sys.executable, "-c", f"import {module}"], check=True)
        times.append(time.perf_counter() - w)
    return statistics.median(times)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", default=os.environ.get("WINGCHECK_CLI") or shutil.which("wingcheck"))
    ap.add_argument("--repeats", type=int, default=7)
    a = ap.parse_args()
    import pandas as pd

    import wingcheck

    print(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f} at the start")
    wingcheck.simulate()  # warm-up: pages in the extension
    rows = {"in-process simulate + to_pandas": [], "CLI simulate --out run.csv + pd.read_csv": []}
    with tempfile.TemporaryDirectory() as work:
        for _ in range(a.repeats):
            rows["in-process simulate + to_pandas"].append(in_process(wingcheck))
            rows["CLI simulate --out run.csv + pd.read_csv"].append(via_cli(a.cli, pd, work))
    med = {k: (statistics.median(x[0] for x in v), statistics.median(x[1] for x in v)) for k, v in rows.items()}
    for k, (w, c) in med.items():
        print(f"{k:<45} wall {w * 1e3:8.1f} ms   CPU {c * 1e3:8.1f} ms   (median of {a.repeats})")
    (wi, ci), (wc, cc) = med.values()
    print(f"ratio in-process / CLI: wall {wi / wc:.2f}, CPU {ci / cc:.2f}")
    n, wc_ = import_seconds("numpy", a.repeats), import_seconds("wingcheck", a.repeats)
    print(f"python -c 'import numpy': {n * 1e3:.0f} ms; 'import wingcheck' (imports numpy): {wc_ * 1e3:.0f} ms; "
          f"ratio {wc_ / n:.2f} (median of {a.repeats} fresh interpreters)")
    print(f"load average {os.getloadavg()[0]:.2f} at the end")


if __name__ == "__main__":
    main()
