//! `bench --what check`: the whole claim checker with its per-row breakdown, certify and the
//! exact re-verification, and the ω₁ enclosure's costs.

use serde::Serialize;
use wingcheck_claims::certify::{self, omega1, CertifyError};
use wingcheck_io::clock::{measure, Elapsed};
use wingcheck_model::Config;
use wingcheck_sim::bench::{median, median_elapsed};

use crate::AppError;

/// One ledger row's wall time (median over the repeats; rows run concurrently).
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct RowTiming {
    /// The row's id.
    pub id: String,
    /// Its wall time (s).
    pub wall_seconds: f64,
}

/// The ω₁ enclosure's costs (CPU where known, s).
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct EnclosureTiming {
    /// Made and checked, uncached.
    pub compute_seconds: f64,
    /// The exact check of the configured certificate alone.
    pub check_seconds: f64,
    /// The exact check of the slowest certificate the verifier accepts (every mesh at its
    /// limit, every number a 32-character fraction).
    pub worst_case_check_seconds: f64,
}

/// The claim checker's timings.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct CheckBench {
    /// The whole `check`, median of the repeats.
    pub check: Elapsed,
    /// Runs timed.
    pub runs: usize,
    /// Per ledger row.
    pub rows: Vec<RowTiming>,
    /// The SDP cross-check at N = 2…32 (wall, s).
    pub sdp_wall_seconds: f64,
    /// The finite-time rows' digital runs, once for both rows (wall, s).
    pub finite_time_digital_runs_wall_seconds: f64,
    /// Distinct closed-loop simulations of one check (each run once).
    pub distinct_simulations: usize,
    /// `certify` of the whole set.
    pub certify: Elapsed,
    /// The exact re-verification of that set.
    pub verify: Elapsed,
    /// Certificates written.
    pub certificates: usize,
    /// The ω₁ enclosure.
    pub omega1_enclosure: EnclosureTiming,
}

/// Run the check bench (guarded by the caller).
pub(crate) fn bench_check(cfg: &Config, repeats: usize) -> Result<CheckBench, AppError> {
    let (mut totals, mut rows, mut sdp, mut digital) = (Vec::new(), Vec::<(String, Vec<f64>)>::new(), vec![], vec![]);
    let mut sims = 0;
    for _ in 0..repeats.max(1) {
        let study = wingcheck_claims::Study::new();
        let settings = wingcheck_claims::CheckSettings::default();
        let (ledger, elapsed) = measure(|| wingcheck_claims::check_all_with(cfg, &study, &settings));
        let ledger = ledger?;
        totals.push(elapsed);
        sims = study.simulations_run();
        for (i, r) in ledger.rows.iter().enumerate() {
            if rows.len() <= i {
                rows.push((r.id.to_string(), Vec::new()));
            }
            rows[i].1.push(ledger.wall_seconds_of(r.id.name()).unwrap_or(0.0));
        }
        sdp.push(ledger.wall_seconds_of(wingcheck_claims::SDP_CROSS_CHECK).unwrap_or(0.0));
        digital.push(ledger.wall_seconds_of(wingcheck_claims::DIGITAL_RUNS).unwrap_or(0.0));
    }
    let tmp = tempfile::tempdir().map_err(|e| AppError::OutputPath {
        path: std::env::temp_dir(),
        message: format!("temporary directory: {e}"),
    })?;
    let (files, certify) = measure(|| certify::write_all(cfg, tmp.path()));
    let certify_error = |source| AppError::Certify { out: tmp.path().to_path_buf(), source };
    let files = files.map_err(certify_error)?;
    let (set, verify) = measure(|| certify::verify_set(tmp.path()));
    set.map_err(|source| AppError::Rejected { path: tmp.path().to_path_buf(), source })?;
    Ok(CheckBench {
        check: median_elapsed(&totals),
        runs: totals.len(),
        rows: rows.into_iter().map(|(id, v)| RowTiming { id, wall_seconds: median(v) }).collect(),
        sdp_wall_seconds: median(sdp),
        finite_time_digital_runs_wall_seconds: median(digital),
        distinct_simulations: sims,
        certify,
        verify,
        certificates: files.len(),
        omega1_enclosure: bench_enclosure(cfg).map_err(certify_error)?,
    })
}

/// The ω₁ enclosure's costs: [`omega1::compute_with`] uncached (a plan the ledger does not use,
/// so nothing is cached), the exact check of the configured certificate, and the exact check
/// of the slowest certificate the verifier accepts (k, both meshes at their limits, every
/// shift and vector entry a 32-character fraction).
fn bench_enclosure(cfg: &Config) -> Result<EnclosureTiming, CertifyError> {
    use omega1::{Plan, LIMITS};
    let plan = Plan { rayleigh_elements: omega1::PLAN.rayleigh_elements + 1, ..omega1::PLAN };
    let (computed, compute) = measure(|| omega1::compute_with(cfg, &plan));
    computed?;
    let cert = omega1::compute(cfg)?.0.clone();
    let (checked, check) = measure(|| cert.check_exact());
    checked?;
    let limits = Plan {
        modes: LIMITS.max_modes,
        inertia_elements: LIMITS.max_inertia_elements,
        rayleigh_elements: LIMITS.max_rayleigh_elements,
    };
    let mut worst = omega1::compute_with(cfg, &limits)?.0.clone();
    for s in worst.shifts.iter_mut() {
        *s = fraction_of_32_chars(parsed(s)? * 1.0001, true);
    }
    for s in worst.vector.iter_mut().skip(3) {
        let v = parsed(s)?;
        if v != 0.0 {
            *s = fraction_of_32_chars(v, false);
        }
    }
    let (checked, worst_case) = measure(|| worst.check_exact());
    checked?;
    Ok(EnclosureTiming {
        compute_seconds: compute.seconds(),
        check_seconds: check.seconds(),
        worst_case_check_seconds: worst_case.seconds(),
    })
}

/// A certificate's decimal entry as written by `certify`.
fn parsed(s: &str) -> Result<f64, CertifyError> {
    s.parse::<f64>()
        .map_err(|e| CertifyError::Invalid { field: "ω₁ certificate entry".into(), message: format!("{s:?}: {e}") })
}

/// `p/q` of exactly 32 characters just above `v` (`up`: one more in p, so a shift stays valid).
fn fraction_of_32_chars(v: f64, up: bool) -> String {
    let mut q: u128 = 98_765_432_109_876_543;
    loop {
        let p = (v.abs() * q as f64).ceil() as u128 + u128::from(up);
        let t = format!("{}{p}/{q}", if v < 0.0 { "-" } else { "" });
        if t.len() <= 32 {
            return t;
        }
        q = q / 10 + 7;
    }
}
