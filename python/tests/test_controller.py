"""Controllers of your own (issue 43): the paper's PD and explicit FTDO written in Python
reproduce the built-in ones; a controller that raises, returns NaN, returns three numbers or
destabilises the loop stops the run with a clear error naming the time, and nothing is written."""

from __future__ import annotations

import json
import math
import os
import threading
import traceback

import numpy as np
import pytest

import wingcheck
from wingcheck.errors import ControllerError, DivergedError

PAPER = wingcheck.Config()
# the state columns of run.csv
STATE = ["q_tip_m", "theta_tip_rad", "q_tip_rate_m_per_s", "theta_tip_rate_rad_per_s", "energy_J"]


class PaperPD:
    """Law (15) without an observer: the continuous part k(a x + b v) and no held input."""

    def __init__(self, cfg: wingcheck.Config) -> None:
        c = cfg["control"]
        self.continuous = wingcheck.Continuous(c["k1"], c["k2"], c["a"], c["b"])

    def __call__(self, t: float, tip: wingcheck.Tip):
        return (0.0, 0.0)


def sign(x: float) -> float:
    return 0.0 if x == 0.0 else math.copysign(1.0, x)


class ExplicitFTDO:
    """The paper's FTDO (16)–(21), explicit rule ĝ_k = φ(σ_k), written from the paper:
    σ = s ξ S w − ν (s = −1, S = EI for bending; s = +1, S = GJ for torsion), ν̇ = ĝ + τ − s S w,
    φ(σ) = κ_lin σ + κ_sw sign σ + κ_frac sign(σ)|σ|^r, r = (2a1 − a2)/a2; u = −ĝ."""

    def __init__(self, cfg: wingcheck.Config) -> None:
        c, o, w = cfg["control"], cfg["observer"], cfg["wing"]
        self.continuous = (c["k1"], c["k2"], c["a"], c["b"])
        self.T = o["sample_period"]
        self.xi = w["xi"]
        self.S = (w["ei"], w["gj"])
        self.s = (-1.0, 1.0)
        self.gain = (
            (o["kappa1"], o["kappa2"], o["kappa3"], (2 * o["a1"] - o["a2"]) / o["a2"]),
            (o["kappa4"], o["kappa5"], o["kappa6"], (2 * o["b1"] - o["b2"]) / o["b2"]),
        )
        self.nu0 = (o["nu1_0"], o["nu2_0"])
        self.reset()

    def reset(self) -> None:
        self.nu = list(self.nu0)
        self.g_hat = [0.0, 0.0]

    def phi(self, c: int, sigma: float) -> float:
        lin, sw, frac, r = self.gain[c]
        return lin * sigma + sw * sign(sigma) + frac * sign(sigma) * abs(sigma) ** r

    def __call__(self, t: float, tip: wingcheck.Tip):
        w = (tip.q_shear, tip.theta_slope)
        tau_int = (tip.tau1_integral, tip.tau2_integral)
        w_int = (tip.q_shear_integral, tip.theta_slope_integral)
        out = []
        for c in range(2):
            if t > 0.0:
                # ν over the period that just ended, with the estimate held over it
                self.nu[c] += self.T * self.g_hat[c] + tau_int[c] - self.s[c] * self.S[c] * w_int[c]
            sigma = self.s[c] * self.xi * self.S[c] * w[c] - self.nu[c]
            self.g_hat[c] = self.phi(c, sigma)
            out.append(-self.g_hat[c])
        return tuple(out)


@pytest.mark.parametrize("basis", ["auto", "nodal"])
def test_python_pd_reproduces_the_builtin_pd(basis):
    # Reference: the built-in PD in the same basis (auto: modal on the paper's grid). The held
    # input is 0 either way and the continuous part is the same law (15) in the same loop, so the
    # state is the same bits (the ĝ columns may differ in the sign of zero only; σ is the
    # built-in observer's in its run and 0 in yours).
    mine = wingcheck.simulate(controller=PaperPD(PAPER), set={"discretisation.basis": basis})
    ref = wingcheck.simulate(controller="pd", set={"discretisation.basis": basis})
    assert mine.summary["stats"]["basis"] == ref.summary["stats"]["basis"]
    assert mine.summary["stats"]["basis"] == ("nodal" if basis == "nodal" else "modal")
    for col in STATE + ["tau1_N", "tau2_N_m", "tau1_rms_N"]:
        assert np.array_equal(mine[col], ref[col]), col


