//! Section 4, Figs 3–20: the proposed FTDO controller against DOBC (57, corrected).
//!
//! Both controllers use the same law (15) and gains; they differ only in ĝ. Metrics over the
//! windows [0, t_end] ("full") and [t_end/2, t_end] ("late") from the 0.01-s output series.
//!
//! Evidence keys, per run label L ∈ {`ftdo-implicit`, `ftdo-explicit`, `dobc`} at the
//! configured (a, b): `L.{rms,max}_{q,theta}_{full,late}` (m, rad), `L.settle_{q,theta}_s`
//! (s; last exit from |q| ≤ `SETTLE_FRACTION`·|q(s,0)|, |θ| ≤ `SETTLE_FRACTION`·|θ(s,0)|; null if never),
//! `L.{rms,peak}_{tau1,tau2}` (N, N m, full window), `L.rms_gtilde{1,2}_{full,late}`,
//! `L.gtilde{1,2}_settle_s` (last exit from |g̃| ≤ `GTILDE_THRESHOLD`); and
//! `rel_diff_rms_q_full`, `rel_diff_rms_theta_full`, `rel_diff_rms_q_late`,
//! `rel_diff_rms_theta_late` ((DOBC − FTDO)/FTDO, implicit FTDO), `gtilde_ratio_late`
//! (RMS g̃ DOBC / FTDO, late, both channels combined), `ab_sweep` (array of objects with
//! a, b and the relative differences), `max_abs_rel_diff_tip` (over the sweep and both rules),
//! `late_min_rel_diff` (most negative late-window difference: < 0 means DOBC smaller).

use std::collections::BTreeMap;
use std::time::Instant;

use serde_json::{json, Value};
use wingcheck_model::{Config, ControllerKind, ObserverRule};
use wingcheck_sim::Series;

use crate::study::Study;

use crate::{Basis, ClaimRow, ClaimsError, Line, PlotData, Verdict};

/// Settling threshold for |q(s,t)| and |θ(s,t)| as a fraction of their initial tip values.
pub const SETTLE_FRACTION: f64 = 0.1;
/// Threshold for |g̃| (N or N m) defining "g̃ has converged".
pub const GTILDE_THRESHOLD: f64 = 1e-4;
/// (a, b) pairs of the sensitivity sweep (besides the configured one).
pub const AB_SWEEP: [(f64, f64); 3] = [(0.5, 1.0), (1.0, 0.5), (2.0, 2.0)];
/// Relative difference of tip metrics below which the controllers count as indistinguishable.
pub const INDISTINGUISHABLE: f64 = 0.05;

/// Metrics of one run.
#[derive(Debug, Clone, PartialEq)]
pub struct Metrics {
    /// Named values (keys as in the module documentation, without the run label).
    pub values: BTreeMap<String, Value>,
}

impl Metrics {
    /// Numeric value by key (0 if missing or not a number, e.g. "never within the horizon").
    pub fn get(&self, key: &str) -> f64 {
        self.values.get(key).and_then(Value::as_f64).unwrap_or(0.0)
    }

    /// A settling time as text: "x.xx s" or "never within the horizon".
    pub fn settle_text(&self, key: &str) -> String {
        match self.values.get(key).and_then(Value::as_f64) {
            Some(t) => format!("{t:.2} s"),
            None => NEVER_SETTLED.into(),
        }
    }
}

/// How a settling time that is not reached before T is written in the evidence and texts.
pub const NEVER_SETTLED: &str = "never within the horizon";

fn settle_value(t: Option<f64>) -> Value {
    match t {
        Some(t) => json!(t),
        None => json!(NEVER_SETTLED),
    }
}

/// Relative excess (y − x)/|x| (0 when both vanish, ±1 when only x does).
fn rel_excess(x: f64, y: f64) -> f64 {
    if x != 0.0 {
        (y - x) / x.abs()
    } else if y == 0.0 {
        0.0
    } else {
        y.signum()
    }
}

/// y/x for non-negative magnitudes, saturating at f64::MAX when x = 0 < y (1 when both vanish).
fn ratio(y: f64, x: f64) -> f64 {
    if x > 0.0 {
        (y / x).min(f64::MAX)
    } else if y > 0.0 {
        f64::MAX
    } else {
        1.0
    }
}

fn rms(x: &[f64]) -> f64 {
    if x.is_empty() {
        return 0.0;
    }
    (x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64).sqrt()
}

fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// Time after which |x| ≤ thr for the rest of the series (None if the last sample exceeds it).
pub fn settle_time(t: &[f64], x: &[f64], thr: f64) -> Option<f64> {
    match x.iter().rposition(|v| v.abs() > thr) {
        None => t.first().copied(),
        Some(i) if i + 1 < t.len() => Some(t[i + 1]),
        Some(_) => None,
    }
}

