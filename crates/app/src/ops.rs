//! The long operations of the front ends, each guarded by the work policy and stoppable through
//! a [`Cancel`] token: check, report, search, certify, verify.

use std::path::Path;

use wingcheck_claims::certify::{self, VerifiedSet, WrittenSet};
use wingcheck_claims::{check_all_cancellable, CheckSettings, Ledger, Study};
use wingcheck_model::{Cancel, Config};
use wingcheck_report::{ReportOptions, ReportSummary};
use wingcheck_search::{RunControl, RunSummary, Search, SearchOptions};

use crate::{AppError, WorkPolicy};

/// The claim ledger of `cfg` (default settings), refused above the work limits; stops with
/// [`AppError::Cancelled`] once `cancel` is set (never a ledger decided on cut-short runs).
pub fn check(cfg: &Config, policy: WorkPolicy, cancel: &Cancel) -> Result<Ledger, AppError> {
    let settings = CheckSettings::default();
    policy.guard(&wingcheck_claims::plan::check_estimate(cfg, &settings))?;
    let study = Study::with_cancel(cancel.clone());
    Ok(check_all_cancellable(cfg, &study, &settings)?)
}

/// The HTML report of `cfg` into `out` (replaced atomically), refused above the work limits;
/// `opts.cancel` stops it before anything is moved into place.
pub fn report(cfg: &Config, out: &Path, policy: WorkPolicy, opts: &ReportOptions) -> Result<ReportSummary, AppError> {
    policy.guard(&wingcheck_report::report_estimate(cfg))?;
    Ok(wingcheck_report::write_report(cfg, out, opts)?)
}

/// A search over `over` (axes `key=lo..hi:log:N`, `key=lo..hi:lin:N`, `key=v1,v2,…`) of
/// `base` into `out` (resumed if it holds this search). The search's own limits apply
/// (`policy.allow_large` lifts them; the refusal names `policy.front`'s override).
pub fn search(
    base: Config,
    over: &[String],
    options: SearchOptions,
    out: &Path,
    policy: WorkPolicy,
    ctl: RunControl<'_>,
) -> Result<RunSummary, AppError> {
    let search = Search::new(base, over, options)?;
    let ctl = RunControl { allow_large: policy.allow_large, allow_large_flag: Some(policy.front.allow_large()), ..ctl };
    Ok(wingcheck_search::run(&search, out, ctl)?)
}

/// `certify`: the exact certificate set of `cfg` into `out` (replaced atomically).
pub fn certify(cfg: &Config, out: &Path, cancel: &Cancel) -> Result<WrittenSet, AppError> {
    cancel.check()?;
    let written = certify::write_set_cancellable(cfg, out, cancel)
        .map_err(|source| AppError::Certify { out: out.to_path_buf(), source })?;
    Ok(written)
}

/// `verify`: re-check the certificate set in `path` in exact rational arithmetic; with
/// `expected`, the set must have been made for exactly that configuration.
pub fn verify(path: &Path, expected: Option<&Config>) -> Result<VerifiedSet, AppError> {
    if path.is_file() {
        return Err(AppError::Argument {
            name: "path",
            message: format!(
                "{} is a file: verify takes a certificate set directory (index.json and the files it lists), \
                 because a certificate is only checked against its set's configuration",
                path.display()
            ),
        });
    }
    certify::verify_set_for(path, expected).map_err(|source| AppError::Rejected { path: path.to_path_buf(), source })
}

/// Run `f` on a rayon pool of its own (`threads`, default: the cores), dropped afterwards.
/// For a host process (the Python extension): rayon's global pool does not survive `fork`, so
/// a library that used it would hang in a forked child; a pool per call leaves nothing behind.
pub fn in_own_pool<T: Send>(
    threads: Option<usize>,
    f: impl FnOnce() -> Result<T, AppError> + Send,
) -> Result<T, AppError> {
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(n) = threads {
        builder = builder.num_threads(n);
    }
    let pool = builder.build().map_err(|e| AppError::Internal(format!("cannot start the worker threads: {e}")))?;
    pool.install(f)
}