@pytest.mark.parametrize("ab", [{}, {"control.a": 1, "control.b": 3000}])
def test_python_explicit_ftdo_reproduces_the_builtin_within_1e_9(ab):
    # Reference: the built-in explicit FTDO in the nodal basis. The Python observer integrates ν
    # from the period integrals the simulator hands over (its own quadrature), so the two differ
    # by the rounding of T·ĝ + ∫τ − sS∫w against h(ĝ + τ̄ − sS w̄) only. (In the modal basis
    # the built-in observer advances σ by h(ḡ − ĝ) instead, and the explicit rule's sign(σ)
    # turns that round-off into switching differences: ~1e-5, the size of the built-in's own
    # nodal–modal difference; crates/sim/tests/foreign_modal.rs.)
    cfg = PAPER.with_overrides(dict(ab, **{"discretisation.basis": "nodal"}))
    mine = wingcheck.simulate(cfg, controller=ExplicitFTDO(cfg))
    ref = wingcheck.simulate(cfg, controller="ftdo", observer="explicit")
    for col in ["q_tip_m", "theta_tip_rad"]:
        scale = np.max(np.abs(ref[col]))
        err = np.max(np.abs(mine[col] - ref[col])) / scale
        print(f"explicit FTDO {ab} {col}: max relative difference {err:.2e}")
        assert err <= 1e-9, (col, err)


def test_the_controller_is_sampled_at_k_ts_and_reset_before_every_run():
    # __call__ at t_k = k T_s, k = 0..K, once each, in order, in every run; reset() before each
    # (simulate's base run first, then the initial layer's runs at finer steps, same T_s).
    class Recorder:
        def __init__(self) -> None:
            self.runs = []

        def reset(self) -> None:
            self.runs.append([])

        def __call__(self, t, tip):
            assert tip.t == t
            self.runs[-1].append(t)
            return (0.0, 0.0)

    rec = Recorder()
    cfg = PAPER.with_overrides({"horizon.t_end": 0.05})
    wingcheck.simulate(cfg, controller=rec)
    T = cfg["observer"]["sample_period"]
    assert len(rec.runs[0]) == round(0.05 / T) + 1
    for times in rec.runs:
        # t_k = k T_s as the simulator computes it
        assert times == [k * T for k in range(len(times))]


def test_an_exception_inside_the_controller_propagates_with_its_traceback():
    class Boom(RuntimeError):
        pass

    def f(t, tip):
        if t >= 0.5:
            raise Boom(f"controller gave up at {t}")
        return (0.0, 0.0)

    with pytest.raises(Boom) as info:
        wingcheck.simulate(PAPER.with_overrides({"horizon.t_end": 1.0}), controller=f)
    frames = [fr.name for fr in traceback.extract_tb(info.value.__traceback__)]
    assert "f" in frames, frames


@pytest.mark.parametrize(
    "bad, what",
    [((float("nan"), 0.0), "tau1 = NaN"), ((0.0, float("inf")), "tau2 = inf"), ((1.0, 2.0, 3.0), "3 or more items")],
)
def test_bad_outputs_name_the_time(bad, what, tmp_path):
    def f(t, tip):
        return bad if t >= 0.25 else (0.0, 0.0)

    out = tmp_path / "run.csv"
    with pytest.raises(ControllerError) as info:
        wingcheck.simulate(PAPER.with_overrides({"horizon.t_end": 1.0}), controller=f, out=out)
    assert what in str(info.value), str(info.value)
    assert "t = 0.25" in str(info.value), str(info.value)
    assert info.value.t == 0.25
    assert not out.exists()


def test_a_destabilising_controller_stops_with_time_and_reason(tmp_path):
    # positive feedback on the tip rate pumps energy in: the loop diverges
    def f(t, tip):
        return (1e3 * tip.q_rate, 1e3 * tip.theta_rate)

    out = tmp_path / "run.csv"
    with pytest.raises(DivergedError) as info:
        wingcheck.simulate(controller=f, out=out)
    assert 0.0 < info.value.t < 20.0
    assert "diverged at t =" in str(info.value)
    assert not out.exists()
    assert os.listdir(tmp_path) == []