/// Metrics of one simulated series (see module docs).
pub fn metrics(s: &Series) -> Metrics {
    let n = s.t.len();
    let t_end = s.t.last().copied().unwrap_or(0.0);
    let late = s.t.partition_point(|&t| t < 0.5 * t_end).min(n);
    let gt1: Vec<f64> = s.g1.iter().zip(&s.g1_hat).map(|(g, h)| g - h).collect();
    let gt2: Vec<f64> = s.g2.iter().zip(&s.g2_hat).map(|(g, h)| g - h).collect();
    let mut v = BTreeMap::new();
    for (name, x) in [("q", &s.q_tip), ("theta", &s.theta_tip)] {
        v.insert(format!("rms_{name}_full"), json!(rms(x)));
        v.insert(format!("max_{name}_full"), json!(max_abs(x)));
        v.insert(format!("rms_{name}_late"), json!(rms(&x[late..])));
        v.insert(format!("max_{name}_late"), json!(max_abs(&x[late..])));
    }
    let thr = |x: &[f64]| SETTLE_FRACTION * x.first().map_or(0.0, |v| v.abs());
    v.insert("settle_q_s".into(), settle_value(settle_time(&s.t, &s.q_tip, thr(&s.q_tip))));
    v.insert("settle_theta_s".into(), settle_value(settle_time(&s.t, &s.theta_tip, thr(&s.theta_tip))));
    for (name, x) in [("tau1", &s.tau1), ("tau2", &s.tau2)] {
        v.insert(format!("rms_{name}"), json!(rms(x)));
        v.insert(format!("peak_{name}"), json!(max_abs(x)));
    }
    for (name, x) in [("gtilde1", &gt1), ("gtilde2", &gt2)] {
        v.insert(format!("rms_{name}_full"), json!(rms(x)));
        v.insert(format!("rms_{name}_late"), json!(rms(&x[late..])));
        v.insert(format!("{name}_settle_s"), settle_value(settle_time(&s.t, x, GTILDE_THRESHOLD)));
    }
    Metrics { values: v }
}

/// Simulate `cfg` with the given controller, rule and (a, b).
pub fn run(cfg: &Config, kind: ControllerKind, rule: ObserverRule, a: f64, b: f64) -> Result<Series, ClaimsError> {
    run_in(&Study::new(), cfg, kind, rule, a, b)
}

/// [`run`] through a study (each distinct configuration simulated once).
pub fn run_in(
    study: &Study,
    cfg: &Config,
    kind: ControllerKind,
    rule: ObserverRule,
    a: f64,
    b: f64,
) -> Result<Series, ClaimsError> {
    let mut c = cfg.clone();
    c.control.kind = kind;
    c.observer.rule = rule;
    c.control.a = a;
    c.control.b = b;
    Ok(study.simulate(&c)?.series.clone())
}

fn rel(ftdo: &Metrics, dobc: &Metrics, key: &str) -> f64 {
    rel_excess(ftdo.get(key), dobc.get(key))
}

