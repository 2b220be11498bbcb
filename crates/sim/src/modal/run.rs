//! `simulate` in the modal basis: the same outputs as the nodal run (series, fields, full-rate
//! peaks, divergence checks), from the modal state, recorded from the one driver [`drive`].

use std::time::Instant;

use wingcheck_model::{Config, TipValues};

use super::{controlled_loop, dot, drive, ModalBasis, ModalLoop, ModalState, ObserverSignal, Reads, Recorder, Signal};
use crate::run::{Envelope, Fields, RunOptions, RunStats, Series, SimOutput, SubStepProbe};
use crate::stepper::FullRate;
use crate::{Sample, SimError};

/// The full-rate peak values [q, θ, q̇, θ̇, τ1, τ2, g̃1, g̃2] of the state with the estimate ĝ
/// and the disturbance g at that instant.
fn peak_values(lp: &ModalLoop<'_>, st: &ModalState, g_hat: [f64; 2], g: [f64; 2]) -> [f64; 8] {
    [
        st.x_tip[0],
        st.x_tip[1],
        st.v_tip[0],
        st.v_tip[1],
        lp.tau(0, st.x_tip[0], st.v_tip[0], g_hat[0]),
        lp.tau(1, st.x_tip[1], st.v_tip[1], g_hat[1]),
        g[0] - g_hat[0],
        g[1] - g_hat[1],
    ]
}

/// What `simulate` records: the sampled series, the fields if asked for, and the full-rate
/// peaks and τ square integrals ([`FullRate`]) with the disturbance g at every instant.
struct Simulation<'c, 'o> {
    cfg: &'c Config,
    basis: &'c ModalBasis,
    total: usize,
    series: Series,
    envelope: Envelope,
    fields: Option<Fields>,
    full_rate: FullRate,
    progress: Option<&'o mut dyn FnMut(f64)>,
    cancel: wingcheck_model::Cancel,
    /// Probe the next step ([`ModalLoop::probe_last_step`]): the held inputs jumped (t = 0 and
    /// every sample), or the step just probed ended with an output still rising toward its
    /// running peak ([`crate::modal::ProbedStep`]), and the probe is on.
    probe_next: bool,
    probe_on: bool,
    exhaustive: bool,
    probe_buf: Vec<f64>,
    /// Steps probed, and probes that raised a running peak.
    probes: usize,
    raised: usize,
    /// g(t) at the step ends, by rotation from step to step ([`TipValues`]).
    tip_values: TipValues,
    /// What the driver must provide ([`Reads::ALL`], or [`Reads::SERIES`] for
    /// [`RunOptions::series_only`]).
    reads: Reads,
}

impl Recorder for Simulation<'_, '_> {
    fn reads(&self) -> Reads {
        self.reads
    }

    fn instant(
        &mut self,
        lp: &ModalLoop<'_>,
        st: &ModalState,
        t: f64,
        g_hat: [f64; 2],
        g: Option<[f64; 2]>,
        exact: Option<[f64; 2]>,
    ) {
        if exact.is_some() && std::mem::take(&mut self.probe_next) {
            self.probe(lp, st, t - self.cfg.discretisation.dt);
        }
        let g = g.unwrap_or_else(|| self.tip_values.at(t));
        self.full_rate.update_step(t, &peak_values(lp, st, g_hat, g), exact);
        if exact.is_none() {
            self.probe_next = self.probe_on;
        }
    }

    fn deferred_squares(&mut self, squares: [f64; 2]) {
        self.full_rate.add_squares(squares);
    }

    fn checkpoint(&self) -> Result<(), SimError> {
        Ok(self.cancel.check()?)
    }

    fn output(&mut self, st: &ModalState, sample: &Sample, k: usize) -> Result<(), SimError> {
        self.series.push(sample, self.full_rate.take_tau_rms());
        self.envelope.push(self.full_rate.take_range(crate::run::Envelope::values(sample)));
        if let Some(f) = &mut self.fields {
            f.q.push(self.basis.field_q.iter().map(|row| dot(row, &st.eta)).collect());
            f.theta.push(self.basis.field_theta.iter().map(|row| dot(row, &st.eta)).collect());
        }
        if k > 0 {
            if let Some(p) = self.progress.as_mut() {
                p(k as f64 / self.total as f64);
            }
        }
        Ok(())
    }
}