def test_other_threads_run_while_a_python_controller_runs():
    # the loop holds the GIL only for the controller's calls
    ticks = []
    stop = threading.Event()

    def spin():
        while not stop.is_set():
            ticks.append(1)

    th = threading.Thread(target=spin)
    th.start()
    try:
        wingcheck.simulate(controller=lambda t, tip: (0.0, 0.0))
    finally:
        stop.set()
        th.join()
    assert len(ticks) > 100


def test_bad_continuous_part_is_a_config_error():
    class Neg:
        continuous = (1.0, 1.0, -1.0, 1.0)

        def __call__(self, t, tip):
            return (0.0, 0.0)

    with pytest.raises(wingcheck.ConfigError, match=r"controller.continuous: a = -1 is not in \[0, "):
        wingcheck.simulate(controller=Neg())
    with pytest.raises(wingcheck.ConfigError, match=r"controller"):
        wingcheck.simulate(controller=42)  # type: ignore[arg-type]


@pytest.mark.parametrize("stepper", ["trapezoid", "exponential"])
def test_a_python_controller_runs_in_the_modal_basis_with_either_scheme(stepper):
    # Reference: the built-in PD in the modal basis with the same scheme: the same bits of the
    # state (see test_python_pd_reproduces_the_builtin_pd).
    set_ = {"discretisation.basis": "modal", "discretisation.stepper": stepper, "horizon.t_end": 2.0}
    mine = wingcheck.simulate(controller=PaperPD(PAPER), set=set_)
    ref = wingcheck.simulate(controller="pd", set=set_)
    assert mine.summary["stats"]["basis"] == "modal"
    assert mine.summary["stats"]["stepper"] == stepper
    for col in STATE:
        assert np.array_equal(mine[col], ref[col]), col


class RecordingFTDO(ExplicitFTDO):
    """The explicit FTDO recording every measurement it is given, one list per run."""

    def __init__(self, cfg: wingcheck.Config) -> None:
        self.runs: list = []
        super().__init__(cfg)

    def reset(self) -> None:
        super().reset()
        self.runs.append([])

    def __call__(self, t: float, tip: wingcheck.Tip):
        self.runs[-1].append(tuple(tip))
        return super().__call__(t, tip)


@pytest.mark.parametrize("basis", ["auto", "nodal"])
def test_the_step_form_gives_the_callback_forms_bits(basis):
    # Reference: simulate(controller=f) with the same controller and configuration, whose
    # controller records what it was given at every sample of its base run (the first after
    # construction; the initial layer's runs follow). The step form is that run with the held
    # inputs handed in from outside (modal under auto, as the callback form), so it gives the
    # same measurements at every sample, and the run's energies at its output samples.
    cfg = PAPER.with_overrides({"horizon.t_end": 2.0, "discretisation.basis": basis})
    recorded = RecordingFTDO(cfg)
    run = wingcheck.simulate(cfg, controller=recorded)
    assert run.summary["stats"]["basis"] == ("nodal" if basis == "nodal" else "modal")
    base = next(r for r in recorded.runs if r)
    ctrl = ExplicitFTDO(cfg)
    c = cfg["control"]
    wing = wingcheck.Wing(cfg, continuous=(c["k1"], c["k2"], c["a"], c["b"]))
    tip = wing.reset()
    every = round(cfg["horizon"]["sample_every"] / cfg["observer"]["sample_period"])
    seen, energy = [tuple(tip)], []
    while tip.t < 2.0 - 1e-12:
        tip, info = wing.step(ctrl(tip.t, tip))
        assert info["t"] == tip.t
        seen.append(tuple(tip))
        if len(seen) % every == 1:
            energy.append(info["energy_J"])
    assert len(seen) == len(base)
    assert seen == base
    assert np.array_equal(np.array(energy), run["energy_J"][1:])
    # the run ends at its horizon
    with pytest.raises(wingcheck.ConfigError, match="horizon"):
        wing.step((0.0, 0.0))


