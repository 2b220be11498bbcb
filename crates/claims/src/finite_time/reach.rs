//! Reaching time of the observer error σ: the bound (38)/(39) (via Lemma 3, (13)–(14)), the
//! continuous-time (Filippov) limit of σ̇ = g(t) − φ(σ), and the digital observers of the
//! simulator (explicit and implicit sampling) across hold periods T.

use crate::numerics::NumericsError;
use wingcheck_control::{ChannelObserver, ObserverGain, TipChannel};
use wingcheck_model::{Config, ObserverRule, TipDisturbance};
use wingcheck_sim::metrics::max_abs;
use wingcheck_sim::modal::{drive, ModalBasis, ModalLoop, ModalState, ObserverSignal, Reads, Recorder};
use wingcheck_sim::{Sample, Stepper};

use crate::ode::rk4_step;
use crate::ClaimsError;

/// Lemma 3, (14): t_f = ln((φ1 Q0^{1−φ3} + φ2)/φ2) / (φ1 (1 − φ3)) (s), the exact time at which
/// the solution of Q̇ = −φ1 Q − φ2 Q^{φ3}, Q(0) = Q0 ≥ 0, reaches 0 (hence an upper bound for
/// any Q with Q̇ ≤ −φ1 Q − φ2 Q^{φ3}). Needs φ1 > 0, φ2 > 0, 0 < φ3 < 1.
pub fn lemma3_time(phi1: f64, phi2: f64, phi3: f64, q0: f64) -> Result<f64, ClaimsError> {
    if !(phi1 > 0.0 && phi2 > 0.0 && phi3 > 0.0 && phi3 < 1.0 && q0 >= 0.0 && q0.is_finite()) {
        return Err(num_err("lemma3_time", NumericsError::Lemma3Inputs { phi1, phi2, phi3, q0 }));
    }
    Ok((phi1 * q0.powf(1.0 - phi3) / phi2).ln_1p() / (phi1 * (1.0 - phi3)))
}

/// The bound (38) (Theorem 3; (39) for Theorem 4 with κ4, κ6, b1, b2) on the reaching time of σ
/// (s), read as
/// t_f ≤ a2/(2κ1(a2 − a1)) · ln{(κ1 Q0^{(a2−a1)/a2} + 2^{a1/a2 − 1} κ3) / (2^{a1/a2 − 1} κ3)},
/// Q0 = σ(0)²/2. This is Lemma 3 with φ1 = 2κ1, φ2 = 2^p κ3, φ3 = p = a1/a2, applied to
/// Q̇ ≤ −2κ1 Q − 2^p κ3 Q^p, which follows from (40) since |σ|^{1+r} = (2Q)^p, r = 2p − 1.
pub fn bound_38(linear: f64, fractional: f64, a1: u32, a2: u32, sigma0: f64) -> Result<f64, ClaimsError> {
    let p = a1 as f64 / a2 as f64;
    if !(linear > 0.0 && fractional > 0.0 && a1 < a2 && 2 * u64::from(a1) > u64::from(a2) && sigma0.is_finite()) {
        return Err(num_err("bound_38", NumericsError::Bound38Inputs { linear, fractional, a1, a2 }));
    }
    let q0 = 0.5 * sigma0 * sigma0;
    let c = 2f64.powf(p - 1.0) * fractional;
    Ok(a2 as f64 / (2.0 * linear * (a2 - a1) as f64) * (linear * q0.powf((a2 - a1) as f64 / a2 as f64) / c).ln_1p())
}

/// The bound (38) with the exponents read literally as printed: Q0^{a2 − a1/a2} and
/// 2^{a1/a2} − 1 (s). Only to show that the literal reading cannot be meant.
pub fn bound_38_literal(linear: f64, fractional: f64, a1: u32, a2: u32, sigma0: f64) -> f64 {
    let (a1, a2) = (a1 as f64, a2 as f64);
    let q0 = 0.5 * sigma0 * sigma0;
    let c = (2f64.powf(a1 / a2) - 1.0) * fractional;
    a2 / (2.0 * linear * (a2 - a1)) * (linear * q0.powf(a2 - a1 / a2) / c).ln_1p()
}

/// Assumption 1's ζ for g = mean + amp·sin(freq·t) on t ≥ 0, tightest value: |mean| + |amp| if
/// the sine moves (freq ≠ 0, amp ≠ 0; the sine reaches ±1), else |mean|. Units of g.
pub fn zeta(g: &TipDisturbance) -> f64 {
    if g.freq != 0.0 && g.amp != 0.0 {
        g.mean.abs() + g.amp.abs()
    } else {
        g.mean.abs()
    }
}

