//! The time scheme and the stepping basis of a run: what `discretisation.stepper` and
//! `discretisation.basis` offer, and how `auto` resolves for a configuration.

use serde::{Deserialize, Serialize};

use crate::{Config, ControllerKind, Method, ObserverRule, UnknownName};

/// Time integrator of the closed loop.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum TimeScheme {
    /// `exponential` for the explicit FTDO stepped in the modal basis (its estimate alternates
    /// at the sample rate, which one TR-BDF2 step per sample resolves only to 1–2 % in RMS τ),
    /// `trbdf2` otherwise; [`Config::time_scheme`] resolves it, and runs report the result.
    #[default]
    Auto,
    /// TR-BDF2 (γ = 2 − √2): second order, L-stable (no ringing of the stiff Kelvin–Voigt
    /// modes under the observer's zero-order-hold jumps), two solves with one step matrix.
    Trbdf2,
    /// The trapezoidal rule: second order, A-stable, one solve per step, exact discrete energy
    /// balance; its stiff modes ring (amplification → −1) under sampled discontinuous inputs.
    Trapezoid,
    /// The exact transition e^{Ah} of the semi-discrete closed loop over each step with the
    /// inputs held (ĝ exactly, g and the distributed load as their step means), with the exact
    /// ∫τ² dt in each step: τ statistics independent of dt at a fixed observer period. Modal
    /// basis only; one dense product per step (≈ 7× a TR-BDF2 step on the default grid) after an
    /// O(n³) setup (≈ 8× TR-BDF2 per default 20-s run).
    Exponential,
}

impl TimeScheme {
    /// Name as used on the command line and in outputs.
    pub fn name(self) -> &'static str {
        match self {
            TimeScheme::Auto => "auto",
            TimeScheme::Trbdf2 => "trbdf2",
            TimeScheme::Trapezoid => "trapezoid",
            TimeScheme::Exponential => "exponential",
        }
    }
}

impl std::fmt::Display for TimeScheme {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(self.name())
    }
}

impl std::str::FromStr for TimeScheme {
    type Err = UnknownName;
    fn from_str(s: &str) -> Result<Self, UnknownName> {
        match s {
            "auto" => Ok(Self::Auto),
            "trbdf2" => Ok(Self::Trbdf2),
            "trapezoid" => Ok(Self::Trapezoid),
            "exponential" => Ok(Self::Exponential),
            _ => Err(UnknownName {
                what: "time scheme",
                given: s.into(),
                allowed: "auto, trbdf2, trapezoid, exponential",
            }),
        }
    }
}

/// Basis in which the semi-discrete closed loop is stepped (the same discrete equations and
/// scheme either way, so the two agree to round-off).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum StepBasis {
    /// `modal` where [`Config::expected_modal`] expects it (up to [`MODAL_AUTO_UNKNOWNS`]
    /// unknowns, above it where the basis's setup is repaid by its cheaper steps) if the modal
    /// basis passes its check, `nodal` otherwise.
    #[default]
    Auto,
    /// The wing's modal basis (K Φ = M Φ Ω², one dense SVD per run): the step
    /// matrix is diagonal plus rank 2, solved by the Woodbury identity in O(n) per solve.
    Modal,
    /// The nodal unknowns: banded Cholesky of the step matrix, O(n·bandwidth) per solve.
    Nodal,
}

/// Largest number of unknowns stepped in the modal basis at all: FD 1 536 intervals, FE 1 024
/// elements. The basis is one O(n³) singular value decomposition per run (≈ 2 s CPU at 1 536
/// unknowns, ≈ 16 s at 3 072; [`crate::work::SECONDS_PER_MODAL_SETUP_CUBE`]), accurate at any
/// of these sizes (`wingcheck_sim::modal::BasisQuality`).
pub const MODAL_MAX_UNKNOWNS: usize = 3072;

/// Up to this many unknowns `basis = "auto"` always steps in the modal basis (FE ≤ 100
/// elements, FD ≤ 150 intervals): its setup is then ≤ 20 ms, below the cost of any run's
/// steps. Above it `auto` compares the estimated costs ([`Config::expected_modal`]).
pub const MODAL_AUTO_UNKNOWNS: usize = 300;

/// Measured CPU seconds of the modal basis's setup per unknown³ (the SVD and its check, once
/// per run): 0.11 s at 576 unknowns (5.8e-10), 0.6 s at 1 152 (3.9e-10), 2.3 s at 1 536
/// (6.3e-10), on the 2-core development machine; the largest is used. The `auto` choice's
/// constant, not an upper estimate (that is [`crate::work::SECONDS_PER_MODAL_SETUP_CUBE`]).
pub const MODAL_SETUP_SECONDS_PER_CUBE: f64 = 6.5e-10;

