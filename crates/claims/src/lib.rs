//! The claim checker: for each claim of the paper ([`spec::CLAIMS`]) a verdict with evidence,
//! the basis it rests on, and the assumptions made where the paper is silent.
//!
//! Rows: `W-bounds` and `mu-conditions` ([`wbounds`], [`mu`]) rest on convex optimisation,
//! closed forms and exact certificates; `UUB` ([`uub`]) combines them with simulation;
//! `finite-time-1/2` ([`finite_time`]), `lemmas` ([`lemmas`]) and `ftdo-vs-dobc`
//! ([`comparison`]) on simulation and adversarial search. Each row's evidence is a typed struct
//! of labelled quantities ([`display`]) with its own [`explain::Explain`]: the verdict and the
//! words come from the evidence alone.

#![forbid(unsafe_code)]

pub mod certify;
pub mod comparison;
pub mod display;
pub mod evidence;
pub mod explain;
pub mod finite_time;
mod ledger;
pub mod lemmas;
pub mod mu;
pub mod numerics;
pub mod ode;
pub mod plan;
pub mod settings;
pub mod spec;
pub mod study;
pub mod uub;
pub mod wbounds;

use std::sync::Arc;
use std::time::Instant;

pub use display::{NEVER_SETTLED, NOT_REACHED};
pub use evidence::Evidence;
pub use explain::Explain;
pub use ledger::{Basis, ClaimId, ClaimRow, Ledger, Line, PlotData, Verdict, WallTime};
pub use settings::CheckSettings;
pub use study::Study;

use wingcheck_model::Config;

