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

Runs under such a controller step in the nodal basis (``discretisation.basis`` auto or nodal).
"""

from __future__ import annotations

import math
from typing import Any, ClassVar, Dict, NamedTuple, Optional, Tuple


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

    #: The unit of every field.
    UNITS: ClassVar[Dict[str, str]] = {
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
    """The object's ``continuous`` part as (k1, k2, a, b), checked: finite and ≥ 0."""
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
    for name, v in zip(Continuous._fields, values):
        if not (math.isfinite(v) and v >= 0.0):
            raise ConfigError(f"controller.continuous.{name} = {v}: must be finite and in [0, inf)")
    return (values[0], values[1], values[2], values[3])


def check_callable(obj: Any) -> None:
    """Refuse an object that cannot be called as f(t, tip)."""
    from .errors import ConfigError

    if not callable(obj):
        raise ConfigError(
            f"controller: expected 'none', 'pd', 'ftdo', 'dobc' or a callable f(t, tip) -> (tau1, tau2); "
            f"got {type(obj).__name__}"
        )
