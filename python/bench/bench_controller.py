"""Benchmark (not a test): a trivial Python controller's 20-s run (20 000 calls at T_s = 1 ms)
against the built-in PD, alternating in one sitting. The Python controller carries the PD's
continuous part and returns (0, 0), so the loops do the same arithmetic: what differs is the
callback (GIL taken and released, a Tip record built, a tuple read back, per sample) and, in
the modal basis (`auto` on the paper's grid), how the held inputs are formed (sampled from the
modal state with the steps' quadratures for a foreign controller, replayed from the precomputed
observer signal for a built-in one). Both bases are timed. CPU time of the process (all
threads) beside wall time; the load average is printed with the numbers.

Usage: python bench_controller.py [--repeats N]
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

import wingcheck


def timed(call) -> tuple:
    w, c = time.perf_counter(), time.process_time()
    call()
    return time.perf_counter() - w, time.process_time() - c


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=7)
    a = ap.parse_args()
    c = wingcheck.Config()["control"]
    calls = [0]

    class Trivial:
        continuous = (c["k1"], c["k2"], c["a"], c["b"])

        def __call__(self, t, tip):
            calls[0] += 1
            return (0.0, 0.0)

    nodal = {"discretisation.basis": "nodal"}
    cases = {
        "python controller (auto: modal)": lambda: wingcheck.simulate(controller=Trivial()),
        "built-in pd (auto: modal)": lambda: wingcheck.simulate(controller="pd"),
        "python controller (nodal)": lambda: wingcheck.simulate(controller=Trivial(), set=nodal),
        "built-in pd (nodal)": lambda: wingcheck.simulate(controller="pd", set=nodal),
    }
    for f in cases.values():  # warm-up
        f()
    calls[0] = 0
    times = {k: [] for k in cases}
    for _ in range(a.repeats):
        for k, f in cases.items():
            times[k].append(timed(f))
    load = os.getloadavg()
    print(f"load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}; medians of {a.repeats}, one sitting")
    print(f"controller calls per python run: {calls[0] // (2 * a.repeats)}")
    med = {k: (statistics.median(w for w, _ in v), statistics.median(c for _, c in v)) for k, v in times.items()}
    for k, (w, cpu) in med.items():
        print(f"{k:28s} wall {1e3 * w:8.1f} ms   CPU {1e3 * cpu:8.1f} ms")
    for basis in ["auto: modal", "nodal"]:
        py, r = med[f"python controller ({basis})"], med[f"built-in pd ({basis})"]
        print(f"ratio python / built-in pd ({basis}): wall {py[0] / r[0]:.2f}, CPU {py[1] / r[1]:.2f}")


if __name__ == "__main__":
    main()
