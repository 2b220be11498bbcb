"""A ``gymnasium.Env`` over :class:`wingcheck.Wing` (needs ``pip install gymnasium``).

Observation: the 11 fields of :class:`wingcheck.Tip` as float64 (t, q, θ, q̇, θ̇, q''', θ',
∫τ1, ∫τ2, ∫q''', ∫θ' over the last sample period; SI units, ``Tip.units()``). Action: the held
inputs (tau1 (N), tau2 (N m)) in [−tau_max, tau_max]. One step is one sample period T_s;
the episode is truncated at t_end. Reward: a choice, replaceable with ``reward=f(tip, action,
info)``; the default −(q² + θ²)·T_s penalises the tip's displacement and twist (units m² s +
rad² s, added as numbers).
"""

from __future__ import annotations

from typing import Any, Callable, Dict, Optional, Tuple

import gymnasium
import numpy as np
from gymnasium import spaces

from ._control import Tip, Wing

Reward = Callable[[Tip, np.ndarray, Dict[str, float]], float]


def tip_penalty(tip: Tip, action: np.ndarray, info: Dict[str, float], period: float) -> float:
    """−(q² + θ²)·T_s: the default reward."""
    return -(tip.q**2 + tip.theta**2) * period


class WingEnv(gymnasium.Env):  # type: ignore[misc]
    """The wing as a gymnasium environment (see the module documentation)."""

    metadata: Dict[str, Any] = {"render_modes": []}

    def __init__(
        self,
        config: Any = None,
        *,
        set: Any = None,
        continuous: Any = None,
        tau_max: float = 10.0,
        reward: Optional[Reward] = None,
    ) -> None:
        self.wing = Wing(config, set=set, continuous=continuous)
        self.observation_space = spaces.Box(-np.inf, np.inf, shape=(len(Tip._fields),), dtype=np.float64)
        self.action_space = spaces.Box(-tau_max, tau_max, shape=(2,), dtype=np.float64)
        self._reward = reward

    def reset(self, *, seed: Optional[int] = None, options: Optional[Dict[str, Any]] = None) -> Tuple[np.ndarray, Dict[str, Any]]:
        super().reset(seed=seed)
        tip = self.wing.reset()
        return np.asarray(tip, dtype=np.float64), {"t": tip.t}

    def step(self, action: Any) -> Tuple[np.ndarray, float, bool, bool, Dict[str, Any]]:
        a = np.asarray(action, dtype=np.float64).reshape(2)
        tip, info = self.wing.step((float(a[0]), float(a[1])))
        if self._reward is None:
            r = tip_penalty(tip, a, info, self.wing.sample_period)
        else:
            r = float(self._reward(tip, a, info))
        truncated = tip.t >= self.wing.t_end - 0.5 * self.wing.sample_period
        return np.asarray(tip, dtype=np.float64), float(r), False, bool(truncated), dict(info)
