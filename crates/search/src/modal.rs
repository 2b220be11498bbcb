//! The closed loop of one search point, run in the modal basis of the wing: one simulation
//! per point, O(n) work per step, and everything that does not change across points computed
//! once per search.
//!
//! It is the simulator's scheme ([`wingcheck_sim::Stepper`]: trapezoidal rule on
//! M ẍ + C ẋ + K_c x = f̄ with C = ξK + b·T, K_c = K + a·T, T = diag(k1, k2) at the tip
//! unknowns; step matrix S = 2M/h + C + (h/2)K_c), written in another basis:
//!
//! - **Modal basis** (per wing, shared): K Φ = M Φ Ω², ΦᵀMΦ = I (Cholesky of M, symmetric
//!   eigenproblem of L⁻¹KL⁻ᵀ). With x = Φη, v = Φζ the step matrix becomes
//!   D + β UKUᵀ with D = diag(2/h + (ξ + h/2)ω_i²), β = b + ha/2 and U = the tip rows of Φ
//!   (n×2): diagonal plus rank 2, solved by the Woodbury identity in O(n) — no sparse
//!   factorisation per point at all.
//! - **Observer signal** (per observer/disturbance, shared): the observer's σ obeys
//!   σ_{n+1} − σ_n = h(ḡ − ĝ_k) whatever the plant (the tip boundary condition cancels τ
//!   and w, see `wingcheck_control::ChannelObserver`), so ĝ_k, and with it the tip input
//!   ḡ − ĝ of every step, is the same at every point of a sweep over plant or control-law
//!   keys. It is computed once, together with the step averages φ̄ of the distributed load.
//!
//! Same equations, so the results agree with `wingcheck_sim::simulate` to round-off
//! (tests/modal.rs), not bit for bit. Only the tip quantities the metrics need are recorded.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use faer::{Mat, Side};
use serde::Serialize;
use wingcheck_control::{ChannelObserver, TipChannel};
use wingcheck_model::{Config, ControllerKind, InitialShape};
use wingcheck_sim::{check_sample, Discretisation, Sample, SimError};

/// Entries kept per cache before it is cleared (bounds memory on sweeps over wing keys).
const CACHE_ENTRIES: usize = 16;

/// The wing in its modal basis (units: ω² in 1/s², modal coordinates in √kg·m).
#[derive(Debug)]
pub struct ModalBasis {
    /// ω_i² (1/s²), ascending.
    omega2: Vec<f64>,
    /// Rows of Φ at the tip unknowns q(s) and θ(s).
    tip: [Vec<f64>; 2],
    /// Φᵀ f_h: the distributed load's shape in modal coordinates.
    load: Vec<f64>,
    /// η(0) = ΦᵀM x(0).
    eta0: Vec<f64>,
}

impl ModalBasis {
    /// Modal basis of the configuration's discretised wing.
    pub fn new(cfg: &Config) -> Result<ModalBasis, SimError> {
        let disc = Discretisation::new(cfg);
        let n = disc.dim();
        if n > crate::limits::MODAL_MAX_UNKNOWNS {
            return Err(SimError::Numerical(format!(
                "{n} unknowns: above the modal runner's {} (dense eigenproblem)",
                crate::limits::MODAL_MAX_UNKNOWNS
            )));
        }
        let dense = |v: Vec<f64>| Mat::from_fn(n, n, |i, j| v[i * n + j]);
        let (m, k) = (dense(disc.mass.to_dense()), dense(disc.stiffness.to_dense()));
        let llt = m
            .llt(Side::Lower)
            .map_err(|e| SimError::Numerical(format!("mass matrix is not positive definite: {e:?}")))?;
        let l = llt.L();
        // C = L⁻¹ K L⁻ᵀ (symmetrised)
        let mut y = k.clone();
        faer::linalg::triangular_solve::solve_lower_triangular_in_place(l, y.as_mut(), faer::Par::Seq);
        let mut c = y.transpose().to_owned();
        faer::linalg::triangular_solve::solve_lower_triangular_in_place(l, c.as_mut(), faer::Par::Seq);
        let c = Mat::from_fn(n, n, |i, j| 0.5 * (c[(i, j)] + c[(j, i)]));
        let evd = c
            .self_adjoint_eigen(Side::Lower)
            .map_err(|e| SimError::Numerical(format!("modal eigenproblem failed: {e:?}")))?;
        let v = evd.U();
        let omega2: Vec<f64> = (0..n).map(|i| evd.S()[i]).collect();
        if omega2.iter().any(|w| !w.is_finite() || *w < 0.0) {
            return Err(SimError::Numerical("stiffness matrix is not positive semidefinite".into()));
        }
        // Φ = L⁻ᵀ V
        let mut phi = v.to_owned();
        faer::linalg::triangular_solve::solve_upper_triangular_in_place(l.transpose(), phi.as_mut(), faer::Par::Seq);
        let tip = [disc.tip_q, disc.tip_theta].map(|d| (0..n).map(|i| phi[(d, i)]).collect::<Vec<f64>>());
        let load = (0..n).map(|i| (0..n).map(|r| phi[(r, i)] * disc.load[r]).sum()).collect();
        let mut mx0 = vec![0.0; n];
        disc.mass.mul_into(&disc.x0, &mut mx0);
        let eta0 = (0..n).map(|i| (0..n).map(|r| phi[(r, i)] * mx0[r]).sum()).collect();
        Ok(ModalBasis { omega2, tip, load, eta0 })
    }

