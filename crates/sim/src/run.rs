//! `simulate`: run the closed loop over the horizon and collect the sampled time series
//! (and optionally the fields on the output grid). Memory grows only with the number of
//! output samples requested, never with the number of integrator steps.

use std::time::Instant;

use serde::Serialize;
use wingcheck_control::{ControlError, Controller};
use wingcheck_model::{Config, StepBasis, TimeScheme, Unit};

use crate::modal::ModalBasis;
use crate::stepper::{Peaks, Sample, Stepper};
use crate::{Discretisation, ExponentialNeedsModal, Interpolation, SimError};

/// Sampled time series of the closed loop (column-oriented; all columns have equal length).
#[derive(Debug, Clone, Default, Serialize, PartialEq, schemars::JsonSchema)]
pub struct Series {
    /// t (s).
    pub t: Vec<f64>,
    /// q(s,t) (m).
    pub q_tip: Vec<f64>,
    /// θ(s,t) (rad).
    pub theta_tip: Vec<f64>,
    /// q̇(s,t) (m/s).
    pub q_tip_rate: Vec<f64>,
    /// θ̇(s,t) (rad/s).
    pub theta_tip_rate: Vec<f64>,
    /// τ1 (N).
    pub tau1: Vec<f64>,
    /// τ2 (N m).
    pub tau2: Vec<f64>,
    /// g1 (N).
    pub g1: Vec<f64>,
    /// g2 (N m).
    pub g2: Vec<f64>,
    /// ĝ1 (N).
    pub g1_hat: Vec<f64>,
    /// ĝ2 (N m).
    pub g2_hat: Vec<f64>,
    /// σ1 (N).
    pub sigma1: Vec<f64>,
    /// σ2 (N m).
    pub sigma2: Vec<f64>,
    /// Mechanical energy E = ½⟨v, Mv⟩ + ½⟨x, Kx⟩ (J).
    pub energy: Vec<f64>,
    /// ⟨x, M v⟩ = ∫(ρqq̇ − ρx_c(qθ̇ + θq̇) + I_pθθ̇) dz (J s) of the discretised state: the
    /// cross term of the Lyapunov function (22)–(23), W = b·E + a·⟨x, Mv⟩ (with the
    /// kinetic-energy coupling ρx_c), and ½ d/dt ⟨x, Mx⟩.
    pub displacement_momentum: Vec<f64>,
    /// q'''(s,t) (1/m²), from the boundary condition.
    pub q_tip_shear: Vec<f64>,
    /// θ'(s,t) (rad/m), from the boundary condition.
    pub theta_tip_slope: Vec<f64>,
    /// RMS of τ1(t) (N) over the output interval ending at t_k, at full rate (every
    /// integrator step, both sides of every jump; [`crate::SquareIntegral`]); |τ1(0)| at t = 0.
    pub tau1_rms: Vec<f64>,
    /// The same for τ2 (N m).
    pub tau2_rms: Vec<f64>,
}

