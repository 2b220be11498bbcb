//! Simulation of the coupled bending–torsion wing with Kelvin–Voigt damping under boundary
//! control (paper eq. (9)–(10), corrected in `docs/model.md`).
//!
//! - [`Discretisation`]: two independent spatial discretisations, the paper's finite
//!   differences ([`fd`]) and finite elements ([`fe`]), both as sparse symmetric M, K (faer).
//! - [`Stepper`]: the closed loop advanced one observer sample at a time (TR-BDF2 by default,
//!   or the trapezoidal rule; step matrix factorised once, digital observer with zero-order
//!   hold), with full-rate [`Peaks`].
//! - [`simulate`]: a whole run, sampled.
//! - [`modes`]: natural frequencies of the undamped, uncontrolled wing, and the analytic
//!   uncoupled ones.

mod assembly;
pub mod banded;
pub mod bench;
pub mod cpu;
pub mod dense;
mod disc;
pub mod error_estimate;
pub mod estimate;
pub mod fd;
pub mod fe;
pub mod layer;
pub mod metrics;
pub mod modal;
pub mod modes;
pub mod numerical;
pub mod output;
pub mod run;
pub mod sparse;
pub mod stepped;
mod stepper;
pub mod strain;

pub use disc::{Discretisation, Interpolation, Parts};
pub use error_estimate::{
    estimate_from_runs, grid_part, refinements, series_error, simulate_with_error, third_grid_run, EstimatedRun,
    ExtraRunError, PeakEstimate, PeakEstimates, SubStepCheck, ThirdGrid, RICHARDSON_2, TIP_TOLERANCE,
};
pub use estimate::Estimate;
pub use numerical::{ExponentialNeedsModal, ModalBasisError, NumericalError, SchemeObstacle};
pub use run::{
    check_sample, resolved_basis, simulate, simulate_base, windowed_rms, BoxedController, ControllerFactory, Envelope,
    Fields, RunOptions, RunStats, Series, SimOutput, SubStepProbe, MAX_EIGENBASIS_ROUNDOFF,
};
pub use stepped::{SteppedRun, SteppedSample};
pub use stepper::{initial_tip_states, trbdf2, Channel, EnergyLedger, Peak, Peaks, Sample, SquareIntegral, Stepper};

use thiserror::Error;

/// Errors of the simulator.
#[derive(Debug, Error)]
pub enum SimError {
    /// The configuration is invalid.
    #[error(transparent)]
    Config(#[from] wingcheck_model::ConfigError),
    /// A linear-algebra step failed (e.g. a matrix that should be positive definite is not).
    #[error("numerical failure: {0}")]
    Numerical(#[from] NumericalError),
    /// The modal basis of the discretisation cannot be built, or fails its orthonormality
    /// check (too many unknowns, a failed eigen-solve): the `auto` basis then steps in the nodal
    /// basis instead; an explicit `modal` reports it.
    #[error("no modal basis: {reason}")]
    NoModalBasis {
        /// Why not.
        reason: ModalBasisError,
    },
    /// `discretisation.stepper = exponential` on a discretisation without a modal basis.
    #[error("numerical failure: {0}")]
    ExponentialNeedsModal(#[from] ExponentialNeedsModal),
    /// A refinement of [`simulate_with_error`] (the doubled grid) cannot run the base run's
    /// time scheme.
    #[error(
        "numerical failure: the spatial refinement ({grid} {unit}) cannot run the base run's {} scheme: {reason}; \
         set discretisation.stepper=trbdf2 to estimate with TR-BDF2, or use a coarser grid",
        scheme.name()
    )]
    RefinementScheme {
        /// The refined grid (elements or intervals).
        grid: usize,
        /// "elements" or "intervals".
        unit: &'static str,
        /// The base run's time scheme.
        scheme: wingcheck_model::TimeScheme,
        /// Why the refined run cannot use it.
        reason: SchemeObstacle,
    },
    /// A loop stepped from outside ([`SteppedRun`]) was asked for a sample after its run ended
    /// with an error (`why`, that error's message, already reported once).
    #[error("the run ended earlier: {why}; call reset()")]
    EndedEarlier {
        /// The message of the error that ended the run.
        why: String,
    },
    /// The thread of a [`SteppedRun`] could not be started.
    #[error("cannot start the stepping thread: {0}")]
    Thread(#[source] std::io::Error),
    /// The run was stopped through [`RunOptions::cancel`].
    #[error(transparent)]
    Cancelled(#[from] wingcheck_model::Cancelled),
    /// A controller of the user's ([`RunOptions::controller`]) failed or returned bad inputs.
    #[error(transparent)]
    Control(#[from] wingcheck_control::ControlError),
    /// A loop stepped from outside ([`SteppedRun`]) was asked for a sample period past its
    /// horizon.
    #[error(
        "the run reached its horizon t_end = {t_end} s: no sample period is left (reset, or set a longer horizon.t_end)"
    )]
    HorizonEnded {
        /// The horizon (s).
        t_end: f64,
    },
    /// The simulation diverged.
    #[error("simulation diverged at t = {t:.4} s: {reason}")]
    Diverged {
        /// Time of detection (s).
        t: f64,
        /// What was detected.
        reason: String,
    },
}

impl From<std::convert::Infallible> for SimError {
    fn from(never: std::convert::Infallible) -> SimError {
        match never {}
    }
}