/// [`Filippov::method`] when σ is integrated as the independent variable.
pub const SIGMA_DOMAIN: &str = "in σ instead of t (an exact change of variable: σ is monotone)";

/// Continuous-time (Filippov) limit of σ̇ = g(t) − φ(σ), σ(0) = σ0.
#[derive(Debug, Clone, PartialEq)]
pub struct Filippov {
    /// Reaching time of σ = 0 (s); `None` if not reached before the time limit.
    pub reach_s: Option<f64>,
    /// Estimated absolute error of `reach_s` (s): the difference of two resolutions plus the
    /// summation's round-off floor in the σ domain; the time step in the time domain.
    pub error_s: f64,
    /// Trajectory up to the reaching time: times (s).
    pub t: Vec<f64>,
    /// Trajectory: σ (units of g).
    pub sigma: Vec<f64>,
    /// How it was integrated, in words: in σ (an exact change of variable, used when σ is
    /// monotone) or in time.
    pub method: &'static str,
}

/// Reaching time of σ̇ = g(t) − φ(σ) from σ0, in the Filippov sense (σ stops at 0).
///
/// While σ ≠ 0 keeps its sign s0 and φ(|σ|) > s0 g(t), σ is monotone, so t is a function of σ:
/// with u = |σ|^r (r = gain exponent, removes the |σ|^r singularity), |σ| = u^{1/r},
/// dt/du = −(1/r) u^{1/r − 1} / (φ(u^{1/r}) − s0 g(t)), integrated by RK4 from u0 = |σ0|^r to 0
/// with `steps` and 2·`steps` steps (Richardson error estimate). If the denominator ever
/// becomes ≤ 0 (possible only when κ_sw < sup|g|) falls back to RK4 in time with step 1e-4 s
/// and linear location of the sign change (first order), up to `t_max` (s).
pub fn filippov_reach(
    gain: &ObserverGain,
    g: &dyn Fn(f64) -> f64,
    sigma0: f64,
    t_max: f64,
    steps: usize,
) -> Result<Filippov, ClaimsError> {
    let gains_ok = [gain.linear, gain.switching, gain.fractional].iter().all(|k| k.is_finite() && *k >= 0.0);
    if !(sigma0.is_finite() && gains_ok && gain.exponent > 0.0 && gain.exponent <= 1.0 && steps >= 2 && t_max > 0.0) {
        return Err(num_err("filippov_reach", NumericsError::FilippovInputs { sigma0, exponent: gain.exponent }));
    }
    if sigma0 == 0.0 {
        return Ok(Filippov { reach_s: Some(0.0), error_s: 0.0, t: vec![0.0], sigma: vec![0.0], method: SIGMA_DOMAIN });
    }
    match sigma_domain(gain, g, sigma0, steps) {
        Some((t1, tr, sg)) => {
            let (t2, _, _) = sigma_domain(gain, g, sigma0, 2 * steps).unwrap_or((t1, vec![], vec![]));
            let error_s = (t2 - t1).abs() + sum_round_off(t2, 2 * steps);
            Ok(Filippov { reach_s: Some(t2), error_s, t: tr, sigma: sg, method: SIGMA_DOMAIN })
        }
        None => Ok(time_domain(gain, g, sigma0, t_max)),
    }
}

/// Relative round-off of one RK4 increment of t(u) (four evaluations of the rate, each a
/// `powf`, a few products and one division, and their weighted sum): 16 ε, generous.
const INCREMENT_ROUND_OFF_EPS: f64 = 16.0;

/// Round-off floor of a time `t` (s) summed from `increments` positive RK4 increments: each
/// carries its own relative error ([`INCREMENT_ROUND_OFF_EPS`] ε) and recursive summation adds
/// at most (n − 1) ε of the sum (all terms have one sign), so (n + 16) ε t in all. The two
/// resolutions' difference alone can fall below it (they round alike), which printed the
/// reaching time with 15 digits on a ± of 9e-15 s at the paper's point.
fn sum_round_off(t: f64, increments: usize) -> f64 {
    (increments as f64 + INCREMENT_ROUND_OFF_EPS) * f64::EPSILON * t.abs()
}