impl Series {
    /// Column names and units in output order (run.csv writes `name_unitsuffix`,
    /// [`Series::csv_header`]).
    /// Its length is [`wingcheck_model::work::SERIES_COLUMNS`], the width the work estimates
    /// count per output sample (a column added here without it does not compile).
    pub const COLUMNS: [(&'static str, Unit); wingcheck_model::work::SERIES_COLUMNS] = [
        ("t", Unit::Second),
        ("q_tip", Unit::Metre),
        ("theta_tip", Unit::Radian),
        ("q_tip_rate", Unit::MetrePerSecond),
        ("theta_tip_rate", Unit::RadianPerSecond),
        ("tau1", Unit::Newton),
        ("tau2", Unit::NewtonMetre),
        ("g1", Unit::Newton),
        ("g2", Unit::NewtonMetre),
        ("g1_hat", Unit::Newton),
        ("g2_hat", Unit::NewtonMetre),
        ("sigma1", Unit::Newton),
        ("sigma2", Unit::NewtonMetre),
        ("energy", Unit::Joule),
        ("displacement_momentum", Unit::JouleSecond),
        ("q_tip_shear", Unit::PerSquareMetre),
        ("theta_tip_slope", Unit::RadianPerMetre),
        ("tau1_rms", Unit::Newton),
        ("tau2_rms", Unit::NewtonMetre),
    ];

    /// The header of run.csv: each column's name with its unit suffix (`t_s`, `q_tip_m`, …).
    pub fn csv_header() -> Vec<String> {
        Self::COLUMNS.iter().map(|(n, u)| wingcheck_io::column_name(n, u.column_suffix())).collect()
    }

    /// Every column empty, with room for `samples` output samples (allocated once, so a run
    /// holds exactly what the work estimate counts).
    pub fn with_capacity(samples: usize) -> Series {
        let v = || Vec::with_capacity(samples);
        Series {
            t: v(),
            q_tip: v(),
            theta_tip: v(),
            q_tip_rate: v(),
            theta_tip_rate: v(),
            tau1: v(),
            tau2: v(),
            g1: v(),
            g2: v(),
            g1_hat: v(),
            g2_hat: v(),
            sigma1: v(),
            sigma2: v(),
            energy: v(),
            displacement_momentum: v(),
            q_tip_shear: v(),
            theta_tip_slope: v(),
            tau1_rms: v(),
            tau2_rms: v(),
        }
    }

    /// Columns in the order of [`Series::COLUMNS`].
    pub fn columns(&self) -> [&Vec<f64>; wingcheck_model::work::SERIES_COLUMNS] {
        [
            &self.t,
            &self.q_tip,
            &self.theta_tip,
            &self.q_tip_rate,
            &self.theta_tip_rate,
            &self.tau1,
            &self.tau2,
            &self.g1,
            &self.g2,
            &self.g1_hat,
            &self.g2_hat,
            &self.sigma1,
            &self.sigma2,
            &self.energy,
            &self.displacement_momentum,
            &self.q_tip_shear,
            &self.theta_tip_slope,
            &self.tau1_rms,
            &self.tau2_rms,
        ]
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// True if there are no samples.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    pub(crate) fn push(&mut self, s: &Sample, tau_rms: [f64; 2]) {
        self.tau1_rms.push(tau_rms[0]);
        self.tau2_rms.push(tau_rms[1]);
        self.t.push(s.t);
        self.q_tip.push(s.q_tip);
        self.theta_tip.push(s.theta_tip);
        self.q_tip_rate.push(s.q_tip_rate);
        self.theta_tip_rate.push(s.theta_tip_rate);
        self.tau1.push(s.tau1);
        self.tau2.push(s.tau2);
        self.g1.push(s.g1);
        self.g2.push(s.g2);
        self.g1_hat.push(s.g1_hat);
        self.g2_hat.push(s.g2_hat);
        self.sigma1.push(s.sigma1);
        self.sigma2.push(s.sigma2);
        self.energy.push(s.energy);
        self.displacement_momentum.push(s.displacement_momentum);
        self.q_tip_shear.push(s.q_tip_shear);
        self.theta_tip_slope.push(s.theta_tip_slope);
    }

    /// Linear interpolation of a column at time t (clamped to the sampled range).
    pub fn at(&self, column: &[f64], t: f64) -> f64 {
        let n = self.t.len();
        if n == 0 {
            return f64::NAN;
        }
        if t <= self.t[0] {
            return column[0];
        }
        if t >= self.t[n - 1] {
            return column[n - 1];
        }
        let i = self.t.partition_point(|&x| x <= t) - 1;
        let u = (t - self.t[i]) / (self.t[i + 1] - self.t[i]);
        column[i] + u * (column[i + 1] - column[i])
    }
}

/// RMS over the window [t0, t1] (s) of a signal given as its full-rate RMS per output interval,
/// `interval_rms[k]` over (t_{k−1}, t_k] (as [`Series::tau1_rms`]): √(Σ rms_k² Δt_k / Σ Δt_k)
/// over the intervals inside the window (ends within 1e-9 s·(1 + |t1|)); None if none is.
/// The one definition of a time-RMS of τ: every crate's RMS τ is this.
pub fn windowed_rms(t: &[f64], interval_rms: &[f64], t0: f64, t1: f64) -> Option<f64> {
    let tol = 1e-9 * (1.0 + t1.abs());
    let (mut sum, mut span) = (0.0, 0.0);
    for k in 1..t.len().min(interval_rms.len()) {
        if t[k - 1] >= t0 - tol && t[k] <= t1 + tol {
            let dt = t[k] - t[k - 1];
            sum += interval_rms[k] * interval_rms[k] * dt;
            span += dt;
        }
    }
    (span > 0.0).then(|| (sum / span).sqrt())
}

/// Full-rate extremes per output interval of the signals that chatter at the observer's sample
/// rate: `tau1[k] = (min, max)` of τ1 over every recorded instant of (t_{k−1}, t_k] (every
/// integrator step's end and both sides of each sample's jump) and t_k itself; the entry at
/// t_0 is the value there. Draw these, not the output samples, for τ and g̃: with the explicit
/// observer the samples alias the chatter into a steady value.
#[derive(Debug, Clone, Default, Serialize, PartialEq, schemars::JsonSchema)]
pub struct Envelope {
    /// (min, max) of τ1 (N) per output interval.
    pub tau1: Vec<(f64, f64)>,
    /// (min, max) of τ2 (N m) per output interval.
    pub tau2: Vec<(f64, f64)>,
    /// (min, max) of g̃1 = g1 − ĝ1 (N) per output interval.
    pub g1_error: Vec<(f64, f64)>,
    /// (min, max) of g̃2 = g2 − ĝ2 (N m) per output interval.
    pub g2_error: Vec<(f64, f64)>,
}

// The envelope's width per output sample is what the work estimates count.
const _: () = assert!(4 * std::mem::size_of::<(f64, f64)>() == 8 * wingcheck_model::work::ENVELOPE_VALUES);

impl Envelope {
    /// Empty, with room for `samples` output samples.
    pub fn with_capacity(samples: usize) -> Envelope {
        let v = || Vec::with_capacity(samples);
        Envelope { tau1: v(), tau2: v(), g1_error: v(), g2_error: v() }
    }