    /// Number of modes (= unknowns).
    pub fn len(&self) -> usize {
        self.omega2.len()
    }

    /// True if there are no modes (never for a valid wing).
    pub fn is_empty(&self) -> bool {
        self.omega2.is_empty()
    }
}

/// The plant-independent inputs of a run: per integrator step the load factor φ̄ and the
/// tip inputs ḡ − ĝ; per observer sample ĝ_k and g(t_k).
#[derive(Debug)]
pub struct InputSignal {
    /// φ̄ over each step (dimensionless time factor of g_h).
    phi_mean: Vec<f64>,
    /// ḡ − ĝ over each step: N (bending), N m (torsion).
    tip_input: [Vec<f64>; 2],
    /// ĝ_k held from t_k, k = 0..=K.
    pub g_hat: [Vec<f64>; 2],
    /// g(t_k), k = 0..=K.
    pub g: [Vec<f64>; 2],
}

impl InputSignal {
    /// The signal of `cfg` (its observer, disturbances, initial tip states, horizon).
    pub fn new(cfg: &Config) -> InputSignal {
        let h = cfg.discretisation.dt;
        let period = cfg.observer.sample_period;
        let (m, total) = (cfg.steps_per_sample(), cfg.total_samples());
        let s = cfg.wing.span;
        // initial tip states q'''(s,0), θ'(s,0), as the stepper sets them
        let w0 = [
            match cfg.initial.shape {
                InitialShape::Linear => 0.0,
                InitialShape::Cantilever => -3.0 * cfg.initial.q_tip / s.powi(3),
            },
            cfg.initial.theta_tip / s,
        ];
        let tips = [&cfg.disturbance.tip_bending, &cfg.disturbance.tip_torsion];
        let dist = &cfg.disturbance.distributed;
        let mut phi_mean = Vec::with_capacity(total * m);
        for k in 0..total {
            let t0 = k as f64 * period;
            for j in 0..m {
                let t = t0 + j as f64 * h;
                phi_mean.push(dist.phi_integral(t, t + h) / h);
            }
        }
        let mut tip_input = [Vec::with_capacity(total * m), Vec::with_capacity(total * m)];
        let mut g_hat = [Vec::with_capacity(total + 1), Vec::with_capacity(total + 1)];
        let mut g = [Vec::with_capacity(total + 1), Vec::with_capacity(total + 1)];
        for (c, ch) in [TipChannel::Bending, TipChannel::Torsion].into_iter().enumerate() {
            let obs = ChannelObserver::new(cfg, ch);
            let estimate = |sigma: f64| if obs.active { obs.gain.sample(obs.rule, sigma, obs.period) } else { 0.0 };
            let mut sigma = obs.sigma(w0[c]);
            for k in 0..=total {
                let t0 = k as f64 * period;
                let gh = estimate(sigma);
                g_hat[c].push(gh);
                g[c].push(tips[c].at(t0));
                if k == total {
                    break;
                }
                for j in 0..m {
                    let t = t0 + j as f64 * h;
                    let gm = tips[c].mean_over(t, t + h);
                    tip_input[c].push(gm - gh);
                    sigma += h * (gm - gh);
                }
            }
        }
        InputSignal { phi_mean, tip_input, g_hat, g }
    }

