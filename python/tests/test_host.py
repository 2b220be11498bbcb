"""A good citizen in a host process: the GIL released, Ctrl-C honoured within 0.1 s with no
partial output, fork after check(), and the extension's own LAPACK symbols not interposed by
a BLAS loaded RTLD_GLOBAL before it."""

from __future__ import annotations

import json
import multiprocessing
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import pytest

import wingcheck


def test_the_gil_is_released_during_a_run():
    counter = [0]
    stop = threading.Event()

    def spin():
        while not stop.is_set():
            counter[0] += 1

    th = threading.Thread(target=spin)
    th.start()
    try:
        time.sleep(0.05)
        before = counter[0]
        t0 = time.monotonic()
        wingcheck.simulate(set={"horizon.t_end": 2000}, allow_large=True)
        elapsed = time.monotonic() - t0
        advanced = counter[0] - before
    finally:
        stop.set()
        th.join()
    # a thread held off by a GIL-holding call would not advance at all during it
    assert elapsed > 0.2 and advanced > 10_000, (elapsed, advanced)


CHILD = textwrap.dedent(
    """
    import sys, time, wingcheck
    what, out = sys.argv[1], sys.argv[2]
    calls = {
        "simulate": lambda: wingcheck.simulate(set={"horizon.t_end": 4000}, out=out + "/run.csv", allow_large=True),
        "check": lambda: wingcheck.check(set={"horizon.t_end": 200}, allow_large=True),
        "search": lambda: wingcheck.search(over=["control.a=1e-3..10:log:40", "control.b=1e-2..1e3:log:40"],
                                           out=out + "/search", set={"horizon.t_end": 40}),
        "report": lambda: wingcheck.report(out=out + "/report", set={"horizon.t_end": 200}, allow_large=True),
    }
    print("ready", flush=True)
    try:
        calls[what]()
        print("finished", flush=True)
    except KeyboardInterrupt:
        print("interrupted", time.monotonic(), flush=True)
    """
)


# Every call meets 0.1 s: a run and a search read the cancel token at every observer sample and
# every point (and are waited for: they write as they go); check writes nothing and the report
# moves its directory into place through the cancel token's gate, so both raise at once while
# their worker ends the stretch it is in (exact arithmetic without a checkpoint) in the
# background — the report's staging directory is removed before the interpreter exits (the
# listing below is taken after the child has exited).
LATENCY = {"simulate": 0.1, "search": 0.1, "check": 0.1, "report": 0.1}


@pytest.mark.parametrize("what", ["simulate", "check", "search", "report"])
def test_ctrl_c_raises_keyboard_interrupt_and_writes_nothing(tmp_path, what):
    out = tmp_path / "out"
    out.mkdir()
    p = subprocess.Popen(
        [sys.executable, "-c", CHILD, what, str(out)], stdout=subprocess.PIPE, text=True, cwd=str(tmp_path)
    )
    assert p.stdout is not None
    assert p.stdout.readline().strip() == "ready"
    time.sleep(1.0)  # well inside the long call
    sent = time.monotonic()
    p.send_signal(signal.SIGINT)
    line = p.stdout.readline().split()
    p.wait(timeout=60)
    assert line and line[0] == "interrupted", line
    latency = float(line[1]) - sent
    print(f"{what}: KeyboardInterrupt {latency * 1e3:.1f} ms after SIGINT")
    assert latency < LATENCY[what], f"{what}: {latency:.3f} s"
    assert os.listdir(out) == [], os.listdir(out)


def _child_after_fork(q) -> None:
    ledger = wingcheck.check(set={"horizon.t_end": 4})
    q.put(len(ledger.rows))


def test_fork_after_check_does_not_hang():
    wingcheck.check(set={"horizon.t_end": 4})
    ctx = multiprocessing.get_context("fork")
    q = ctx.Queue()
    p = ctx.Process(target=_child_after_fork, args=(q,))
    p.start()
    p.join(timeout=120)
    hung = p.is_alive()
    if hung:
        p.kill()
    assert not hung, "the forked child hung"
    assert p.exitcode == 0 and q.get(timeout=5) == 7


# A LAPACK whose dsyevr_ (the symmetric eigen-solver of clarabel's PSD cone) answers wrongly:
# every eigenvalue 1 and the identity as eigenvectors, "successfully".
FAKE_LAPACK = r"""
void dsyevr_(const char *jobz, const char *range, const char *uplo, const int *n, double *a,
             const int *lda, const double *vl, const double *vu, const int *il, const int *iu,
             const double *abstol, int *m, double *w, double *z, const int *ldz, int *isuppz,
             double *work, const int *lwork, int *iwork, const int *liwork, int *info) {
    *info = 0;
    if (*lwork == -1 || *liwork == -1) { work[0] = 64.0 * (*n + 1); iwork[0] = 16 * (*n + 1); return; }
    *m = *n;
    for (int i = 0; i < *n; i++) {
        w[i] = 1.0;
        for (int j = 0; j < *n; j++) z[i + j * *ldz] = (i == j) ? 1.0 : 0.0;
    }
}
"""

LEDGER_CHILD = textwrap.dedent(
    """
    import ctypes, sys
    if sys.argv[1] != "-":
        ctypes.CDLL(sys.argv[1], mode=ctypes.RTLD_GLOBAL)
    import wingcheck
    print(wingcheck.check(set={"horizon.t_end": 4}).to_json(), end="")
    """
)


def test_a_blas_loaded_rtld_global_first_does_not_change_the_sdp_answer(tmp_path):
    src = tmp_path / "fake.c"
    src.write_text(FAKE_LAPACK)
    lib = tmp_path / "libfakelapack.so"
    subprocess.run(["gcc", "-shared", "-fPIC", "-O1", "-o", str(lib), str(src)], check=True)
    run = lambda arg: subprocess.run(  # noqa: E731
        [sys.executable, "-c", LEDGER_CHILD, arg], capture_output=True, text=True, check=True
    ).stdout
    clean, poisoned = run("-"), run(str(lib))
    rows = {r["id"]: r for r in json.loads(clean)["rows"]}
    # the W-bounds row carries the SDP cross-check (clarabel's PSD cone calls dsyevr_)
    assert "sdp" in json.dumps(rows["W-bounds"]["evidence"]).lower()
    assert poisoned == clean
