//! The one closed-loop driver of the modal basis: `simulate` ([`super::simulate_modal`]) and
//! the parameter search run the loop through [`drive`], with the same inputs, the same steps
//! and the same divergence check, and differ only in what they record ([`Recorder`]) and in
//! where the observer signal comes from ([`Signal`]: generated while stepping, or replayed from
//! a [`super::RecordedSignal`] shared by many runs — the same numbers either way).

use wingcheck_model::Config;

use wingcheck_control::TipMeasurement;

use super::{measurement, ModalBasis, ModalLoop, ModalState, SampleInput, StepInput, StepQuadrature};
use crate::run::{check_sample, energy_limit};
use crate::{Sample, SimError};

/// The observer signal of a run, one sample period at a time (the observer and the
/// disturbances only: σ_{n+1} − σ_n = h(ḡ − ĝ_k) holds whatever the plant, see [`super`]).
pub trait Signal {
    /// Whether the held inputs depend on the plant (a controller of any origin,
    /// [`super::ControlledSignal`]): the driver then forms every step's quadrature and calls
    /// [`Signal::observe`] after each sample period. False for the observer signals (their
    /// runs skip that work).
    const READS_PLANT: bool = false;
    /// The observer's output at the current sample t_k.
    fn current(&self) -> SampleInput;
    /// Call `step(t_j, input)` for each integrator step [t_j, t_j + h) of the current sample
    /// period with its inputs, then move to the next sample.
    fn advance(&mut self, step: impl FnMut(f64, &StepInput));
    /// For a signal that [`Signal::READS_PLANT`]: the quadratures of the period's steps just
    /// made, in order, and the measurements and the loop's energy (J) at the new sample, before
    /// [`Signal::current`] is read there. An error (the controller's) stops the run.
    fn observe(&mut self, _steps: &[StepQuadrature], _tip: &TipMeasurement, _energy: f64) -> Result<(), SimError> {
        Ok(())
    }
}

/// What a run keeps of the loop it drives.
pub trait Recorder {
    /// Called at every recorded instant: t = 0, the end of every integrator step (`exact`: the
    /// scheme's exact ∫τ_c² dt over that step, N² s and N² m² s, where it has one) and the far
    /// side of every sample's jump of the held estimate (same t, new `g_hat`, `exact` None).
    /// Full-rate statistics (peaks, ∫τ² dt) are folded in here. `g`: the disturbance g(t)
    /// where the driver has it (t = 0 and the samples: the observer's g(t_k), the value the
    /// samples carry), `None` at the step ends.
    fn instant(
        &mut self,
        lp: &ModalLoop<'_>,
        st: &ModalState,
        t: f64,
        g_hat: [f64; 2],
        g: Option<[f64; 2]>,
        exact: Option<[f64; 2]>,
    );

    /// Called at each output sample k (t_k = k T, every `samples_per_output` samples and the
    /// last), after the tip values were recomputed from the modal state and `sample` passed the
    /// divergence check ([`check_sample`]).
    fn output(&mut self, st: &ModalState, sample: &Sample, k: usize) -> Result<(), SimError>;

    /// Called at each output sample before [`Recorder::output`] with what the steps' `exact`
    /// values since the previous output still lack (N² s, N² m² s), for a scheme that defers
    /// part of its ∫τ² to checkpoints ([`ModalLoop::checkpoint`]): the steps' values plus this
    /// are the exact ∫τ_c² over the output interval.
    fn deferred_squares(&mut self, squares: [f64; 2]);

    /// Called at every observer sample (every T): an error stops the run there (a cancelled
    /// run, [`crate::RunOptions::cancel`]). The default never stops.
    fn checkpoint(&self) -> Result<(), SimError> {
        Ok(())
    }

    /// What the recorder reads beyond each output's tip values, τ and observer output
    /// ([`Reads`]); the default, [`Reads::ALL`], is always correct, a leaner value saves work.
    fn reads(&self) -> Reads {
        Reads::ALL
    }
}