    /// sup |g(t_k) − ĝ_k| over the output samples of `cfg` (k a multiple of
    /// `samples_per_output`, and k = K), per channel: ζ3 (N), ζ4 (N m) of (32) as
    /// `wingcheck_claims::mu::disturbance_bounds` defines them (sup over the FTDO run's series).
    pub fn sup_tilde(&self, cfg: &Config) -> (f64, f64) {
        let (every, total) = (cfg.samples_per_output(), cfg.total_samples());
        let sup = |c: usize| {
            (0..=total)
                .filter(|k| k % every == 0 || *k == total)
                .map(|k| (self.g[c][k] - self.g_hat[c][k]).abs())
                .fold(0.0, f64::max)
        };
        (sup(0), sup(1))
    }
}

/// What the metrics need of a run, at the output samples: t (s), q(s,t) (m), θ(s,t) (rad),
/// τ1 (N), τ2 (N m), g̃ = g − ĝ per channel, and E(T) (J).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct TipTrace {
    /// Sample times (s).
    pub t: Vec<f64>,
    /// q(s,t) (m).
    pub q_tip: Vec<f64>,
    /// θ(s,t) (rad).
    pub theta_tip: Vec<f64>,
    /// τ1 (N).
    pub tau1: Vec<f64>,
    /// τ2 (N m).
    pub tau2: Vec<f64>,
    /// g1 − ĝ1 (N).
    pub g1_tilde: Vec<f64>,
    /// g2 − ĝ2 (N m).
    pub g2_tilde: Vec<f64>,
    /// Mechanical energy at T (J).
    pub energy_end: f64,
}

impl TipTrace {
    /// The trace of a full simulator run (fallback path and tests).
    pub fn from_series(s: &wingcheck_sim::Series) -> TipTrace {
        let tilde = |g: &[f64], h: &[f64]| g.iter().zip(h).map(|(a, b)| a - b).collect();
        TipTrace {
            t: s.t.clone(),
            q_tip: s.q_tip.clone(),
            theta_tip: s.theta_tip.clone(),
            tau1: s.tau1.clone(),
            tau2: s.tau2.clone(),
            g1_tilde: tilde(&s.g1, &s.g1_hat),
            g2_tilde: tilde(&s.g2, &s.g2_hat),
            energy_end: s.energy.last().copied().unwrap_or(0.0),
        }
    }
}