    /// The values of an output sample: [τ1, τ2, g̃1, g̃2].
    pub(crate) fn values(s: &Sample) -> [f64; 4] {
        [s.tau1, s.tau2, s.g1 - s.g1_hat, s.g2 - s.g2_hat]
    }

    pub(crate) fn push(&mut self, r: [(f64, f64); 4]) {
        self.tau1.push(r[0]);
        self.tau2.push(r[1]);
        self.g1_error.push(r[2]);
        self.g2_error.push(r[3]);
    }
}

impl Fields {
    /// Empty fields on the grid `z`, with room for the output samples of `cfg`.
    pub fn with_capacity(z: Vec<f64>, cfg: &Config) -> Fields {
        let n = cfg.output_samples();
        Fields { z, q: Vec::with_capacity(n), theta: Vec::with_capacity(n) }
    }
}

/// q(z,t) and θ(z,t) on the coarse output grid at the sample times.
#[derive(Debug, Clone, Default, Serialize, PartialEq, schemars::JsonSchema)]
pub struct Fields {
    /// Grid points z_j (m).
    pub z: Vec<f64>,
    /// q[k][j] = q(z_j, t_k) (m).
    pub q: Vec<Vec<f64>>,
    /// theta[k][j] = θ(z_j, t_k) (rad).
    pub theta: Vec<Vec<f64>>,
}

/// Options of a run that do not change its result (beyond its stated round-off, for
/// [`RunOptions::eigenbasis`]).
#[derive(Default)]
pub struct RunOptions<'a> {
    /// Record q(z,t), θ(z,t) on the output grid.
    pub fields: bool,
    /// Called with the fraction done (0..=1) at every output sample.
    pub progress: Option<&'a mut dyn FnMut(f64)>,
    /// Read at every observer sample (and between the runs of a layer resolution or an error
    /// estimate): once set, the run stops with [`crate::SimError::Cancelled`].
    pub cancel: wingcheck_model::Cancel,
    /// The exponential scheme's sub-step probe (`crate::modal`'s probe): screened (the
    /// default), exhaustive, or off.
    pub sub_step_probe: SubStepProbe,
    /// Step the exponential scheme in the closed loop's eigenbasis (`crate::modal`'s diagonal
    /// form, O(N) per step) where its round-off estimate, relative of the state, is at most
    /// this (clamped to [`MAX_EIGENBASIS_ROUNDOFF`]) and its other checks pass; the dense form
    /// otherwise, and always for `None` (the default). The eigenbasis form has no sub-step
    /// probe, and its ∫τ² is exact per output interval only ([`RunStats::eigenbasis_roundoff`]
    /// says whether it ran and with what estimate). For runs that only need statistics.
    pub eigenbasis: Option<f64>,
    /// Record only what whole-run metrics read (`crate::modal`'s [`crate::modal::Reads::SERIES`];
    /// ignored with `fields`): every output's tip values, τ and observer output, every output
    /// interval's ∫τ², and the state at the last output. Where the run steps in the eigenbasis,
    /// the outputs before the last then skip the O(N²) reconstruction of the modal state: their
    /// `energy` is the O(N) upper bound of the mechanical energy, the columns formed from the
    /// state (`displacement_momentum`, `q_tip_shear`, `theta_tip_slope`) are not brought up to
    /// date, and every other value is the one a full recording gives, to round-off. For
    /// refinement runs read through their tip, τ and observer columns.
    pub series_only: bool,
    /// A controller of the user's in place of `control.kind` ([`ControllerFactory`]): each run
    /// (the base run, the initial layer's, an error estimate's refinements) makes one and
    /// resets it. Stepped in the basis [`resolved_basis`] selects, as the built-ins are; in the
    /// modal one its held inputs are sampled from the modal state at every t_k
    /// ([`crate::modal::ControlledSignal`]; the built-ins keep their precomputed observer
    /// signal, which needs no plant state), and `eigenbasis` is not used.
    pub controller: Option<ControllerFactory<'a>>,
}

