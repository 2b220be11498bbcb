"""compare (issue 43): rows with error bars from the --error-estimate refinements; the FTDO and
DOBC rows agree with `check`'s ftdo-vs-dobc evidence; a controller of your own sits beside them."""

from __future__ import annotations

import json

import numpy as np

import wingcheck

# compare's labels → the ftdo-vs-dobc evidence keys of `check --json`
SHARED = {
    "RMS q(s,t) over [t_end/2, t_end]": "rms_q_late",
    "peak |q(s,t)|": "peak_q",
    "RMS θ(s,t) over [t_end/2, t_end]": "rms_theta_late",
    "peak |θ(s,t)|": "peak_theta",
    "q(s,t) settling time": "settle_q",
    "θ(s,t) settling time": "settle_theta",
    "RMS τ1": "rms_tau1",
    "peak |τ1|": "peak_tau1",
    "RMS τ2": "rms_tau2",
    "peak |τ2|": "peak_tau2",
}


def check_runs(ledger: wingcheck.Ledger) -> dict:
    """The ftdo-vs-dobc row's runs at the configured gains, by controller."""
    doc = json.loads(ledger.to_json())
    row = next(r for r in doc["rows"] if r["id"] == "ftdo-vs-dobc")
    runs = {}
    for r in row["evidence"]["runs"]["rows"]:
        name = "DOBC" if r["run"]["value"] == "DOBC" else "FTDO"
        if name in runs:  # the FTDO's configured rule comes first; the other rule is secondary
            continue
        runs[name] = r
    return runs


def test_ftdo_and_dobc_rows_agree_with_checks_evidence():
    # Reference: `check`'s own ftdo-vs-dobc runs (the same runs of the same configuration): every
    # quantity both report must agree within compare's error bar (here: to round-off).
    c = wingcheck.compare(None, {"FTDO": "ftdo", "DOBC": "dobc"})
    runs = check_runs(wingcheck.check())
    for name in ["FTDO", "DOBC"]:
        for label, key in SHARED.items():
            theirs = runs[name][key]["value"]
            mine, err = c.value(name, label)
            assert abs(mine - theirs) <= err + 1e-12 * abs(theirs), (name, label, mine, err, theirs)


def test_every_value_has_an_error_and_settling_includes_the_sampling():
    c = wingcheck.compare(None, {"FTDO": "ftdo"})
    dt_out = wingcheck.Config()["horizon"]["sample_every"]
    row = c.rows["FTDO"]
    assert len(row) == len(c.columns)
    for label, (v, e) in row.items():
        assert np.isfinite(v) and e >= 0.0, label
    assert row["q(s,t) settling time"][1] >= dt_out
    assert "error-estimate" in c.error_rule
    assert {cid for cid, _ in c.not_applicable} >= {"W-bounds", "UUB", "finite-time"}


def test_an_own_controller_row_beside_the_paper_ones():
    # a saturated PD: |τ| ≤ 0.5 (N, N m) on the paper's law (15) without observer
    k1, k2 = 2.0, 1.0

    def saturated_pd(t, tip):
        sat = lambda u: max(-0.5, min(0.5, u))  # noqa: E731
        return (sat(-k1 * (tip.q + tip.q_rate)), sat(-k2 * (tip.theta + tip.theta_rate)))

    c = wingcheck.compare(None, {"mine": saturated_pd, "FTDO": "ftdo", "DOBC": "dobc"})
    assert list(c.rows) == ["mine", "FTDO", "DOBC"]
    # your own row steps in the basis `auto` resolves to, as the built-in rows do
    assert c.basis["mine"] == c.basis["FTDO"] == "modal"
    # the held input never exceeds the saturation (full-rate peak of τ, sample-and-hold of u)
    assert c.value("mine", "peak |τ1|")[0] <= 0.5 + 1e-12
    assert c.value("mine", "peak |τ2|")[0] <= 0.5 + 1e-12
    df = c.to_pandas()
    assert list(df.index) == ["mine", "FTDO", "DOBC"]