/// RK4 of t(u) on a uniform u grid; `None` if σ is not monotone along the path.
fn sigma_domain(
    gain: &ObserverGain,
    g: &dyn Fn(f64) -> f64,
    sigma0: f64,
    steps: usize,
) -> Option<(f64, Vec<f64>, Vec<f64>)> {
    let s0 = sigma0.signum();
    let r = gain.exponent;
    let m = 1.0 / r;
    let u0 = sigma0.abs().powf(r);
    let du = u0 / steps as f64;
    // dt/dv with v = u0 − u increasing: m u^{m−1} / (φ(u^m) − s0 g(t)).
    let rate = |v: f64, t: f64| -> Option<f64> {
        let u = (u0 - v).max(0.0);
        let x = u.powf(m);
        let den = gain.linear * x + gain.switching + gain.fractional * u - s0 * g(t);
        let num = m * u.powf(m - 1.0);
        if den > 0.0 {
            Some(num / den)
        } else if num == 0.0 && den == 0.0 {
            Some(0.0)
        } else {
            None
        }
    };
    let stride = (steps / 400).max(1);
    let (mut t, mut tr, mut sg) = (0.0, vec![0.0], vec![sigma0]);
    for i in 0..steps {
        let v = i as f64 * du;
        t = rk4_step(rate, v, t, du)?;
        if (i + 1) % stride == 0 || i + 1 == steps {
            tr.push(t);
            sg.push(s0 * (u0 - v - du).max(0.0).powf(m));
        }
    }
    Some((t, tr, sg))
}

fn time_domain(gain: &ObserverGain, g: &dyn Fn(f64) -> f64, sigma0: f64, t_max: f64) -> Filippov {
    let h = 1e-4;
    let f = |t: f64, s: f64| g(t) - gain.phi(s);
    let (mut t, mut s) = (0.0, sigma0);
    let (mut tr, mut sg) = (vec![0.0], vec![sigma0]);
    let mut reach = None;
    let mut k = 0usize;
    while t < t_max {
        let next = rk4_step(|t, s| Some(f(t, s)), t, s, h).unwrap_or(f64::NAN);
        if next == 0.0 || next.signum() != sigma0.signum() {
            reach = Some(t + h * s / (s - next));
            break;
        }
        s = next;
        t += h;
        k += 1;
        if k % 100 == 0 {
            tr.push(t);
            sg.push(s);
        }
    }
    Filippov { reach_s: reach, error_s: h, t: tr, sigma: sg, method: "in time (fixed steps, σ not monotone)" }
}

/// Per-channel results of one digital run.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct DigitalChannel {
    /// σ(0) (units of g).
    pub sigma0: f64,
    /// Reaching time (s): implicit rule — first sample from which |σ_k| ≤ T κ_sw for the rest of
    /// the run (the deadbeat band); explicit rule — first sample where σ_k = 0 or changes sign.
    pub reach_s: Option<f64>,
    /// max |σ_k| after reaching (units of g): implicit — over the samples after the entry sample
    /// (≤ T·sup|g| when the observer slides); explicit — from the first crossing on (chatter band).
    /// If never reached: max |σ_k| over the whole run.
    pub sigma_after_max: f64,
    /// max |g(t_k) − ĝ_k| over the chatter window (units of g): the sampled g̃.
    pub gtilde_max: f64,
    /// max |ĝ_{k+1} − ĝ_k| over the chatter window: sample-to-sample jump of ĝ.
    pub ghat_jump_max: f64,
    /// max |τ_{k+1} − τ_k| over the chatter window: sample-to-sample jump of τ (N or N m).
    pub tau_jump_max: f64,
    /// Sample times (s), only if a trace was requested.
    pub t: Vec<f64>,
    /// σ_k, only with a trace.
    pub sigma: Vec<f64>,
    /// ĝ_k, only with a trace.
    pub g_hat: Vec<f64>,
    /// τ_k, only with a trace.
    pub tau: Vec<f64>,
}

/// One closed-loop run of the FTDO with a given sampling rule and hold period.
#[derive(Debug, Clone, PartialEq)]
pub struct DigitalRun {
    /// Sampling rule.
    pub rule: ObserverRule,
    /// Hold period T (s).
    pub period: f64,
    /// Chatter window [start, end] (s).
    pub window: (f64, f64),
    /// Bending and torsion channels.
    pub channels: [DigitalChannel; 2],
}

