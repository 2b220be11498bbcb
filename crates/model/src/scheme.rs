//! The time scheme and the stepping basis of a run: what `discretisation.stepper` and
//! `discretisation.basis` offer, and how `auto` resolves for a configuration.

use serde::{Deserialize, Serialize};

use crate::{Config, ControllerKind, Method, ObserverRule};

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
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "auto" => Ok(Self::Auto),
            "trbdf2" => Ok(Self::Trbdf2),
            "trapezoid" => Ok(Self::Trapezoid),
            "exponential" => Ok(Self::Exponential),
            _ => Err(format!("unknown time scheme `{s}`: allowed auto, trbdf2, trapezoid, exponential")),
        }
    }
}

/// Basis in which the semi-discrete closed loop is stepped (the same discrete equations and
/// scheme either way, so the two agree to round-off).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum StepBasis {
    /// `modal` up to [`MODAL_AUTO_UNKNOWNS`] unknowns if the modal basis passes its
    /// orthonormality check, `nodal` otherwise.
    #[default]
    Auto,
    /// The wing's modal basis (K Φ = M Φ Ω², dense eigenproblem once per run): the step
    /// matrix is diagonal plus rank 2, solved by the Woodbury identity in O(n) per solve.
    Modal,
    /// The nodal unknowns: banded Cholesky of the step matrix, O(n·bandwidth) per solve.
    Nodal,
}

/// Largest number of unknowns stepped in the modal basis at all (the dense eigenproblems are
/// O(n³) once per run: ≈ 0.3 s at 600 unknowns).
pub const MODAL_MAX_UNKNOWNS: usize = 600;

/// Largest number of unknowns `basis = "auto"` steps in the modal basis (FE ≤ 100 elements,
/// FD ≤ ~150 intervals): measured, the modal and nodal runs agree within 1e-9 relative on every
/// series on the default FE and FD grids and FE 48 elements, and at FE 96 elements (288
/// unknowns) within 3e-10 on the tip series and 3e-7 on the energy; above it the modal basis's
/// round-off grows (see `wingcheck_sim::modal::MASS_TOLERANCE`) and the nodal stepper is used.
pub const MODAL_AUTO_UNKNOWNS: usize = 300;

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
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "auto" => Ok(Self::Auto),
            "modal" => Ok(Self::Modal),
            "nodal" => Ok(Self::Nodal),
            _ => Err(format!("unknown basis `{s}`: allowed auto, modal, nodal")),
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
    /// expected for `basis = modal`, for `stepper = exponential` and for `basis = auto` up to
    /// [`MODAL_AUTO_UNKNOWNS`] unknowns (there its orthonormality check may still send the run to
    /// the nodal basis, and `auto` then means the cheaper TR-BDF2). For work estimates.
    pub fn expected_time_scheme(&self) -> TimeScheme {
        self.time_scheme(self.expected_modal())
    }

    /// Whether a run is expected in the modal basis (see [`Config::expected_time_scheme`]).
    pub fn expected_modal(&self) -> bool {
        match self.discretisation.basis {
            StepBasis::Modal => true,
            StepBasis::Nodal => false,
            StepBasis::Auto => {
                self.discretisation.stepper == TimeScheme::Exponential || self.unknowns() <= MODAL_AUTO_UNKNOWNS
            }
        }
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