/// Errors of the claim checker (a failed claim is a verdict, not an error).
#[derive(Debug, Clone, thiserror::Error)]
pub enum ClaimsError {
    /// A simulation needed as evidence failed (shared: the study runs each simulation once).
    #[error(transparent)]
    Sim(Arc<wingcheck_sim::SimError>),
    /// A computation panicked (a bug of wingcheck): caught, so that it becomes its row's
    /// `inconclusive` with the reason instead of ending the process.
    #[error(transparent)]
    Panicked(#[from] wingcheck_io::Panicked),
    /// The check was stopped through its study's cancel token ([`check_all_cancellable`]).
    #[error(transparent)]
    Cancelled(#[from] wingcheck_model::Cancelled),
    /// A numerical step failed.
    #[error("numerical failure in {what}: {cause}")]
    Numerical {
        /// Which computation.
        what: &'static str,
        /// What failed.
        #[source]
        cause: crate::numerics::NumericsError,
    },
}

impl From<wingcheck_sim::SimError> for ClaimsError {
    fn from(e: wingcheck_sim::SimError) -> Self {
        ClaimsError::Sim(Arc::new(e))
    }
}

/// SHA-256 (hex) of the configuration's JSON (struct field order, so stable).
pub fn config_sha256(cfg: &Config) -> String {
    cfg.sha256()
}

/// Run every check on `cfg` and assemble the ledger, in the paper's order, with a fresh
/// [`Study`] (each distinct simulation runs once) and the default [`CheckSettings`].
pub fn check_all(cfg: &Config) -> Result<Ledger, ClaimsError> {
    check_all_with(cfg, &Study::new(), &CheckSettings::default())
}

/// `f()`, with a panic inside it (also in its parallel parts) caught as
/// [`ClaimsError::Panicked`]: every row's computation runs under it, so a panic in one row
/// becomes that row's `inconclusive` with the reason and never ends the process.
pub fn guarded<T>(f: impl FnOnce() -> Result<T, ClaimsError>) -> Result<T, ClaimsError> {
    wingcheck_io::catch(f).unwrap_or_else(|p| Err(ClaimsError::Panicked(p)))
}

/// [`check_all_with`] stopped once `study`'s cancel token is set ([`Study::with_cancel`]):
/// the rows in flight end early as `inconclusive`, and the ledger is then discarded for
/// [`ClaimsError::Cancelled`], so a cancelled check never returns rows decided on cut-short
/// evidence.
pub fn check_all_cancellable(cfg: &Config, study: &Study, settings: &CheckSettings) -> Result<Ledger, ClaimsError> {
    study.cancel().check()?;
    let ledger = check_all_with(cfg, study, settings)?;
    study.cancel().check()?;
    Ok(ledger)
}

/// A row's outcome with its wall time; a failed (or panicking) computation becomes
/// `inconclusive` with the reason.
fn timed(id: ClaimId, f: impl FnOnce() -> Result<ClaimRow, ClaimsError>) -> (ClaimRow, WallTime) {
    let (row, seconds) = seconds(|| guarded(f));
    let row = row.unwrap_or_else(|e| ClaimRow::inconclusive(id, Basis::Computation, format!("Not decided: {e}.")));
    (row, WallTime { what: id.name().into(), seconds })
}

/// The name of the finite-time rows' shared digital runs among [`Ledger::wall_seconds`].
pub const DIGITAL_RUNS: &str = "finite-time digital runs";

/// The name of the W-bounds row's SDP cross-check (all N) among [`Ledger::wall_seconds`].
pub const SDP_CROSS_CHECK: &str = "W-bounds SDP cross-check";

/// The rows that rest on simulation (their computations side by side on the pool), and the
/// wall time of the finite-time rows' digital runs (computed once for both rows).
fn simulation_rows(cfg: &Config, study: &Study, settings: &CheckSettings) -> (Vec<(ClaimRow, WallTime)>, WallTime) {
    let finite_rows = || {
        let (digital, seconds) = seconds(|| guarded(|| finite_time::digital_runs(cfg, settings)));
        let shared = WallTime { what: DIGITAL_RUNS.into(), seconds };
        let finite = |id: ClaimId, channel: finite_time::Channel| {
            timed(id, || finite_time::check_with(cfg, channel, settings, digital.as_ref().map_err(Clone::clone)?))
        };
        (
            [
                finite(ClaimId::FiniteTime1, finite_time::Channel::Bending),
                finite(ClaimId::FiniteTime2, finite_time::Channel::Torsion),
            ],
            shared,
        )
    };
    // independent computations side by side, so that either thread of the pool can take them
    let (([ft1, ft2], shared), comparison) =
        rayon::join(finite_rows, || timed(ClaimId::FtdoVsDobc, || comparison::check(cfg, study, settings)));
    (vec![ft1, ft2, comparison], shared)
}

/// `f()` and its wall time (s): the one timing helper of the rows, the report's stages and
/// their parts.
pub fn seconds<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let start = Instant::now();
    (f(), start.elapsed().as_secs_f64())
}

/// The rows that rest on theory (W-bounds, mu-conditions, UUB, lemmas), and their wall times.
fn theory_rows(cfg: &Config, study: &Study, settings: &CheckSettings) -> (Vec<(ClaimRow, WallTime)>, Vec<WallTime>) {
    // W-bounds, mu-conditions and lemmas are independent: side by side on the pool; UUB needs
    // the first two.
    let ((w, w_seconds), ((m, m_seconds), lemmas)) = rayon::join(
        || seconds(|| guarded(|| wbounds::check_cancellable(cfg, settings, study.cancel()))),
        || {
            rayon::join(
                || seconds(|| guarded(|| mu::check(cfg, study, settings))),
                || timed(ClaimId::Lemmas, || lemmas::check(cfg, settings)),
            )
        },
    );
    let w_time = WallTime { what: ClaimId::WBounds.name().into(), seconds: w_seconds };
    let m_time = WallTime { what: ClaimId::MuConditions.name().into(), seconds: m_seconds };
    let uub = match (&w, &m) {
        (Ok(w), Ok(m)) => timed(ClaimId::Uub, || uub::check(cfg, w, m, study, settings)),
        _ => (
            ClaimRow::inconclusive(
                ClaimId::Uub,
                Basis::Computation,
                "Not decided: it needs the W-bounds and mu-conditions rows, which could not be computed.",
            ),
            WallTime { what: ClaimId::Uub.name().into(), seconds: 0.0 },
        ),
    };
    let extra = w.as_ref().map(|w| w.wall.clone()).unwrap_or_default();
    let fail =
        |id: ClaimId, e: &ClaimsError| ClaimRow::inconclusive(id, Basis::Computation, format!("Not decided: {e}."));
    let rows = vec![
        (w.as_ref().map_or_else(|e| fail(ClaimId::WBounds, e), |w| w.row.clone()), w_time),
        (m.as_ref().map_or_else(|e| fail(ClaimId::MuConditions, e), |m| m.row.clone()), m_time),
        uub,
        lemmas,
    ];
    (rows, extra)
}

/// Why `certify` writes no certificates for a configuration.
#[derive(Debug, thiserror::Error)]
enum NoCertificates {
    /// It panicked (a bug of wingcheck).
    #[error(transparent)]
    Panicked(#[from] wingcheck_io::Panicked),
    /// It refused or failed.
    #[error(transparent)]
    Certify(#[from] certify::CertifyError),
}

/// The certificate files `certify` writes for `cfg`, per claim (empty with the reason when the
/// configuration cannot be certified).
fn certificate_files(cfg: &Config) -> Result<Vec<(ClaimId, String)>, NoCertificates> {
    let files = wingcheck_io::catch(|| certify::certificates(cfg))??;
    Ok(files
        .iter()
        .filter_map(|f| {
            let id = spec::role(&f.id)?.claim;
            Some((id, format!("{}.json", f.id)))
        })
        .collect())
}

/// [`check_all`] with a caller's study (e.g. shared with the report's own runs) and settings.
/// A row whose computation fails becomes `inconclusive` with the reason; the other rows are
/// still computed, so this only returns `Ok`.
pub fn check_all_with(cfg: &Config, study: &Study, settings: &CheckSettings) -> Result<Ledger, ClaimsError> {
    // Two independent groups of rows side by side (each row is deterministic, so the ledger
    // does not depend on the schedule; the study's cache is thread-safe).
    let (sims, (theory, extra, certificates)) = beside(
        || simulation_rows(cfg, study, settings),
        || {
            let ((theory, extra), certificates) =
                rayon::join(|| theory_rows(cfg, study, settings), || certificate_files(cfg));
            (theory, extra, certificates)
        },
    );
    let (sims, shared) = sims.unwrap_or_else(|p| {
        let rows = [ClaimId::FiniteTime1, ClaimId::FiniteTime2, ClaimId::FtdoVsDobc]
            .map(|id| {
                let row = ClaimRow::inconclusive(id, Basis::Computation, format!("Not decided: {p}."));
                (row, WallTime { what: id.name().into(), seconds: 0.0 })
            })
            .into();
        (rows, WallTime { what: DIGITAL_RUNS.into(), seconds: 0.0 })
    });
    let mut by_id: Vec<(ClaimRow, WallTime)> = theory.into_iter().chain(sims).collect();
    by_id.sort_by_key(|(r, _)| r.id);
    let mut rows = Vec::new();
    let mut wall_seconds = Vec::new();
    for (mut row, time) in by_id {
        match &certificates {
            Ok(files) => {
                row.certificates = files.iter().filter(|(id, _)| *id == row.id).map(|(_, f)| f.clone()).collect()
            }
            Err(why) if !row.id.certificates().is_empty() => {
                row.assumptions.push(format!("no certificate: certify cannot write one for this configuration ({why})"))
            }
            Err(_) => {}
        }
        rows.push(row);
        wall_seconds.push(time);
    }
    wall_seconds.push(shared);
    wall_seconds.extend(extra);
    let mut ledger = Ledger {
        schema_version: wingcheck_io::SCHEMA_VERSION,
        tool: format!("wingcheck {}", env!("CARGO_PKG_VERSION")),
        config_sha256: config_sha256(cfg),
        provenance: wingcheck_io::Provenance::new(&config_sha256(cfg), Vec::new()),
        settings: settings.clone(),
        rows,
        wall_seconds,
    };
    reject_unlabelled_or_non_finite(&mut ledger);
    Ok(ledger)
}

/// [`beside`] with the roles turned: `first` starts at once on this thread (its panic returned
/// as an `Err`), `then` waits on the pool for a free thread. For the longest sequential chain.
pub(crate) fn first_beside<F: Send, T: Send>(
    first: impl FnOnce() -> F + Send,
    then: impl FnOnce() -> T + Send,
) -> (Result<F, wingcheck_io::Panicked>, T) {
    rayon::join(|| wingcheck_io::catch(first), then)
}

/// Runs `side` beside `main` on the rayon pool and returns both results, `side`'s panic as an
/// `Err` with its message (recorded by the caller, never fatal; [`wingcheck_io::catch`]). Not on threads of their own: the computations
/// use the pool themselves (the enclosure's inertia counts), and a pool worker blocked joining
/// an OS thread that waits for a free worker never wakes — `report` hung with one worker
/// (`RAYON_NUM_THREADS=1` or a one-core machine) and two reports in one process hung with two.
/// A worker waiting in `rayon::join` takes other work instead.
pub(crate) fn beside<S: Send, M: Send>(
    side: impl FnOnce() -> S + Send,
    main: impl FnOnce() -> M + Send,
) -> (Result<S, wingcheck_io::Panicked>, M) {
    let (m, s) = rayon::join(main, || wingcheck_io::catch(side));
    (s, m)
}

/// Places named in the reason of a row whose values are not finite (the rest are counted).
const NON_FINITE_SHOWN: usize = 4;

/// A non-finite value, or evidence that is not made of labelled leaves: never print it, say so
/// instead (the row becomes `inconclusive`, naming where).
fn reject_unlabelled_or_non_finite(ledger: &mut Ledger) {
    use rayon::prelude::*;
    // the rows are independent: checked side by side (each serialises its evidence and plots)
    ledger.rows.par_iter_mut().for_each(|r| {
        let bad = ledger::non_finite_paths(r);
        let text = if !bad.is_empty() {
            let shown: Vec<&str> = bad.iter().take(NON_FINITE_SHOWN).map(String::as_str).collect();
            let more = bad.len().saturating_sub(NON_FINITE_SHOWN);
            Some(format!(
                "Not decided: the computation gave values that are not finite in double precision at {}{} \
                 (configured values this far apart overflow or underflow this row's arithmetic)",
                shown.join(", "),
                if more > 0 { format!(" and {more} more places") } else { String::new() }
            ))
        } else {
            r.evidence.nodes().err().map(|e| format!("Internal error: evidence without a label at {e}"))
        };
        if let Some(t) = text {
            *r = ClaimRow::inconclusive(r.id, Basis::Computation, format!("{t}."));
        }
    });
}