/// The configuration of a digital FTDO run: `cfg` with the given rule and hold period T (s),
/// integrator step dt = T / ⌈T/dt_cfg⌉ (≤ the configured dt, a whole fraction of T), horizon `t_end`.
/// ([`wingcheck_model::work::finite_time_config`], the run the work estimate counts).
pub fn digital_config(cfg: &Config, rule: ObserverRule, period: f64, t_end: f64) -> Config {
    wingcheck_model::work::finite_time_config(cfg, rule, period, t_end)
}

/// σ(0) of channel `ix` (0: bending, 1: torsion) from the configured initial state.
pub fn sigma0_other(cfg: &Config, ix: usize) -> Result<f64, ClaimsError> {
    let c = digital_config(cfg, cfg.observer.rule, cfg.observer.sample_period, cfg.horizon.t_end);
    Ok(wingcheck_sim::Stepper::new(&c)?.channels[ix].sigma)
}

/// Run the closed loop (FTDO, `rule`, hold `period`) over [0, `t_end`] sample by sample and
/// measure σ's reaching time and the chatter of ĝ and τ over the last `window` seconds.
/// `trace_from`: keep per-sample traces from this time on (None: no traces). `basis`: the modal
/// basis of `cfg`'s discretisation when the simulator steps `cfg` in it
/// ([`wingcheck_sim::run::resolved_basis`]), None for the nodal stepper: the same discrete
/// equations either way, so the samples agree to round-off.
pub fn digital_run(
    cfg: &Config,
    basis: Option<&ModalBasis>,
    rule: ObserverRule,
    period: f64,
    t_end: f64,
    window: f64,
    trace_from: Option<f64>,
) -> Result<DigitalRun, ClaimsError> {
    if !(period > 0.0 && t_end > period && window > 0.0) {
        return Err(num_err("digital_run", NumericsError::DigitalRunInputs { period, t_end, window }));
    }
    let c = digital_config(cfg, rule, period, t_end);
    let n = c.total_samples();
    let bands =
        [TipChannel::Bending, TipChannel::Torsion].map(|ch| period * ChannelObserver::new(&c, ch).gain.switching);
    let fresh = || Analysis {
        rule,
        window_start: t_end - window,
        trace_from,
        bands,
        g: [c.disturbance.tip_bending.clone(), c.disturbance.tip_torsion.clone()],
        out: Default::default(),
        first_out: [None; 2],
        sig_hist: [Vec::with_capacity(n + 1), Vec::with_capacity(n + 1)],
        prev: None,
    };
    let mut run = fresh();
    let modal = match basis {
        Some(basis) => {
            // every sample is an output (the config's sample_every is T); the scheme the nodal
            // stepper would take (`auto`: TR-BDF2)
            let mut m = c.clone();
            m.discretisation.stepper = c.time_scheme(false);
            m.validate().map_err(wingcheck_sim::SimError::Config)?;
            let lp = ModalLoop::new(&m, basis)?;
            let mut st = lp.initial_state(&m, basis);
            let mut rec = EachSample(&mut run);
            match drive(&m, basis, &lp, &mut st, &mut ObserverSignal::new(&m), &mut rec) {
                Ok(()) => true,
                // The driver stops a run whose energy explodes; a digital run measures what the
                // observer does even then (e.g. the explicit rule with κ_lin·T > 2, unstable
                // by design), as the nodal stepper always has: that run is stepped there.
                Err(wingcheck_sim::SimError::Diverged { .. }) => {
                    run = fresh();
                    false
                }
                Err(e) => return Err(e.into()),
            }
        }
        None => false,
    };
    if !modal {
        let mut st = Stepper::new(&c)?;
        for k in 0..=n {
            if k > 0 {
                st.advance_sample();
            }
            run.push(k, &st.sample());
        }
    }
    let Analysis { mut out, first_out, sig_hist, .. } = run;
    reach_and_overshoot(&mut out, rule, period, &first_out, &sig_hist, n);
    Ok(DigitalRun { rule, period, window: (t_end - window, t_end), channels: out })
}

/// What a digital run measures, sample by sample.
struct Analysis {
    rule: ObserverRule,
    window_start: f64,
    trace_from: Option<f64>,
    /// The implicit rule's deadbeat bands T·κ_sw per channel (units of g).
    bands: [f64; 2],
    g: [TipDisturbance; 2],
    out: [DigitalChannel; 2],
    /// Implicit: the last sample outside the band; explicit: the first crossing.
    first_out: [Option<usize>; 2],
    sig_hist: [Vec<f64>; 2],
    prev: Option<Sample>,
}