/// A controller in place of the built-in ones, boxed (see [`wingcheck_control::Controller`]).
pub type BoxedController = Box<dyn Controller<Error = ControlError>>;

/// Makes a [`BoxedController`] for a run ([`RunOptions::controller`]).
pub type ControllerFactory<'a> = &'a (dyn Fn() -> BoxedController + Sync);

/// Largest round-off estimate [`RunOptions::eigenbasis`] accepts (relative of the state). The
/// estimate is checked against the dense scheme over whole 20-s horizons by the eigenbasis unit
/// test in `modal::scheme`, with the search's limit lifted, up to 3.1e-3 (the paper's wing on
/// 192 elements: measured 1.8e-3 of the modal state, 0.58 × the estimate, and 7.4e-5 of the
/// whole run's ∫τ²; 96 elements: estimate 1.5e-4, measured 0.61 × it; a stiff SI-scale wing:
/// estimate 7.9e-4, measured 5.5e-4 of the modal state, 0.70 ×), and by
/// `tests/statistics_runs.rs` through `check`'s own statistics runs. Their users add the
/// estimate to the quantity's error (the explicit FTDO's RMS τ: ×4.8 of the value), so a run
/// near the limit widens its ± instead of hiding a difference. Up to it the doubled grid of a
/// 96-element check (576 unknowns) steps in O(N) instead of a dense (2n)² product per step.
pub const MAX_EIGENBASIS_ROUNDOFF: f64 = 4e-3;

/// How a run of the exponential scheme looks inside its steps after each jump of the held
/// inputs (the other schemes have no probe).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum SubStepProbe {
    /// The coarse grid, and the fine grid near its maximum where that may raise a peak.
    #[default]
    Screened,
    /// The whole fine grid for every output (no screen): to test the screen.
    Exhaustive,
    /// Not at all: peaks at the recorded instants only (an independent reference at a fine step).
    Off,
}