/// Compare FTDO and DOBC (Section 4, Figs 3–20).
pub fn check(cfg: &Config, study: &Study) -> Result<ClaimRow, ClaimsError> {
    let clock = Instant::now();
    let (a0, b0) = (cfg.control.a, cfg.control.b);
    let fi = run_in(study, cfg, ControllerKind::Ftdo, ObserverRule::Implicit, a0, b0)?;
    let fe = run_in(study, cfg, ControllerKind::Ftdo, ObserverRule::Explicit, a0, b0)?;
    let db = run_in(study, cfg, ControllerKind::Dobc, ObserverRule::Implicit, a0, b0)?;
    let (mi, me, md) = (metrics(&fi), metrics(&fe), metrics(&db));
    let mut ev: BTreeMap<String, Value> = BTreeMap::new();
    for (label, m) in [("ftdo-implicit", &mi), ("ftdo-explicit", &me), ("dobc", &md)] {
        for (k, v) in &m.values {
            ev.insert(format!("{label}.{k}"), v.clone());
        }
    }
    let keys = ["rms_q_full", "rms_theta_full", "rms_q_late", "rms_theta_late"];
    for k in keys {
        ev.insert(format!("rel_diff_{k}"), json!(rel(&mi, &md, k)));
    }
    let gl = |m: &Metrics| m.get("rms_gtilde1_late").hypot(m.get("rms_gtilde2_late"));
    let gratio = ratio(gl(&md), gl(&mi));
    ev.insert("gtilde_ratio_late".into(), json!(gratio));
    // Relative differences (DOBC − FTDO)/FTDO of the four tip RMS metrics, for every compared pair.
    let mut diffs: Vec<[f64; 4]> = vec![keys.map(|k| rel(&mi, &md, k)), keys.map(|k| rel(&me, &md, k))];
    let mut sweep = Vec::new();
    for (a, b) in AB_SWEEP {
        let f = metrics(&run_in(study, cfg, ControllerKind::Ftdo, ObserverRule::Implicit, a, b)?);
        let d = metrics(&run_in(study, cfg, ControllerKind::Dobc, ObserverRule::Implicit, a, b)?);
        let r = keys.map(|k| rel(&f, &d, k));
        diffs.push(r);
        sweep.push(json!({"a": a, "b": b, "rel_diff_rms_q_full": r[0], "rel_diff_rms_theta_full": r[1],
            "rel_diff_rms_q_late": r[2], "rel_diff_rms_theta_late": r[3], "gtilde_ratio_late": ratio(gl(&d), gl(&f))}));
    }
    ev.insert("ab_sweep".into(), Value::Array(sweep));
    let worst = diffs.iter().flatten().fold(0.0_f64, |m, x| m.max(x.abs()));
    ev.insert("max_abs_rel_diff_tip".into(), json!(worst));
    let range = |j: usize| {
        let v = diffs.iter().map(|d| d[j]);
        (v.clone().fold(f64::INFINITY, f64::min), v.fold(f64::NEG_INFINITY, f64::max))
    };
    let (fq, ft, lq, lt) = (range(0), range(1), range(2), range(3));
    ev.insert("late_min_rel_diff".into(), json!(lq.0.min(lt.0)));
    // Holds only if DOBC is worse by a clear margin in every tip metric of every pair and
    // FTDO's disturbance error is clearly smaller; partly reproduced if exactly one of the two is.
    let tip_clear = diffs.iter().flatten().all(|&x| x > INDISTINGUISHABLE);
    let gtilde_clear = gratio > 1.0 + INDISTINGUISHABLE;
    let full_better = fq.0 > INDISTINGUISHABLE && ft.0 > INDISTINGUISHABLE;
    let late_better = lq.0 > INDISTINGUISHABLE && lt.0 > INDISTINGUISHABLE;
    ev.insert("tip_response_clearly_better".into(), json!(tip_clear));
    ev.insert("gtilde_clearly_smaller".into(), json!(gtilde_clear));
    let verdict = match (tip_clear, gtilde_clear) {
        (true, true) => Verdict::Holds,
        (false, false) => Verdict::Fails,
        _ => Verdict::PartlyReproduced,
    };
    let pct = |r: (f64, f64)| format!("{:+.1}%..{:+.1}%", 100.0 * r.0, 100.0 * r.1);
    let d = &cfg.disturbance;
    let (z1, z2) =
        (d.tip_bending.mean.abs() + d.tip_bending.amp.abs(), d.tip_torsion.mean.abs() + d.tip_torsion.amp.abs());
    let g_text = format!(
        "FTDO's disturbance error: |g̃| ≤ {thr:e} from {s1} / {s2} on (implicit rule); late RMS g̃ ratio DOBC/FTDO = {gratio:.3e}",
        thr = GTILDE_THRESHOLD,
        s1 = mi.settle_text("gtilde1_settle_s"),
        s2 = mi.settle_text("gtilde2_settle_s"),
    );
    let tip_text = format!(
        "relative excess (DOBC − FTDO)/FTDO of the tip RMS over (a, b) ∈ {{({a0}, {b0}), (0.5, 1), (1, 0.5), (2, 2)}} and both FTDO rules: \
         q over [0,T] {}, θ over [0,T] {}, q over [T/2,T] {}, θ over [T/2,T] {}",
        pct(fq),
        pct(ft),
        pct(lq),
        pct(lt)
    );
    let mut reproduced = Vec::new();
    let mut not_reproduced = Vec::new();
    if gtilde_clear {
        reproduced.push(g_text)
    } else {
        not_reproduced.push(g_text)
    }
    if tip_clear {
        reproduced.push(format!("a clearly better tip response ({tip_text})"));
    } else {
        let part = match (full_better, late_better) {
            (true, false) => " (FTDO is clearly better over [0, T] but not over [T/2, T])",
            (false, true) => " (FTDO is clearly better over [T/2, T] but not over [0, T])",
            _ => "",
        };
        not_reproduced.push(format!("a clearly better tip response{part}: {tip_text}"));
    }
    let list = |v: &[String]| if v.is_empty() { "nothing".to_string() } else { v.join("; ") };
    let summary = format!(
        "Reproduced: {}. Not reproduced: {}. At the configured (a, b): RMS q(s,t) {:.4} vs {:.4} m, RMS θ(s,t) {:.4} vs {:.4} rad; \
         settle to {SETTLE_FRACTION} × the initial tip values at {} / {} (FTDO) vs {} / {} (DOBC). The tip disturbances are bounded by \
         {z1:.3} N and {z2:.3} N m. Costs: FTDO's τ2 peak {:.3} N m vs DOBC {:.3}; explicit FTDO RMS τ1 {:.3} N vs DOBC {:.3}.",
        list(&reproduced),
        list(&not_reproduced),
        mi.get("rms_q_full"),
        md.get("rms_q_full"),
        mi.get("rms_theta_full"),
        md.get("rms_theta_full"),
        mi.settle_text("settle_q_s"),
        mi.settle_text("settle_theta_s"),
        md.settle_text("settle_q_s"),
        md.settle_text("settle_theta_s"),
        mi.get("peak_tau2"),
        md.get("peak_tau2"),
        me.get("rms_tau1"),
        md.get("rms_tau1"),
    );
    let plots = plots(&fi, &db, &mi, &md);
    Ok(ClaimRow {
        id: crate::ClaimId::FtdoVsDobc,
        equation: "Section 4, Figs 3–20, (57)".into(),
        claim: "the proposed controller suppresses vibration better than DOBC".into(),
        verdict,
        basis: Basis::Simulation,
        summary,
        correction: None,
        evidence: ev,
        highlights: Vec::new(),
        assumptions: vec![
            "DOBC (57) corrected: b q̇(s) in τ1, ĝ from d ĝ/dt = g − ĝ with p(0) = 0; same k1, k2, a, b as FTDO".into(),
            format!("(a, b) not given by the paper: configured ({a0}, {b0}) plus the sweep (0.5, 1), (1, 0.5), (2, 2)"),
            format!(
                "metrics from the {} s output series; settle thresholds {SETTLE_FRACTION} × the initial |q(s,0)|, |θ(s,0)|; |g̃| ≤ {GTILDE_THRESHOLD:e}",
                cfg.horizon.sample_every
            ),
            format!("'indistinguishable' = relative difference of tip RMS below {INDISTINGUISHABLE}"),
        ],
        certificates: vec![],
        plots,
        seconds: clock.elapsed().as_secs_f64(),
    })
}