impl Analysis {
    /// Fold in sample `k` (at t_k = k T, after the held estimate's jump).
    fn push(&mut self, k: usize, s: &Sample) {
        let prev = *self.prev.get_or_insert(*s);
        let sig = [s.sigma1, s.sigma2];
        let gh = [s.g1_hat, s.g2_hat];
        let tau = [s.tau1, s.tau2];
        let pgh = [prev.g1_hat, prev.g2_hat];
        let ptau = [prev.tau1, prev.tau2];
        let w0 = self.window_start;
        for i in 0..2 {
            let ch = &mut self.out[i];
            if k == 0 {
                ch.sigma0 = sig[i];
            }
            self.sig_hist[i].push(sig[i]);
            match self.rule {
                ObserverRule::Implicit => {
                    if sig[i].abs() > self.bands[i] {
                        self.first_out[i] = Some(k);
                    }
                }
                ObserverRule::Explicit => {
                    if ch.reach_s.is_none() && (sig[i] == 0.0 || sig[i].signum() != ch.sigma0.signum()) {
                        ch.reach_s = Some(s.t);
                        self.first_out[i] = Some(k);
                    }
                }
            }
            if s.t >= w0 - 1e-12 {
                ch.gtilde_max = ch.gtilde_max.max((self.g[i].at(s.t) - gh[i]).abs());
                if k > 0 && prev.t >= w0 - 1e-12 {
                    ch.ghat_jump_max = ch.ghat_jump_max.max((gh[i] - pgh[i]).abs());
                    ch.tau_jump_max = ch.tau_jump_max.max((tau[i] - ptau[i]).abs());
                }
            }
            if self.trace_from.is_some_and(|t0| s.t >= t0 - 1e-12) {
                ch.t.push(s.t);
                ch.sigma.push(sig[i]);
                ch.g_hat.push(gh[i]);
                ch.tau.push(tau[i]);
            }
        }
        self.prev = Some(*s);
    }
}

/// The modal driver's recorder of a digital run: every output sample (every observer sample)
/// into the [`Analysis`]; nothing else is read, so the driver skips the state's reconstruction
/// and the tip boundary states (neither feeds back).
struct EachSample<'a>(&'a mut Analysis);

impl Recorder for EachSample<'_> {
    fn instant(
        &mut self,
        _: &ModalLoop<'_>,
        _: &ModalState,
        _: f64,
        _: [f64; 2],
        _: Option<[f64; 2]>,
        _: Option<[f64; 2]>,
    ) {
    }

    fn output(&mut self, _: &ModalState, sample: &Sample, k: usize) -> Result<(), wingcheck_sim::SimError> {
        debug_assert_eq!(k, self.0.sig_hist[0].len(), "every sample is an output");
        self.0.push(k, sample);
        Ok(())
    }

    fn deferred_squares(&mut self, _: [f64; 2]) {}

    fn reads(&self) -> Reads {
        Reads::OUTPUTS
    }
}

/// Each channel's reach time (implicit: the sample after the last one outside the band T·k_sw;
/// explicit: the first sign change of σ) and max |σ_k| after it (over the whole run if the band
/// was never reached). `first_out` holds the deciding sample of each channel, `sig_hist` σ_k.
fn reach_and_overshoot(
    out: &mut [DigitalChannel; 2],
    rule: ObserverRule,
    period: f64,
    first_out: &[Option<usize>; 2],
    sig_hist: &[Vec<f64>; 2],
    n: usize,
) {
    for i in 0..2 {
        let ch = &mut out[i];
        let start = match rule {
            ObserverRule::Implicit => match first_out[i] {
                None => Some(0),
                Some(k) if k < n => Some(k + 1),
                Some(_) => None,
            },
            ObserverRule::Explicit => first_out[i],
        };
        if let Some(k0) = start {
            ch.reach_s = Some(k0 as f64 * period);
            // Implicit: strictly after the entry sample (the entry itself may be anywhere in the band).
            let from = if rule == ObserverRule::Implicit { k0 + 1 } else { k0 };
            ch.sigma_after_max = max_abs(sig_hist[i].get(from..).unwrap_or(&[])).unwrap_or(0.0);
        } else {
            ch.reach_s = None;
            // never reached: the band was never entered, report max |σ_k| over the whole run
            ch.sigma_after_max = max_abs(&sig_hist[i]).unwrap_or(0.0);
        }
    }
}

/// A [`ClaimsError::Numerical`].
pub(crate) fn num_err(what: &'static str, cause: NumericsError) -> ClaimsError {
    ClaimsError::Numerical { what, cause }
}