/// Cost statistics of a run.
#[derive(Debug, Clone, Serialize, PartialEq, schemars::JsonSchema)]
pub struct RunStats {
    /// Unknowns of the semi-discrete system.
    pub unknowns: usize,
    /// Stored entries of the step matrix's banded Cholesky factor (0 in the modal basis,
    /// which factorises nothing: its step matrix is diagonal plus rank 2).
    pub factor_nnz: usize,
    /// Basis the loop was stepped in: `modal` or `nodal` (`discretisation.basis`, `auto`
    /// resolved).
    pub basis: StepBasis,
    /// Time scheme it was stepped with: `trbdf2`, `trapezoid` or `exponential`
    /// (`discretisation.stepper`, `auto` resolved by `Config::time_scheme`).
    pub stepper: TimeScheme,
    /// Integrator steps taken.
    pub steps: usize,
    /// Wall time for assembly and factorisation (s).
    pub setup_seconds: f64,
    /// Wall time for time stepping (s).
    pub stepping_seconds: f64,
    /// Steps probed inside by the exponential scheme's sub-step probe (the first step after
    /// every jump of the held inputs; 0 for the other schemes), and of those, the steps whose
    /// probe raised a running full-rate peak.
    pub sub_step_probes: [usize; 2],
    /// The eigenbasis form's round-off estimate, relative of the state, where the run stepped
    /// in the closed loop's eigenbasis ([`RunOptions::eigenbasis`]); absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub eigenbasis_roundoff: Option<f64>,
}

/// Result of [`simulate`].
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct SimOutput {
    /// Sampled time series.
    pub series: Series,
    /// Fields on the output grid, if requested.
    pub fields: Option<Fields>,
    /// Full-rate extremes over the whole run (every integrator step, both sides of every
    /// sample's jump), with the initial layer resolved ([`crate::layer`]): use these for
    /// peaks, never the output samples.
    pub peaks: Peaks,
    /// The base run's full-rate extremes after the initial layer (internal to the merge).
    #[serde(skip)]
    pub peaks_after_layer: Peaks,
    /// How the initial layer was resolved (None for a run that did not resolve it).
    pub initial_layer: Option<crate::layer::InitialLayer>,
    /// Full-rate (min, max) of τ and g̃ per output interval (one entry per output sample).
    pub envelope: Envelope,
    /// From when |g̃1|, |g̃2| stay ≤ [`crate::metrics::GTILDE_THRESHOLD`] (s), measured at full
    /// rate (every integrator step's end and both sides of every sample's jump) in the run at
    /// the configured step: the first instant after the last one above; None if the last
    /// instant is above. Not serialised (`t_band` of the report's notation).
    #[serde(skip)]
    pub gtilde_band_entry: [Option<f64>; 2],
    /// Cost statistics (wall times vary; everything else is deterministic).
    pub stats: RunStats,
}

/// Energy above which a run is declared diverged (relative to 1 + E(0)).
const DIVERGENCE_FACTOR: f64 = 1e12;

/// The basis `cfg` is stepped in, and the modal basis if that is the modal one:
/// `discretisation.basis`, with `auto` resolved to `modal` where [`Config::expected_modal`]
/// expects it (up to [`wingcheck_model::MODAL_AUTO_UNKNOWNS`] unknowns, and above where the
/// basis's setup is repaid by its cheaper steps) and the modal basis passes its check
/// ([`crate::modal::MASS_TOLERANCE`], [`crate::modal::FREQUENCY_TOLERANCE`]), `nodal`
/// otherwise. An explicit `modal` (or `auto` with `discretisation.stepper = exponential`, which
/// runs in the modal basis only) whose basis cannot be built or fails the check is an error
/// naming the reason. `disc` is `cfg`'s discretisation (`Discretisation::new(cfg)`); the basis
/// is built once per [`ModalBasis::key`] while it is kept ([`ModalBasis::of_config`]).
pub fn resolved_basis(cfg: &Config, disc: &Discretisation) -> Result<(StepBasis, Option<ModalBasis>), SimError> {
    let needs_modal = cfg.discretisation.stepper == wingcheck_model::TimeScheme::Exponential;
    let modal = || {
        ModalBasis::of_config(cfg, disc).map_err(|e| match e {
            SimError::NoModalBasis { reason } if needs_modal => ExponentialNeedsModal { reason }.into(),
            other => other,
        })
    };
    match cfg.discretisation.basis {
        StepBasis::Nodal => Ok((StepBasis::Nodal, None)),
        StepBasis::Modal => Ok((StepBasis::Modal, Some(modal()?))),
        StepBasis::Auto if needs_modal => Ok((StepBasis::Modal, Some(modal()?))),
        StepBasis::Auto if !cfg.expected_modal() => Ok((StepBasis::Nodal, None)),
        StepBasis::Auto => match ModalBasis::of_config(cfg, disc) {
            Ok(basis) => Ok((StepBasis::Modal, Some(basis))),
            Err(SimError::NoModalBasis { .. }) => Ok((StepBasis::Nodal, None)),
            Err(e) => Err(e),
        },
    }
}

