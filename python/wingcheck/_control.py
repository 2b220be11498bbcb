"""Controllers of your own: the tip record they read and how an object is taken apart.

A controller is a callable ``f(t, tip) -> (tau1, tau2)`` or an object with ``__call__`` and,
optionally, ``continuous`` and ``reset()``:

- ``__call__(t, tip)`` is called once per sample period T_s = ``observer.sample_period`` at
  t_k = k T_s (k = 0, 1, …, from t = 0), with the measurements taken at t_k (no delay), and
  returns the held inputs (tau1 in N, tau2 in N m), applied by zero-order hold over
  [t_k, t_k + T_s);
- ``continuous``: the continuous linear part of law (15), ``(k1, k2, a, b)`` (N/m, N m/rad, –,
  s) or an object with those attributes: τ_c(t) = −k_c (a x_c(t) + b ẋ_c(t)) + u_c(t_k), integrated
  implicitly by the simulator at every integrator step (default: all zero);
- ``reset()``: called before every run (an error estimate makes three runs, the initial layer
  more), so that each starts from the controller's state at t = 0.

Runs under such a controller step in the basis the configuration resolves to, as the built-in
ones do (``discretisation.basis``; ``auto`` is modal on the default grid), and so does the
step form (:class:`Wing`), which is the same run driven from outside.
"""

from __future__ import annotations

import json
from typing import Any, Dict, List, NamedTuple, Optional, Tuple


class Tip(NamedTuple):
    """What a digital implementation measures at the tip at t_k (the paper's Remark 2), SI units,
    plus the integrals over the sample period that just ended (zero at t = 0) by the simulator's
    own quadrature, which an observer of (16)–(21) integrates (17)/(19) with."""

    #: t_k (s).
    t: float
    #: q(s, t_k) (m).
    q: float
    #: θ(s, t_k) (rad).
    theta: float
    #: q̇(s, t_k) (m/s).
    q_rate: float
    #: θ̇(s, t_k) (rad/s).
    theta_rate: float
    #: q'''(s, t_k) (1/m²), the tip shear state.
    q_shear: float
    #: θ'(s, t_k) (1/m), the tip slope state.
    theta_slope: float
    #: ∫ τ1 dt over [t_{k−1}, t_k] (N s).
    tau1_integral: float
    #: ∫ τ2 dt over [t_{k−1}, t_k] (N m s).
    tau2_integral: float
    #: ∫ q'''(s, t) dt over [t_{k−1}, t_k] (s/m²).
    q_shear_integral: float
    #: ∫ θ'(s, t) dt over [t_{k−1}, t_k] (s/m).
    theta_slope_integral: float

    @staticmethod
    def units() -> Dict[str, str]:
        """The unit of every field."""
        return dict(TIP_UNITS)


#: The unit of every field of :class:`Tip`.
TIP_UNITS: Dict[str, str] = {
    "t": "s",
    "q": "m",
    "theta": "rad",
    "q_rate": "m/s",
    "theta_rate": "rad/s",
    "q_shear": "1/m^2",
    "theta_slope": "1/m",
    "tau1_integral": "N s",
    "tau2_integral": "N m s",
    "q_shear_integral": "s/m^2",
    "theta_slope_integral": "s/m",
}


class Continuous(NamedTuple):
    """The continuous linear part of law (15): τ_c ⊇ −k_c (a x_c + b ẋ_c)."""

    #: k1 (N/m).
    k1: float = 0.0
    #: k2 (N m/rad).
    k2: float = 0.0
    #: a (dimensionless).
    a: float = 0.0
    #: b (s).
    b: float = 0.0


def continuous_of(obj: Any) -> Tuple[float, float, float, float]:
    """The object's ``continuous`` part as (k1, k2, a, b) (four numbers)."""
    from .errors import ConfigError

    raw: Optional[Any] = getattr(obj, "continuous", None)
    if raw is None:
        return (0.0, 0.0, 0.0, 0.0)
    try:
        if all(hasattr(raw, n) for n in Continuous._fields):
            values = tuple(float(getattr(raw, n)) for n in Continuous._fields)
        else:
            values = tuple(float(v) for v in raw)
    except (TypeError, ValueError) as e:
        raise ConfigError(f"controller.continuous: expected (k1, k2, a, b) as numbers: {e}") from None
    if len(values) != 4:
        raise ConfigError(f"controller.continuous: expected 4 numbers (k1, k2, a, b), got {len(values)}")
    # the ranges are checked by the simulator (those of control.k1, k2, a, b)
    return (values[0], values[1], values[2], values[3])


def check_callable(obj: Any) -> None:
    """Refuse an object that cannot be called as f(t, tip)."""
    from .errors import ConfigError

    if not callable(obj):
        raise ConfigError(
            f"controller: expected 'none', 'pd', 'ftdo', 'dobc' or a callable f(t, tip) -> (tau1, tau2); "
            f"got {type(obj).__name__}"
        )