fn plots(f: &Series, d: &Series, mf: &Metrics, md: &Metrics) -> Vec<PlotData> {
    let line = |label: &str, x: &[f64], y: Vec<f64>| Line { label: label.into(), x: x.to_vec(), y, points: false };
    let gt = |g: &[f64], h: &[f64]| g.iter().zip(h).map(|(a, b)| a - b).collect::<Vec<f64>>();
    let mk = |name: &str, what: &str, unit: &str, yf: Vec<f64>, yd: Vec<f64>, title: String| PlotData {
        name: format!("ftdo-vs-dobc-{name}"),
        title,
        x_label: "t (s)".into(),
        y_label: format!("{what} ({unit})"),
        log_x: false,
        log_y: false,
        lines: vec![line("FTDO (implicit)", &f.t, yf), line("DOBC", &d.t, yd)],
    };
    let two = |key: &str| (mf.get(key), md.get(key));
    let (a, b) = two("rms_q_full");
    let (c, e) = two("rms_theta_full");
    let (g1f, g1d) = two("rms_gtilde1_late");
    let (g2f, g2d) = two("rms_gtilde2_late");
    let (p1f, p1d) = two("peak_tau1");
    let (p2f, p2d) = two("peak_tau2");
    vec![
        mk(
            "q-tip",
            "q(s,t)",
            "m",
            f.q_tip.clone(),
            d.q_tip.clone(),
            format!("Tip bending: RMS FTDO {a:.5} m, DOBC {b:.5} m"),
        ),
        mk(
            "theta-tip",
            "θ(s,t)",
            "rad",
            f.theta_tip.clone(),
            d.theta_tip.clone(),
            format!("Tip twist: RMS FTDO {c:.5} rad, DOBC {e:.5} rad"),
        ),
        mk(
            "gtilde1",
            "g̃1",
            "N",
            gt(&f.g1, &f.g1_hat),
            gt(&d.g1, &d.g1_hat),
            format!("g̃1 = g1 − ĝ1: late RMS FTDO {g1f:.2e}, DOBC {g1d:.2e} N"),
        ),
        mk(
            "gtilde2",
            "g̃2",
            "N m",
            gt(&f.g2, &f.g2_hat),
            gt(&d.g2, &d.g2_hat),
            format!("g̃2 = g2 − ĝ2: late RMS FTDO {g2f:.2e}, DOBC {g2d:.2e} N m"),
        ),
        mk("tau1", "τ1", "N", f.tau1.clone(), d.tau1.clone(), format!("τ1: peak FTDO {p1f:.3} N, DOBC {p1d:.3} N")),
        mk("tau2", "τ2", "N m", f.tau2.clone(), d.tau2.clone(), format!("τ2: peak FTDO {p2f:.3}, DOBC {p2d:.3} N m")),
    ]
}