/// Run the closed loop of `cfg` over [0, T], in the basis [`resolved_basis`] selects (the
/// same discrete equations either way: the results agree to round-off; `stats.basis` says
/// which).
pub fn simulate(cfg: &Config, opts: RunOptions<'_>) -> Result<SimOutput, SimError> {
    let (sub_step_probe, controller) = (opts.sub_step_probe, opts.controller);
    let cancel = opts.cancel.clone();
    let (mut out, basis) = base_run(cfg, opts)?;
    // The layer runs change the step, horizon and output sampling only, none of which the
    // basis depends on: a layer run whose basis key (`ModalBasis::key`, which also fixes the
    // choice of basis) is the base run's is stepped in the base run's modal basis instead of
    // building it again (the same bits: the basis is a deterministic function of the key's
    // inputs). Any other layer run is a run of its own.
    let base_key = basis.as_ref().map(|_| ModalBasis::key(cfg));
    let layer = crate::layer::resolve(cfg, &mut out, |c| {
        let opts = RunOptions { sub_step_probe, cancel: cancel.clone(), controller, ..Default::default() };
        match (&basis, &base_key) {
            (Some(basis), Some(key)) if ModalBasis::key(c) == *key => {
                crate::modal::simulate_modal(c, basis, Instant::now(), opts)
            }
            _ => simulate_base(c, opts),
        }
    })?;
    out.initial_layer = Some(layer);
    Ok(out)
}

/// [`simulate`] without resolving the initial layer: the run at the configured step only.
pub fn simulate_base(cfg: &Config, opts: RunOptions<'_>) -> Result<SimOutput, SimError> {
    base_run(cfg, opts).map(|(out, _)| out)
}

/// The run at the configured step in the basis [`resolved_basis`] selects, and that modal
/// basis where it is the modal one.
fn base_run(cfg: &Config, opts: RunOptions<'_>) -> Result<(SimOutput, Option<ModalBasis>), SimError> {
    cfg.validate().map_err(SimError::Config)?;
    let start = Instant::now();
    let disc = Discretisation::new(cfg);
    let (_, basis) = resolved_basis(cfg, &disc)?;
    let out = match (&basis, opts.controller) {
        (Some(basis), _) => crate::modal::simulate_modal(cfg, basis, start, opts)?,
        (None, Some(make)) => simulate_nodal(cfg, Stepper::with_controller(cfg, disc, make())?, start, opts)?,
        (None, None) => simulate_nodal(cfg, Stepper::with_discretisation(cfg, disc)?, start, opts)?,
    };
    Ok((out, basis))
}

