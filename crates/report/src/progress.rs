//! Progress of [`crate::write_report`]: per stage ([`Progress`]) and as one monotone fraction
//! ([`Overall`]) for a progress bar owned by the caller.

use crate::ReportOptions;

/// Progress of a stage, for a progress bar owned by the caller.
#[derive(Debug, Clone, Copy)]
pub struct Progress<'a> {
    /// Stage name (`ledger`, `simulations`, `region map`, `charts`, …).
    pub stage: &'a str,
    /// Units done in this stage.
    pub done: usize,
    /// Units in this stage.
    pub total: usize,
}

/// Overall progress of [`crate::write_report`] for a progress bar: a fraction in [0, 1] that never
/// decreases across stages (the stages' own counts restart; this does not).
#[derive(Debug, Clone, Copy)]
pub struct Overall<'a> {
    /// The stage that moved.
    pub stage: &'a str,
    /// Fraction of the whole report done.
    pub fraction: f64,
}

/// Stage weights of the overall fraction. The ledger runs concurrently with the simulations,
/// the region map, the certificates (which report no progress) and, after those, the run charts
/// (the figures that need no ledger); the charts that need the ledger follow it.
const WEIGHTS: [(&str, f64); 7] = [
    ("ledger", 0.35),
    ("simulations", 0.15),
    ("region map", 0.35),
    ("run charts", 0.08),
    ("charts", 0.02),
    ("html", 0.04),
    ("write", 0.01),
];

/// Turns per-stage counts into one monotone fraction.
pub(crate) struct Tracker<'a> {
    stages: std::sync::Mutex<(Vec<f64>, f64)>,
    progress: Option<&'a (dyn Fn(Progress) + Sync)>,
    overall: Option<&'a (dyn Fn(Overall) + Sync)>,
}

impl<'a> Tracker<'a> {
    pub(crate) fn new(o: &ReportOptions<'a>) -> Self {
        Tracker {
            stages: std::sync::Mutex::new((vec![0.0; WEIGHTS.len()], 0.0)),
            progress: o.progress,
            overall: o.overall,
        }
    }

    pub(crate) fn update(&self, p: Progress) {
        if let Some(cb) = self.progress {
            cb(p);
        }
        let Some(cb) = self.overall else { return };
        // The callback is called under the lock: called after it, two threads could deliver
        // their fractions in the other order, and the caller would see the fraction go back.
        let mut g = self.stages.lock().expect("progress lock");
        if let Some(i) = WEIGHTS.iter().position(|(n, _)| *n == p.stage) {
            let f = if p.total == 0 { 1.0 } else { (p.done as f64 / p.total as f64).clamp(0.0, 1.0) };
            g.0[i] = g.0[i].max(f);
        }
        let sum: f64 = g.0.iter().zip(WEIGHTS).map(|(f, (_, w))| f * w).sum();
        g.1 = g.1.max(sum.min(1.0));
        cb(Overall { stage: p.stage, fraction: g.1 });
    }
}

/// Report `done` of `total` units of `stage` to `progress`, if any.
pub(crate) fn report(progress: Option<&(dyn Fn(Progress) + Sync)>, stage: &str, done: usize, total: usize) {
    if let Some(p) = progress {
        p(Progress { stage, done, total });
    }
}