class Comparison:
    """Controllers side by side (:func:`wingcheck.compare`): one row per controller, each metric
    with its error from the ``--error-estimate`` refinements (``error_rule``); ``series[name]``
    holds the base run's t (s), q (m), θ (rad), τ1 (N), τ2 (N m); ``not_applicable`` names the
    ledger's claims that say nothing about a controller of your own, and why."""

    def __init__(self, text: str) -> None:
        doc = json.loads(text)
        #: (label, unit) of each metric.
        self.columns: List[Tuple[str, str]] = [(c[0], c[1]) for c in doc["columns"]]
        #: The error rule, in words.
        self.error_rule: str = doc["error_rule"]
        #: (claim id, why it does not apply to a foreign controller).
        self.not_applicable: List[Tuple[str, str]] = [(c[0], c[1]) for c in doc["not_applicable"]]
        #: The basis each row stepped in (``modal`` or ``nodal``).
        self.basis: Dict[str, str] = {r["name"]: r["basis"] for r in doc["rows"]}
        #: name → {label: (value, error)}; a settling time never reached is absent.
        self.rows: Dict[str, Dict[str, Tuple[float, float]]] = {}
        #: name → {"t_s", "q_tip_m", "theta_tip_rad", "tau1_N", "tau2_N_m"} arrays.
        self.series: Dict[str, Dict[str, Any]] = {}
        import numpy as np

        for r in doc["rows"]:
            vals: Dict[str, Tuple[float, float]] = {}
            for q in r["values"]:
                if q is not None:
                    vals[q["label"]] = (float(q["value"]), float(q["error"]))
            self.rows[r["name"]] = vals
            names = ["t_s", "q_tip_m", "theta_tip_rad", "tau1_N", "tau2_N_m"]
            self.series[r["name"]] = {n: np.asarray(col) for n, col in zip(names, r["series"])}

    def value(self, name: str, label: str) -> Tuple[float, float]:
        """(value, error) of metric ``label`` in row ``name``."""
        return self.rows[name][label]

    def to_pandas(self) -> Any:
        """One row per controller; each metric as ``label [unit]`` and its error as ``± label``."""
        import importlib

        pd = importlib.import_module("pandas")

        data = {}
        for name, vals in self.rows.items():
            row: Dict[str, float] = {}
            for label, unit in self.columns:
                v, e = vals.get(label, (float("nan"), float("nan")))
                row[f"{label} [{unit}]"] = v
                row[f"± {label}"] = e
            data[name] = row
        df = pd.DataFrame.from_dict(data, orient="index")
        df.attrs["error_rule"] = self.error_rule
        df.attrs["not_applicable"] = self.not_applicable
        return df

    def plot(self, ax: Any = None) -> Any:
        """Tip responses and inputs of every row on common axes (matplotlib): four panels
        q (m), θ (rad), τ1 (N), τ2 (N m) against t (s). Returns the figure."""
        import importlib

        plt = importlib.import_module("matplotlib.pyplot")

        fig, axes = plt.subplots(4, 1, sharex=True, figsize=(8, 9)) if ax is None else (ax[0].figure, ax)
        keys = [("q_tip_m", "q(s,t) [m]"), ("theta_tip_rad", "θ(s,t) [rad]"), ("tau1_N", "τ1 [N]"), ("tau2_N_m", "τ2 [N m]")]
        for name, s in self.series.items():
            for a, (k, label) in zip(axes, keys):
                a.plot(s["t_s"], s[k], label=name, lw=0.8)
                a.set_ylabel(label)
        axes[-1].set_xlabel("t [s]")
        axes[0].legend()
        return fig


def _pair(action: Any, t: float) -> Tuple[float, float]:
    """(tau1, tau2) from an action, or ControllerError naming the time."""
    from .errors import ControllerError

    try:
        items = list(action)
    except TypeError:
        items = []
    if len(items) != 2:
        e = ControllerError(f"the action at t = {t} s is not a pair (tau1, tau2) of numbers: {action!r}")
        e.t = t
        raise e
    return (float(items[0]), float(items[1]))


class Wing:
    """The closed loop driven one sample period at a time (the form reinforcement-learning and
    co-simulation codes use): ``wing = Wing(config); tip = wing.reset(); tip, info =
    wing.step((tau1, tau2))``. ``step`` holds (tau1 (N), tau2 (N m)) over [t_k, t_k + T_s) on
    top of the ``continuous`` part (k1, k2, a, b) of law (15) and returns the measurements at
    t_{k+1} (a :class:`Tip`) and ``info`` = {``"t"`` (s), ``"energy_J"``}. It is the run of
    ``simulate(config, controller=f)`` with the held inputs handed in from outside (the basis
    and scheme the configuration resolves to, modal by default), so the same inputs give the
    same bits; a step past t_end raises :class:`~wingcheck.errors.ConfigError`. A diverged loop
    raises :class:`~wingcheck.errors.DivergedError`; a NaN, inf or non-pair action
    :class:`~wingcheck.errors.ControllerError`."""

    def __init__(self, config: Any = None, *, set: Any = None, continuous: Any = None) -> None:
        from . import _wingcheck
        from ._config import source

        holder = type("_C", (), {"continuous": continuous})()
        self._loop = _wingcheck.WingLoop(continuous=continuous_of(holder), **source(config, set))
        #: T_s (s) and t_end (s) of the configuration.
        self.sample_period, self.t_end = self._loop.timing()
        self._t = 0.0

    def reset(self) -> Tip:
        """Back to t = 0; the measurements there."""
        tip = Tip(*self._loop.reset())
        self._t = tip.t
        return tip

    def step(self, action: Any) -> Tuple[Tip, Dict[str, float]]:
        """Hold ``action`` = (tau1, tau2) for one sample period; the measurements after it."""
        tau1, tau2 = _pair(action, self._t)
        obs, t, energy = self._loop.step(tau1, tau2)
        tip = Tip(*obs)
        self._t = tip.t
        return tip, {"t": t, "energy_J": energy}