/// [`simulate`] in the nodal basis (banded Cholesky of the step matrix).
fn simulate_nodal<C: Controller>(
    cfg: &Config,
    mut stepper: Stepper<C>,
    start: Instant,
    mut opts: RunOptions<'_>,
) -> Result<SimOutput, SimError>
where
    C::Error: Into<SimError>,
{
    let setup_seconds = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let total = cfg.total_samples();
    let every = cfg.samples_per_output();
    let mut series = Series::with_capacity(cfg.output_samples());
    let mut envelope = Envelope::with_capacity(cfg.output_samples());
    let mut fields = opts.fields.then(|| Fields::with_capacity(stepper.discretisation().interp.z.clone(), cfg));
    let e0 = stepper.sample().energy;
    let mut record = |st: &mut Stepper<C>, series: &mut Series, fields: &mut Option<Fields>| -> Result<(), SimError> {
        let s = st.sample();
        check_sample(&s, e0)?;
        series.push(&s, st.take_tau_rms());
        envelope.push(st.take_range(Envelope::values(&s)));
        if let Some(f) = fields {
            let (x, _) = st.state();
            let d: &Discretisation = st.discretisation();
            f.q.push(Interpolation::eval(&d.interp.q_rows, x));
            f.theta.push(Interpolation::eval(&d.interp.theta_rows, x));
        }
        Ok(())
    };
    record(&mut stepper, &mut series, &mut fields)?;
    crate::cpu::clear_upper_vector_state();
    for k in 1..=total {
        stepper.try_advance_sample().map_err(Into::into)?;
        opts.cancel.check()?;
        if k % every == 0 || k == total {
            record(&mut stepper, &mut series, &mut fields)?;
            if let Some(p) = opts.progress.as_mut() {
                p(k as f64 / total as f64);
            }
        }
    }
    let (unknowns, factor_nnz) = stepper.solver_size();
    Ok(SimOutput {
        series,
        fields,
        peaks: *stepper.peaks(),
        peaks_after_layer: *stepper.peaks_after_layer(),
        initial_layer: None,
        envelope,
        gtilde_band_entry: stepper.band_entry(),
        stats: RunStats {
            unknowns,
            factor_nnz,
            basis: StepBasis::Nodal,
            stepper: cfg.time_scheme(false),
            steps: total * cfg.steps_per_sample(),
            setup_seconds,
            stepping_seconds: start.elapsed().as_secs_f64(),
            sub_step_probes: [0, 0],
            eigenbasis_roundoff: None,
        },
    })
}

/// The energy (J) above which a run with initial energy `e0` (J) counts as diverged:
/// 1e12 × (1 + E(0)).
pub(crate) fn energy_limit(e0: f64) -> f64 {
    DIVERGENCE_FACTOR * (1.0 + e0)
}

/// Stop with a message saying when and why if the state is no longer finite or the energy
/// has grown beyond any physical meaning (energy above 1e12 × (1 + E(0)), E in J). Public so
/// that every runner of the closed loop (the nodal stepper, the modal driver) uses the same rule.
pub fn check_sample(s: &Sample, e0: f64) -> Result<(), SimError> {
    let values = [
        ("q(s,t)", s.q_tip),
        ("θ(s,t)", s.theta_tip),
        ("q̇(s,t)", s.q_tip_rate),
        ("θ̇(s,t)", s.theta_tip_rate),
        ("τ1", s.tau1),
        ("τ2", s.tau2),
        ("ĝ1", s.g1_hat),
        ("ĝ2", s.g2_hat),
    ];
    check_values(s.t, &values, s.energy, e0)
}

/// [`check_sample`]'s rule on named values at time `t` (s) and the energy (J): for a runner
/// that has no [`Sample`] at hand (the step form, [`crate::SteppedRun`]).
pub(crate) fn check_values(t: f64, values: &[(&str, f64)], energy: f64, e0: f64) -> Result<(), SimError> {
    let energy_value = [("energy", energy)];
    if let Some((name, v)) = values.iter().chain(&energy_value).find(|(_, v)| !v.is_finite()) {
        return Err(SimError::Diverged { t, reason: format!("{name} became {v}") });
    }
    if energy > energy_limit(e0) {
        return Err(SimError::Diverged {
            t,
            reason: format!(
                "energy {:.3e} J exceeds {:.0e} × (1 + E(0) = {:.3e} J)",
                energy,
                DIVERGENCE_FACTOR,
                1.0 + e0
            ),
        });
    }
    Ok(())
}