def test_the_step_form_refuses_bad_actions_and_reports_divergence():
    wing = wingcheck.Wing()
    wing.reset()
    with pytest.raises(ControllerError, match="t = 0"):
        wing.step((1.0, 2.0, 3.0))
    with pytest.raises(ControllerError, match="tau2 = NaN"):
        wing.step((0.0, float("nan")))
    tip = wing.reset()
    with pytest.raises(DivergedError):
        for _ in range(20000):
            tip, _ = wing.step((1e3 * tip.q_rate, 1e3 * tip.theta_rate))


def test_gymnasium_env_passes_check_env():
    gymnasium = pytest.importorskip("gymnasium")
    from gymnasium.utils.env_checker import check_env

    from wingcheck.gym import WingEnv

    env = WingEnv(set={"horizon.t_end": 0.05})
    check_env(env, skip_render_check=True)
    obs, info = env.reset(seed=0)
    assert obs.shape == (11,)
    steps, truncated = 0, False
    while not truncated:
        obs, r, terminated, truncated, info = env.step(env.action_space.sample() * 0.0)
        steps += 1
        assert r <= 0.0 and not terminated
    assert steps == 50


def test_the_tip_record_has_eleven_fields_with_units():
    assert len(wingcheck.Tip._fields) == 11
    assert set(wingcheck.Tip.units()) == set(wingcheck.Tip._fields)


def test_the_error_estimate_runs_a_python_controller_with_reset_per_run():
    # Reference: the built-in PD through the same --error-estimate machinery, in the same (modal)
    # basis: the same refinements and the same exponential twin give the same tip errors (bits).
    class PD(PaperPD):
        resets = 0

        def reset(self) -> None:
            PD.resets += 1

    mine = wingcheck.simulate(controller=PD(PAPER), error_estimate=True)
    ref = wingcheck.simulate(controller="pd", error_estimate=True)
    a, b = mine.summary["error_estimate"], ref.summary["error_estimate"]
    for key in ["max_q_tip_error", "max_theta_tip_error", "max_space_error", "max_time_error"]:
        assert a[key] == b[key], key
    # base run + its initial layer runs + the 2N and dt/2 runs (each with their layers) + 4N
    assert PD.resets >= 4


def test_search_runs_a_python_controller_at_every_point(tmp_path):
    # Reference: the same search under the built-in PD. The Python PD's continuous part is the
    # paper's law (15) at the base point, so the axes sweep something else (ξ): the same law in
    # the same loop at every point, the same bits (crates/search/tests/own_controller.rs).
    over = ["wing.xi=0.01,0.02"]
    set_ = {"horizon.t_end": 2, "control.kind": "pd"}
    ref = wingcheck.search(over=over, out=tmp_path / "ref", set=set_, threads=1)
    mine = wingcheck.search(over=over, out=tmp_path / "mine", set=set_, threads=1, controller=PaperPD(PAPER))
    with open(ref.results_csv) as a, open(mine.results_csv) as b:
        assert a.read() == b.read()
    with open(os.path.join(mine.out_dir, "manifest.json")) as f:
        assert json.load(f)["options"]["controller"] == "PaperPD"
    with pytest.raises(wingcheck.ConfigError, match="control.kind"):
        wingcheck.search(over=over, out=tmp_path / "x", controller="pd")


def test_a_search_with_a_stateful_python_controller_runs_its_points_one_at_a_time(tmp_path):
    # The explicit FTDO carries ν from call to call. Reference: the same search with threads=1
    # given explicitly; left to its default (all cores) it must give the same file, which
    # points run in parallel on the one object would not (their calls would interleave).
    over = ["wing.xi=0.01,0.02,0.03,0.04"]
    set_ = {"horizon.t_end": 0.5}
    one = wingcheck.search(over=over, out=tmp_path / "one", set=set_, threads=1, controller=ExplicitFTDO(PAPER))
    default = wingcheck.search(over=over, out=tmp_path / "default", set=set_, controller=ExplicitFTDO(PAPER))
    with open(one.results_csv) as a, open(default.results_csv) as b:
        assert a.read() == b.read()
    with pytest.raises(wingcheck.ConfigError, match="threads"):
        wingcheck.search(over=over, out=tmp_path / "t", set=set_, threads=2, controller=ExplicitFTDO(PAPER))
    with pytest.raises(wingcheck.ConfigError, match=r"control\.a"):
        wingcheck.search(over=["control.a=0.5,1"], out=tmp_path / "a", controller=ExplicitFTDO(PAPER))