/// Measured CPU seconds a nodal TR-BDF2 step costs per unknown beyond a modal one: 2.2e-8 s
/// nodal (banded factor) against 1.7e-9 s modal at 1 152 unknowns (default 20-s run, its
/// 42 222 steps with the initial layer's: 1.08 s nodal, 0.68 s modal with its setup).
pub const NODAL_EXTRA_SECONDS_PER_UNKNOWN_STEP: f64 = 2.0e-8;

impl StepBasis {
    /// Name as used on the command line and in outputs.
    pub fn name(self) -> &'static str {
        match self {
            StepBasis::Auto => "auto",
            StepBasis::Modal => "modal",
            StepBasis::Nodal => "nodal",
        }
    }
}

impl std::fmt::Display for StepBasis {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(self.name())
    }
}

impl std::str::FromStr for StepBasis {
    type Err = UnknownName;
    fn from_str(s: &str) -> Result<Self, UnknownName> {
        match s {
            "auto" => Ok(Self::Auto),
            "modal" => Ok(Self::Modal),
            "nodal" => Ok(Self::Nodal),
            _ => Err(UnknownName { what: "basis", given: s.into(), allowed: "auto, modal, nodal" }),
        }
    }
}

impl Config {
    /// Unknowns (displacement degrees of freedom) of the discretisation: FE 3 per element (q, q'
    /// per node and θ per node, root clamped), FD 2 per grid interval (q, θ per node but the
    /// root's) — the number `discretisation.basis = auto` compares with [`MODAL_AUTO_UNKNOWNS`].
    pub fn unknowns(&self) -> usize {
        match self.discretisation.method {
            Method::Fe => 3 * self.discretisation.elements,
            Method::Fd => 2 * self.discretisation.fd_points,
        }
    }

    /// The time scheme a run is expected to use, before its basis is built: the modal basis is
    /// expected for `basis = modal`, for `stepper = exponential` and for `basis = auto` where
    /// [`Config::expected_modal`] says so (its orthonormality check may still send the run to the
    /// nodal basis, and `auto` then means the cheaper TR-BDF2). For work estimates.
    pub fn expected_time_scheme(&self) -> TimeScheme {
        self.time_scheme(self.expected_modal())
    }

    /// Whether a run is expected in the modal basis (see [`Config::expected_time_scheme`]); for
    /// `basis = auto` the choice the simulator makes: modal for `stepper = exponential` (modal
    /// only), up to [`MODAL_AUTO_UNKNOWNS`] unknowns, and up to [`MODAL_MAX_UNKNOWNS`] — where the
    /// modal basis keeps the time scheme (not for the explicit FTDO under `stepper = auto`, which
    /// the modal basis would step by the exponential scheme, (2n)² per step) — where the
    /// basis's setup (n³·[`MODAL_SETUP_SECONDS_PER_CUBE`]) costs less than the nodal steps would
    /// cost beyond the modal ones (n·steps·[`NODAL_EXTRA_SECONDS_PER_UNKNOWN_STEP`], the run's
    /// steps with the initial layer's, which step in the same basis): for the default 20-s run
    /// at dt = 1 ms (42 222 steps) up to ≈ 1 140 unknowns (FE 380 elements).
    pub fn expected_modal(&self) -> bool {
        match self.discretisation.basis {
            StepBasis::Modal => true,
            StepBasis::Nodal => false,
            StepBasis::Auto => {
                let n = self.unknowns();
                self.discretisation.stepper == TimeScheme::Exponential
                    || n <= MODAL_AUTO_UNKNOWNS
                    || (n <= MODAL_MAX_UNKNOWNS
                        && self.time_scheme(true) != TimeScheme::Exponential
                        && self.modal_setup_repaid())
            }
        }
    }

    /// Whether the modal basis's estimated setup is repaid by its cheaper steps (see
    /// [`Config::expected_modal`]).
    fn modal_setup_repaid(&self) -> bool {
        let n = self.unknowns() as f64;
        let steps = (self.horizon.t_end / self.discretisation.dt).ceil() + crate::work::layer_steps_max(self);
        n.powi(3) * MODAL_SETUP_SECONDS_PER_CUBE <= n * steps * NODAL_EXTRA_SECONDS_PER_UNKNOWN_STEP
    }

    /// The time scheme a run of this configuration uses when stepped in the modal basis
    /// (`modal`) or the nodal one: `discretisation.stepper`, with [`TimeScheme::Auto`] resolved to
    /// `exponential` for the explicit FTDO in the modal basis and to `trbdf2` otherwise.
    pub fn time_scheme(&self, modal: bool) -> TimeScheme {
        match self.discretisation.stepper {
            TimeScheme::Auto
                if modal
                    && self.control.kind == ControllerKind::Ftdo
                    && self.observer.rule == ObserverRule::Explicit =>
            {
                TimeScheme::Exponential
            }
            TimeScheme::Auto => TimeScheme::Trbdf2,
            scheme => scheme,
        }
    }
}