impl Simulation<'_, '_> {
    /// Fold in the sub-step probe of the step from `start` (s) just made.
    fn probe(&mut self, lp: &ModalLoop<'_>, st: &ModalState, start: f64) {
        // the probed outputs are the first PROBED signals of Peaks::signals
        let running = self.full_rate.running(start, std::array::from_fn(|o| o));
        let Some(found) = lp.probe_last_step(st, running, &mut self.probe_buf, self.exhaustive) else {
            return;
        };
        self.probes += 1;
        self.probe_next = found.rising_at_end;
        let mut raised = false;
        for (o, peak) in found.peaks.iter().enumerate() {
            if let Some(p) = peak {
                let t = start + p.s;
                raised |= p.value.abs() > self.full_rate.running(t, [o])[0];
                self.full_rate.update_sub_step(o, t, p.value, p.miss);
            }
        }
        self.raised += usize::from(raised);
    }
}

/// Run the closed loop of `cfg` over [0, T] in the modal basis of its discretisation
/// (see [`crate::modal`]) through the one driver [`drive`]; the outputs are those of the nodal
/// `simulate` to round-off. `start` is when the setup began (the basis's construction counts
/// as setup). Under a controller of the user's ([`RunOptions::controller`]) the held inputs are
/// sampled from the modal state ([`ControlledSignal`]) and the exponential scheme steps in its
/// dense form (the eigenbasis form brings w up to date at the outputs only, and the controller
/// measures it at every sample).
pub fn simulate_modal(
    cfg: &Config,
    basis: &ModalBasis,
    start: Instant,
    opts: RunOptions<'_>,
) -> Result<SimOutput, SimError> {
    cfg.validate().map_err(SimError::Config)?;
    if let Some(make) = opts.controller {
        let (lp, mut st, mut signal) = controlled_loop(cfg, basis, make)?;
        return run(cfg, basis, &lp, &mut st, &mut signal, start, opts);
    }
    let lp = match opts.eigenbasis {
        Some(limit) => ModalLoop::with_eigenbasis_within(cfg, basis, limit.min(crate::MAX_EIGENBASIS_ROUNDOFF))?,
        None => ModalLoop::new(cfg, basis)?,
    };
    let mut st = lp.initial_state(cfg, basis);
    run(cfg, basis, &lp, &mut st, &mut ObserverSignal::new(cfg), start, opts)
}

/// [`simulate_modal`] once its loop, state and signal are made.
fn run<S: Signal>(
    cfg: &Config,
    basis: &ModalBasis,
    lp: &ModalLoop<'_>,
    st: &mut ModalState,
    signal: &mut S,
    start: Instant,
    opts: RunOptions<'_>,
) -> Result<SimOutput, SimError> {
    let setup_seconds = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let total = cfg.total_samples();
    let mut rec = Simulation {
        cfg,
        basis,
        total,
        series: Series::with_capacity(cfg.output_samples()),
        envelope: Envelope::with_capacity(cfg.output_samples()),
        fields: opts.fields.then(|| Fields::with_capacity(basis.field_z.clone(), cfg)),
        full_rate: FullRate::new(crate::layer::layer_end(cfg)),
        progress: opts.progress,
        cancel: opts.cancel,
        probe_next: false,
        probe_on: opts.sub_step_probe != SubStepProbe::Off && lp.probe_points() > 0,
        exhaustive: opts.sub_step_probe == SubStepProbe::Exhaustive,
        probe_buf: lp.probe_buffer(),
        probes: 0,
        raised: 0,
        tip_values: cfg.disturbance.tip_values(cfg.discretisation.dt),
        reads: if opts.series_only && !opts.fields { Reads::SERIES } else { Reads::ALL },
    };
    drive(cfg, basis, lp, st, signal, &mut rec)?;
    Ok(SimOutput {
        series: rec.series,
        fields: rec.fields,
        peaks: rec.full_rate.peaks,
        peaks_after_layer: rec.full_rate.after_layer,
        initial_layer: None,
        envelope: rec.envelope,
        gtilde_band_entry: rec.full_rate.band_entry(),
        stats: RunStats {
            unknowns: basis.len(),
            factor_nnz: 0,
            basis: wingcheck_model::StepBasis::Modal,
            stepper: lp.scheme(),
            steps: total * cfg.steps_per_sample(),
            setup_seconds,
            stepping_seconds: start.elapsed().as_secs_f64(),
            sub_step_probes: [rec.probes, rec.raised],
            eigenbasis_roundoff: lp.eigenbasis_roundoff(),
        },
    })
}
