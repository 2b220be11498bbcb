//! `simulate` in the modal basis: the same outputs as the nodal run (series, fields, full-rate
//! peaks, divergence checks), from the modal state.

use std::time::Instant;

use wingcheck_model::Config;

use super::{dot, ModalBasis, ModalLoop, ModalState, ObserverSignal, SampleInput};
use crate::run::{check_sample, Fields, RunOptions, RunStats, Series, SimOutput};
use crate::stepper::FullRate;
use crate::SimError;

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

/// Run the closed loop of `cfg` over [0, T] in the modal basis of its discretisation
/// (see [`crate::modal`]); the outputs are those of the nodal `simulate` to round-off.
/// `start` is when the setup began (the basis's construction counts as setup).
pub fn simulate_modal(
    cfg: &Config,
    basis: &ModalBasis,
    start: Instant,
    mut opts: RunOptions<'_>,
) -> Result<SimOutput, SimError> {
    cfg.validate().map_err(SimError::Config)?;
    let lp = ModalLoop::new(cfg, basis)?;
    let mut st = lp.initial_state(cfg, basis);
    let mut signal = ObserverSignal::new(cfg);
    let setup_seconds = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let (total, every, period) = (cfg.total_samples(), cfg.samples_per_output(), cfg.observer.sample_period);
    let h = cfg.discretisation.dt;
    let mut series = Series::default();
    let mut fields = opts.fields.then(|| Fields { z: basis.field_z.clone(), ..Default::default() });
    let mut full_rate = FullRate::default();
    let first = signal.current();
    let e0 = basis.energy(&st.eta, &st.zeta);
    let record = |st: &ModalState,
                  obs: &SampleInput,
                  t: f64,
                  rms: [f64; 2],
                  series: &mut Series,
                  fields: &mut Option<Fields>| {
        let s = lp.sample(basis, st, t, obs);
        check_sample(&s, e0)?;
        series.push(&s, rms);
        if let Some(f) = fields {
            f.q.push(basis.field_q.iter().map(|row| dot(row, &st.eta)).collect());
            f.theta.push(basis.field_theta.iter().map(|row| dot(row, &st.eta)).collect());
        }
        Ok::<(), SimError>(())
    };
    full_rate.update(0.0, &peak_values(&lp, &st, first.g_hat, first.g));
    record(&st, &first, 0.0, full_rate.take_tau_rms(), &mut series, &mut fields)?;
    crate::cpu::clear_upper_vector_state();
    for k in 1..=total {
        signal.advance(|t, input| {
            let square = lp.step(&mut st, input);
            let t1 = t + h;
            full_rate.update_step(t1, &peak_values(&lp, &st, input.g_hat, signal_g(cfg, t1)), square);
        });
        let now = signal.current();
        let t = k as f64 * period;
        full_rate.update(t, &peak_values(&lp, &st, now.g_hat, now.g));
        if k % every == 0 || k == total {
            st.sync_tip(basis);
            record(&st, &now, t, full_rate.take_tau_rms(), &mut series, &mut fields)?;
            if let Some(p) = opts.progress.as_mut() {
                p(k as f64 / total as f64);
            }
        }
    }
    Ok(SimOutput {
        series,
        fields,
        peaks: full_rate.peaks,
        stats: RunStats {
            unknowns: basis.len(),
            factor_nnz: 0,
            basis: "modal".into(),
            stepper: lp.scheme().name().into(),
            steps: total * cfg.steps_per_sample(),
            setup_seconds,
            stepping_seconds: start.elapsed().as_secs_f64(),
        },
    })
}

/// g(t) of both channels (N, N m).
fn signal_g(cfg: &Config, t: f64) -> [f64; 2] {
    [cfg.disturbance.tip_bending.at(t), cfg.disturbance.tip_torsion.at(t)]
}