/// Run the closed loop of `cfg` on a shared basis and signal (built from configurations that
/// agree with `cfg` on the keys they read; [`RunCache`] guarantees it).
pub fn run(cfg: &Config, basis: &ModalBasis, signal: &InputSignal) -> Result<TipTrace, SimError> {
    cfg.validate().map_err(SimError::Config)?;
    let n = basis.len();
    let h = cfg.discretisation.dt;
    let (a, b, xi) = (cfg.control.a, cfg.control.b, cfg.wing.xi);
    let gain = match cfg.control.kind {
        ControllerKind::None => [0.0, 0.0],
        _ => [cfg.control.k1, cfg.control.k2],
    };
    let beta = b + 0.5 * h * a;
    let (om, u) = (&basis.omega2, &basis.tip);
    let d_inv: Vec<f64> = om.iter().map(|w| 1.0 / (2.0 / h + (xi + 0.5 * h) * w)).collect();
    let z: [Vec<f64>; 2] = [0, 1].map(|c| (0..n).map(|i| d_inv[i] * u[c][i]).collect());
    let coef_zeta: Vec<f64> = d_inv.iter().map(|d| (2.0 / h) * d).collect();
    let coef_eta: Vec<f64> = (0..n).map(|i| d_inv[i] * om[i]).collect();
    let load_d: Vec<f64> = (0..n).map(|i| d_inv[i] * basis.load[i]).collect();
    // Q = Uᵀ D⁻¹ U; G = I + βK Q; H = G⁻¹ βK
    let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>();
    let q = [[dot(&u[0], &z[0]), dot(&u[0], &z[1])], [dot(&u[1], &z[0]), dot(&u[1], &z[1])]];
    let wk = [beta * gain[0], beta * gain[1]];
    let g = [[1.0 + wk[0] * q[0][0], wk[0] * q[0][1]], [wk[1] * q[1][0], 1.0 + wk[1] * q[1][1]]];
    let det = g[0][0] * g[1][1] - g[0][1] * g[1][0];
    if !(det.is_finite() && det > 0.0) {
        return Err(SimError::Numerical(format!("step matrix capacitance is singular (det {det:e})")));
    }
    let gi = [[g[1][1] / det, -g[0][1] / det], [-g[1][0] / det, g[0][0] / det]];
    let hm = [[gi[0][0] * wk[0], gi[0][1] * wk[1]], [gi[1][0] * wk[0], gi[1][1] * wk[1]]];

    let mut eta = basis.eta0.clone();
    let mut zeta = vec![0.0; n];
    let mut y = vec![0.0; n];
    let mut x_tip = [dot(&u[0], &eta), dot(&u[1], &eta)];
    let mut v_tip = [0.0, 0.0];
    let s = cfg.wing.span;
    let stiff = [cfg.wing.ei, cfg.wing.gj];
    let sign = [TipChannel::Bending.bc_sign(), TipChannel::Torsion.bc_sign()];
    let mut w = [
        match cfg.initial.shape {
            InitialShape::Linear => 0.0,
            InitialShape::Cantilever => -3.0 * cfg.initial.q_tip / s.powi(3),
        },
        cfg.initial.theta_tip / s,
    ];
    let energy =
        |eta: &[f64], zeta: &[f64]| 0.5 * (0..n).map(|i| zeta[i] * zeta[i] + om[i] * eta[i] * eta[i]).sum::<f64>();
    let (m, total, every) = (cfg.steps_per_sample(), cfg.total_samples(), cfg.samples_per_output());
    let period = cfg.observer.sample_period;
    let mut trace = TipTrace::default();
    let mut e0 = 0.0;
    let mut record = |k: usize, x_tip: [f64; 2], v_tip: [f64; 2], w: [f64; 2], e: f64, tr: &mut TipTrace| {
        let gh = [signal.g_hat[0][k], signal.g_hat[1][k]];
        let tau = [0, 1].map(|c| -gain[c] * (a * x_tip[c] + b * v_tip[c]) - gh[c]);
        let sample = Sample {
            t: k as f64 * period,
            q_tip: x_tip[0],
            theta_tip: x_tip[1],
            q_tip_rate: v_tip[0],
            theta_tip_rate: v_tip[1],
            tau1: tau[0],
            tau2: tau[1],
            g1: signal.g[0][k],
            g2: signal.g[1][k],
            g1_hat: gh[0],
            g2_hat: gh[1],
            sigma1: 0.0,
            sigma2: 0.0,
            energy: e,
            q_tip_shear: w[0],
            theta_tip_slope: w[1],
        };
        if k == 0 {
            e0 = e;
        }
        check_sample(&sample, e0)?;
        tr.t.push(sample.t);
        tr.q_tip.push(sample.q_tip);
        tr.theta_tip.push(sample.theta_tip);
        tr.tau1.push(tau[0]);
        tr.tau2.push(tau[1]);
        tr.g1_tilde.push(sample.g1 - gh[0]);
        tr.g2_tilde.push(sample.g2 - gh[1]);
        tr.energy_end = e;
        Ok::<(), SimError>(())
    };
    record(0, x_tip, v_tip, w, energy(&eta, &zeta), &mut trace)?;
    let mut step = 0;
    for k in 1..=total {
        let gh = [signal.g_hat[0][k - 1], signal.g_hat[1][k - 1]];
        for _ in 0..m {
            let phi = signal.phi_mean[step];
            let f = [
                signal.tip_input[0][step] - a * gain[0] * x_tip[0],
                signal.tip_input[1][step] - a * gain[1] * x_tip[1],
            ];
            step += 1;
            // y = D⁻¹ r with r = (2/h)ζ − Ω²η + φ̄ Φᵀf_h + U f, per mode with the factors
            // D⁻¹ folded in (coef_zeta = 2/h D⁻¹, coef_eta = Ω² D⁻¹, load_d = D⁻¹Φᵀf_h, z = D⁻¹U);
            // t = Uᵀ y. Iterators over equal-length slices: no bounds checks, vectorised.
            let (mut t0, mut t1) = (0.0, 0.0);
            for (((((yi, (&zt, &et)), (&cz, &ce)), &ld), (&z0, &z1)), (&u0, &u1)) in y
                .iter_mut()
                .zip(zeta.iter().zip(eta.iter()))
                .zip(coef_zeta.iter().zip(&coef_eta))
                .zip(&load_d)
                .zip(z[0].iter().zip(&z[1]))
                .zip(u[0].iter().zip(&u[1]))
            {
                let v = cz * zt - ce * et + phi * ld + z0 * f[0] + z1 * f[1];
                *yi = v;
                t0 += u0 * v;
                t1 += u1 * v;
            }
            let c = [hm[0][0] * t0 + hm[0][1] * t1, hm[1][0] * t0 + hm[1][1] * t1];
            for (((yi, (zt, et)), &z0), &z1) in y.iter().zip(zeta.iter_mut().zip(eta.iter_mut())).zip(&z[0]).zip(&z[1])
            {
                let zbar = yi - z0 * c[0] - z1 * c[1];
                *et += h * zbar;
                *zt = 2.0 * zbar - *zt;
            }
            // tip rates v̄ = Uᵀ ζ̄ = t − Q c, and the tip boundary states w (as the stepper)
            let vbar = [t0 - q[0][0] * c[0] - q[0][1] * c[1], t1 - q[1][0] * c[0] - q[1][1] * c[1]];
            for ch in 0..2 {
                let xbar = x_tip[ch] + 0.5 * h * vbar[ch];
                let tau_mean = -gain[ch] * (a * xbar + b * vbar[ch]) - gh[ch];
                let force = tau_mean + signal.tip_input[ch][step - 1] + gh[ch];
                let st = stiff[ch];
                w[ch] = if xi > 0.0 {
                    (xi * st * w[ch] + h * sign[ch] * force - 0.5 * h * st * w[ch]) / (xi * st + 0.5 * h * st)
                } else {
                    sign[ch] * force / st
                };
                x_tip[ch] += h * vbar[ch];
                v_tip[ch] = 2.0 * vbar[ch] - v_tip[ch];
            }
        }
        if k % every == 0 || k == total {
            record(k, x_tip, v_tip, w, energy(&eta, &zeta), &mut trace)?;
        }
    }
    Ok(trace)
}

