"""The binding against the command line: run.csv columns bit for bit, the ledger's JSON, a
search's results.csv; verify on a report's proofs/."""

from __future__ import annotations

import csv
import json
import os

import numpy as np
import pytest

import wingcheck

from conftest import run_cli

# (keyword arguments of wingcheck.simulate, the same as CLI flags): the paper's point, the
# explicit observer, and FD (which implies grading 0) at a = 1, b = 3000
CASES = [
    ({}, []),
    ({"observer": "explicit"}, ["--observer", "explicit"]),
    (
        {"method": "fd", "set": {"control.a": 1, "control.b": 3000}},
        ["--method", "fd", "--set", "control.a=1", "--set", "control.b=3000"],
    ),
]


def read_csv_exact(path: str):
    """Every column as float64 (each entry's shortest round-trip digits read back exactly) where
    every entry is a number, else as text."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    cols = {}
    for i, h in enumerate(header):
        text = [r[i] for r in body]
        try:
            cols[h] = np.array([float(x) for x in text])
        except ValueError:
            cols[h] = text
    return header, cols


@pytest.mark.parametrize("kwargs,flags", CASES, ids=["paper", "explicit-observer", "fd-a1-b3000"])
def test_simulate_columns_equal_the_cli_run_csv_bit_for_bit(cli, tmp_path, kwargs, flags):
    run_cli(cli, ["simulate", *flags, "--out", "run.csv"], cwd=str(tmp_path))
    header, cols = read_csv_exact(str(tmp_path / "run.csv"))
    run = wingcheck.simulate(**kwargs)
    assert list(run.columns) == header
    assert len(header) == 19
    for name in header:
        a, b = run[name], cols[name]
        assert a.dtype == np.float64 and a.shape == b.shape, name
        # bit for bit: the CSV holds shortest round-trip digits, so float() gives back the f64
        assert np.array_equal(a.view(np.uint64), b.view(np.uint64)), name
    df = run.to_pandas()
    assert df.attrs["units"]["q_tip_m"] == "m" and df.attrs["provenance"]["config_sha256"] == run.config.sha256


def test_simulate_out_writes_the_cli_file(cli, tmp_path):
    run_cli(cli, ["simulate", "--out", "cli.csv"], cwd=str(tmp_path))
    wingcheck.simulate(out=tmp_path / "py.csv")
    assert (tmp_path / "py.csv").read_bytes() == (tmp_path / "cli.csv").read_bytes()


def test_simulate_summary_equals_simulate_json_but_for_wall_times(cli, tmp_path):
    doc = json.loads(run_cli(cli, ["simulate", "--json", "--sample-times", "1,2.5"], cwd=str(tmp_path)).stdout)
    run = wingcheck.simulate(sample_times=[1, 2.5])
    # wall times differ from run to run by nature; nothing else may
    for d in (doc, run.summary):
        d.pop("run_seconds")
        d["stats"].pop("setup_seconds")
        d["stats"].pop("stepping_seconds")
    assert run.summary == doc
    assert run.peaks["q_tip"].unit == "m" and run.peaks["q_tip"].error is None
    est = wingcheck.simulate(error_estimate=True, set={"horizon.t_end": 2})
    assert est.peaks["q_tip"].error is not None and est.peaks["q_tip"].error > 0


def test_check_json_equals_check_json_of_the_cli(cli, tmp_path):
    cli_text = run_cli(cli, ["check", "--json"], cwd=str(tmp_path)).stdout
    ledger = wingcheck.check()
    # the ledger JSON records no wall time or build: identical text
    assert ledger.to_json() == cli_text
    assert ledger["W-bounds"].verdict is wingcheck.Verdict.FAILS
    assert ledger["W-bounds"].basis is wingcheck.Basis.EXACT_CERTIFICATE
    df = ledger.to_pandas()
    assert list(df.index) == [r.id for r in ledger.rows]


SEARCH = ["control.a=1e-3..10:log:4", "control.b=1e-2..1e3:log:3"]


def test_search_dataframe_equals_results_csv_and_the_cli_search(cli, tmp_path):
    res = wingcheck.search(over=SEARCH, out=tmp_path / "py", threads=2, set={"horizon.t_end": 2})
    assert res.complete and res.summary["points_total"] == 12
    header, cols = read_csv_exact(res.results_csv)
    df = res.to_pandas()
    assert list(df.columns) == header
    numeric = 0
    for name in header:
        if isinstance(cols[name], np.ndarray):
            numeric += 1
            assert df[name].dtype == np.float64 or df[name].dtype == np.int64, name
            got = df[name].to_numpy().astype(np.float64)
            assert np.array_equal(got.view(np.uint64), cols[name].view(np.uint64)), name
    assert numeric >= 15
    args = ["search", "--set", "horizon.t_end=2", "--threads", "2", "--out", "cli"]
    for axis in SEARCH:
        args += ["--over", axis]
    run_cli(cli, args, cwd=str(tmp_path))
    assert (tmp_path / "cli" / "results.csv").read_bytes() == (tmp_path / "py" / "results.csv").read_bytes()
    assert len(res.best) > 0


def test_verify_on_a_reports_proofs_and_certify(tmp_path):
    cfg = wingcheck.Config(set={"horizon.t_end": 4})
    rep = wingcheck.report(cfg, out=tmp_path / "report")
    assert os.path.exists(rep.index_html)
    verified = wingcheck.verify(tmp_path / "report" / "proofs", cfg)
    assert verified.pinned and verified.config_sha256 == cfg.sha256
    assert verified.certificates and all(c.statement for c in verified.certificates)
    files, _ = wingcheck.certify(cfg, out=tmp_path / "proofs")
    assert files
    again = wingcheck.verify(tmp_path / "proofs")
    assert [c.id for c in again.certificates] == [c.id for c in verified.certificates]
    with pytest.raises(wingcheck.VerificationError, match="REJECTED"):
        wingcheck.verify(tmp_path / "proofs", set={"control.a": 0.5})


def test_modes_and_build_info(cli, tmp_path):
    doc = json.loads(run_cli(cli, ["modes", "--json"], cwd=str(tmp_path)).stdout)
    assert wingcheck.modes().document == doc
    info = wingcheck.build_info()
    assert set(info) == {"version", "commit", "tree", "describe", "rustc"}
    cli_doc = json.loads(run_cli(cli, ["simulate", "--json"], cwd=str(tmp_path)).stdout)
    assert cli_doc["provenance"]["build"]["commit"] == info["commit"]