/// What a [`Recorder`] reads, so that the driver skips the work nobody reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Reads {
    /// ∫τ² per output interval (true) or only over the whole run. With false, a scheme that
    /// defers part of its ∫τ² to checkpoints adds that part once, at the last output
    /// ([`ModalLoop::checkpoint`]): the intervals' values in between are not the intervals'
    /// integrals, their sum over the run is the run's (the deferred terms telescope), and the
    /// O(N r) work of each intermediate checkpoint's part is saved.
    pub interval_squares: bool,
    /// The modal state at every output (true) or only the tip values, τ and the observer's
    /// output there, and the state at the last output. With false, where the scheme carries the
    /// state in the eigenbasis, the outputs before the last skip its O(N²) reconstruction (an
    /// interval's ∫τ², where read, is formed in the eigenbasis,
    /// [`ModalLoop::interval_squares`]): their tip values are the step's own (UᵀV x̂ from
    /// precomputed rows, equal to the reconstructed ones to round-off), their `energy` is the
    /// O(N) upper bound [`ModalLoop::energy_bound`], and η, ζ, w and the quantities formed from
    /// them are the previous checkpoint's. The divergence check gives the same verdict: where
    /// the bound passes, the energy passes; where it does not, the state is reconstructed and
    /// checked.
    pub state: bool,
    /// The tip boundary states w (q'''(s), θ'(s): the samples' `q_tip_shear`,
    /// `theta_tip_slope`). With false, TR-BDF2 does not advance them
    /// ([`ModalLoop::step_with`]): they do not feed back, so every other value is the same,
    /// and the samples carry w(0) in their place.
    pub tip_states: bool,
}

impl Reads {
    /// Everything: every output interval's ∫τ², the state and the tip boundary states.
    pub const ALL: Reads = Reads { interval_squares: true, state: true, tip_states: true };
    /// Only the outputs' tip values, τ and observer output, and ∫τ² over the whole run: what
    /// the search and the finite-time rows' digital runs read.
    pub const OUTPUTS: Reads = Reads { interval_squares: false, state: false, tip_states: false };
    /// The outputs' tip values, τ and observer output, and every output interval's ∫τ²; the
    /// state at the last output only (`simulate`'s [`crate::RunOptions::series_only`]).
    pub const SERIES: Reads = Reads { interval_squares: true, state: false, tip_states: false };
}

/// Run the loop `lp` of `cfg` on `basis` over [0, T] from the state `st`, with the observer
/// signal `signal` (of the same configuration), reporting to `rec`. A run whose sample is not
/// finite or whose energy explodes stops with [`SimError::Diverged`] saying when and why.
pub fn drive<S: Signal, R: Recorder>(
    cfg: &Config,
    basis: &ModalBasis,
    lp: &ModalLoop<'_>,
    st: &mut ModalState,
    signal: &mut S,
    rec: &mut R,
) -> Result<(), SimError> {
    let (total, every, period) = (cfg.total_samples(), cfg.samples_per_output(), cfg.observer.sample_period);
    let h = cfg.discretisation.dt;
    let e0 = basis.energy(&st.eta, &st.zeta);
    let reads = rec.reads();
    let lean = !reads.state;
    // a controller that reads the plant measures w
    let tip_states = reads.tip_states || S::READS_PLANT;
    let mut quads = Vec::with_capacity(if S::READS_PLANT { cfg.steps_per_sample() } else { 0 });
    let output = |st: &mut ModalState, obs: &SampleInput, t: f64, k: usize, rec: &mut R| {
        if lean && k != total {
            // margin 1e-10 relative: far above the bound's and the energy's round-off
            if let Some(bound) = lp.energy_bound(st).filter(|b| b * (1.0 + 1e-10) <= energy_limit(e0)) {
                if reads.interval_squares {
                    if let Some(squares) = lp.interval_squares(st) {
                        rec.deferred_squares(squares);
                    }
                }
                let sample = Sample { energy: bound, ..lp.sample(basis, st, t, obs) };
                check_sample(&sample, e0)?;
                return rec.output(st, &sample, k);
            }
        }
        if let Some(squares) = lp.checkpoint(st, reads.interval_squares || k == total) {
            rec.deferred_squares(squares);
        }
        st.sync_tip(basis);
        let sample = lp.sample(basis, st, t, obs);
        check_sample(&sample, e0)?;
        rec.output(st, &sample, k)
    };
    let first = signal.current();
    rec.instant(lp, st, 0.0, first.g_hat, Some(first.g), None);
    output(st, &first, 0.0, 0, rec)?;
    crate::cpu::clear_upper_vector_state();
    for k in 1..=total {
        let t = k as f64 * period;
        if S::READS_PLANT {
            quads.clear();
            signal.advance(|t, input| {
                let (exact, quad) = lp.step_quadrature(st, input, true);
                quads.push(quad);
                rec.instant(lp, st, t + h, input.g_hat, None, exact);
            });
            signal.observe(&quads, &measurement(st, t), basis.energy(&st.eta, &st.zeta))?;
        } else {
            signal.advance(|t, input| {
                let exact = lp.step_with(st, input, tip_states);
                rec.instant(lp, st, t + h, input.g_hat, None, exact);
            });
        }
        let now = signal.current();
        rec.instant(lp, st, t, now.g_hat, Some(now.g), None);
        rec.checkpoint()?;
        if k % every == 0 || k == total {
            output(st, &now, t, k, rec)?;
        }
    }
    Ok(())
}