fn cache_get<T>(map: &Mutex<HashMap<String, Arc<T>>>, key: String, make: impl FnOnce() -> T) -> Arc<T> {
    if let Some(v) = map.lock().expect("cache lock").get(&key) {
        return v.clone();
    }
    let v = Arc::new(make());
    let mut m = map.lock().expect("cache lock");
    if m.len() >= CACHE_ENTRIES {
        m.clear();
    }
    m.entry(key).or_insert(v).clone()
}

/// Shared modal bases and input signals of a search (thread-safe; values are pure functions
/// of their keys, so caching never changes a result).
#[derive(Default)]
pub struct RunCache {
    bases: Mutex<HashMap<String, Arc<Result<ModalBasis, String>>>>,
    signals: Mutex<HashMap<String, Arc<InputSignal>>>,
}

impl RunCache {
    /// Empty caches.
    pub fn new() -> Self {
        Self::default()
    }

    /// Modal basis of the wing: keyed by everything `Discretisation::new` reads.
    pub fn basis(&self, cfg: &Config) -> Arc<Result<ModalBasis, String>> {
        let key = serde_json::to_string(&(
            &cfg.wing,
            &cfg.discretisation.method,
            cfg.discretisation.elements,
            cfg.discretisation.grading,
            &cfg.initial,
            &cfg.disturbance.distributed,
            cfg.horizon.field_points,
        ))
        .expect("serialises");
        cache_get(&self.bases, key, || ModalBasis::new(cfg).map_err(|e| e.to_string()))
    }

    /// Input signal of `cfg` (its control kind); keyed by everything [`InputSignal::new`] reads.
    pub fn signal(&self, cfg: &Config) -> Arc<InputSignal> {
        let key = serde_json::to_string(&(
            &cfg.observer,
            &cfg.disturbance,
            &cfg.control.kind,
            &cfg.initial,
            (cfg.wing.span, cfg.wing.ei, cfg.wing.gj, cfg.wing.xi),
            cfg.discretisation.dt,
            &cfg.horizon,
        ))
        .expect("serialises");
        cache_get(&self.signals, key, || InputSignal::new(cfg))
    }
}
