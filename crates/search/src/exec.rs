//! Running, merging and finalising search directories.
//!
//! A directory is a search's own if it holds a `manifest.json` that parses as a [`Manifest`];
//! `search` and `merge` write only into such a directory (of the same search), an empty one,
//! or a new one, and refuse anything else. On failure they leave nothing behind: a directory
//! they created (or found empty) is removed again unless it holds completed chunks, which a
//! rerun resumes from. The final files are written all or nothing ([`wingcheck_io::FileSet`]).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use rayon::prelude::*;

use crate::modal::{RunCache, CACHE_POINTS};
use crate::point::{PointResult, Status};
use crate::verify::{ChunkCheck, Verifier};
use crate::{finalize, limits, store, Manifest, Progress, RunControl, RunSummary, Search, SearchError, TheoryCache};

fn mismatch(dir: &Path, reason: impl Into<String>) -> SearchError {
    SearchError::Mismatch { dir: dir.display().to_string(), reason: reason.into() }
}

/// The output directory's name and type, before any work ([`wingcheck_io::check_output_dir`]:
/// a directory or missing; a symlink to a directory is followed, as the files are written into
/// it).
fn check_out(out: &Path) -> Result<(), SearchError> {
    Ok(wingcheck_io::check_output_dir(out, false)?)
}

/// Creates `path` holding `text` unless it exists ([`wingcheck_io::create_file_atomic`]);
/// whether this call created it.
fn create_new(path: &Path, text: &str) -> Result<bool, SearchError> {
    match wingcheck_io::create_file_atomic(path, text.as_bytes()) {
        Ok(()) => Ok(true),
        Err(wingcheck_io::IoError::Exists { .. }) => Ok(false),
        Err(e) => Err(e.into()),
    }
}

/// How `prepare_out` found the output directory.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Found {
    /// Did not exist: created.
    Created,
    /// Existed and was empty.
    Empty,
    /// Held this search already (resume).
    Ours,
}

/// Make `out` ready for the search with manifest `text`, refusing directories that are not a
/// search's own. Two identical searches started together on one `out` both go on: the manifest
/// is created without overwriting ([`wingcheck_io::create_file_atomic`]), and the one that finds it already
/// there (or sees it appear while looking) takes the directory as its own.
fn prepare_out(out: &Path, text: &str) -> Result<Found, SearchError> {
    // a manifest that appears while the directory is being looked at: look again (bounded, as
    // a failing concurrent run may remove it again)
    let mut found = None;
    for _ in 0..3 {
        found = classify(out, text)?;
        if found.is_some() {
            break;
        }
    }
    let Some(mut found) = found else {
        return Err(mismatch(
            out,
            "its manifest.json keeps appearing and disappearing (another search is using it?); use another --out",
        ));
    };
    // the manifest first: a run killed at any moment leaves a directory the next run takes
    // (no manifest: nothing but our temp files; a manifest: this search, resumed)
    let mut setup = || -> Result<(), SearchError> {
        store::mkdir(out)?;
        wingcheck_io::remove_stale_temps(out);
        if found != Found::Ours && !create_new(&out.join("manifest.json"), text)? {
            // another run created it since we looked: ours only if it is this search
            // (either way the directory is that run's now: nothing here is ours to clean up)
            found = Found::Ours;
            if store::read(&out.join("manifest.json"))? != text {
                return Err(mismatch(out, "another search started in it meanwhile; use another --out"));
            }
        }
        store::mkdir(&out.join(store::CHUNK_DIR))?;
        wingcheck_io::remove_stale_temps(&out.join(store::CHUNK_DIR));
        Ok(())
    };
    if let Err(e) = setup() {
        clean_up(out, found, true);
        return Err(e);
    }
    Ok(found)
}

/// How `out` stands for the search with manifest `text`; `None` when a manifest appeared while
/// its entries were being read.
fn classify(out: &Path, text: &str) -> Result<Option<Found>, SearchError> {
    if !out.exists() {
        return Ok(Some(Found::Created));
    }
    if !out.is_dir() {
        return Err(mismatch(out, "exists and is not a directory"));
    }
    let manifest = out.join("manifest.json");
    if manifest.exists() {
        let have = store::read(&manifest)?;
        if serde_json::from_str::<Manifest>(&have).is_err() {
            return Err(mismatch(out, "manifest.json is not a wingcheck search manifest; use another --out"));
        }
        if have != text {
            return Err(mismatch(
                out,
                "manifest.json describes a different search (config, axes or options); use another --out",
            ));
        }
        return Ok(Some(Found::Ours));
    }
    // empty, or holding only what a search killed while setting up leaves: temp files of the
    // manifest's write and an empty chunks/ (the manifest is written first)
    let io = |source| SearchError::FileSystem { path: out.to_path_buf(), source };
    for e in std::fs::read_dir(out).map_err(io)? {
        let e = e.map_err(io)?;
        let name = e.file_name().to_string_lossy().to_string();
        if name == "manifest.json" {
            return Ok(None);
        }
        let empty_chunks = name == store::CHUNK_DIR
            && std::fs::read_dir(e.path())
                .is_ok_and(|mut d| d.all(|x| x.is_ok_and(|x| wingcheck_io::is_temp(&x.file_name().to_string_lossy()))));
        if !(wingcheck_io::is_temp(&name) || empty_chunks) {
            // a concurrent run's manifest and chunks may have arrived after the first look
            if manifest.exists() {
                return Ok(None);
            }
            return Err(mismatch(
                out,
                "exists, is not empty and is not a wingcheck search directory (no manifest.json); use a new or empty --out",
            ));
        }
    }
    Ok(Some(Found::Empty))
}

/// After a failure: remove what this invocation created in a directory it created or found
/// empty, unless completed chunks are there (and `force` is false).
fn clean_up(out: &Path, found: Found, force: bool) {
    if found == Found::Ours {
        return;
    }
    let has_chunks = std::fs::read_dir(out.join(store::CHUNK_DIR))
        .map(|mut d| d.any(|e| e.is_ok_and(|e| e.file_name().to_string_lossy().starts_with("chunk-"))))
        .unwrap_or(false);
    if has_chunks && !force {
        return;
    }
    match found {
        Found::Created => {
            let _ = std::fs::remove_dir_all(out);
        }
        _ => {
            if let Ok(entries) = std::fs::read_dir(out) {
                for e in entries.flatten() {
                    let p = e.path();
                    let _ = if p.is_dir() { std::fs::remove_dir_all(&p) } else { std::fs::remove_file(&p) };
                }
            }
        }
    }
}

/// Run (this shard of) a search into `out`, resuming from chunks already there; when every
/// chunk of the search is present, write the final files ([`finalize`]). Refused before any
/// work above the limits ([`limits::check`]) or with a bad thread count.
pub fn run(search: &Search, out: &Path, ctl: RunControl<'_>) -> Result<RunSummary, SearchError> {
    check_out(out)?;
    if let Some(n) = ctl.threads {
        limits::check_threads(n)?;
    }
    search.check_controller(ctl.controller)?;
    let flag = ctl.allow_large_flag.unwrap_or(wingcheck_model::work::ALLOW_LARGE_FLAG);
    limits::check_with_flag(&search.estimate_for(ctl.threads), ctl.allow_large, flag)?;
    if let Some(n) = ctl.threads {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map_err(|source| SearchError::ThreadPool { threads: n, source })?;
        return pool.install(|| run(search, out, RunControl { threads: None, ..ctl }));
    }
    let found = prepare_out(out, &search.manifest_text())?;
    let result = run_in(search, out, &ctl);
    match &result {
        // a cancelled run into a directory it created leaves nothing behind
        Err(SearchError::Cancelled(_)) => clean_up(out, found, matches!(found, Found::Created | Found::Empty)),
        Err(_) => clean_up(out, found, false),
        Ok(_) => {}
    }
    result
}

/// This shard's chunks found on disk before any new work.
struct Scan {
    /// Points in the chunks already done.
    skipped: usize,
    /// Chunks this shard owns.
    owned: usize,
    /// Of which done.
    completed: usize,
    /// Points still to evaluate.
    total: usize,
    /// Points of the done chunks recomputed to prove them this search's own.
    verified: usize,
    /// Per chunk: done.
    done: Vec<bool>,
}

/// First pass over this shard's chunks: which are done, each proven this search's own by
/// recomputing some of its points (all with --verify-chunks) before any new work; chunks are
/// read one at a time (a bit per chunk is kept).
fn scan(search: &Search, out: &Path, ctl: &RunControl<'_>) -> Result<Scan, SearchError> {
    let mut scan =
        Scan { skipped: 0, owned: 0, completed: 0, total: 0, verified: 0, done: vec![false; search.chunks()] };
    let mut verifier = Verifier::new(search, ctl.verify, ctl.controller);
    for c in (0..search.chunks()).filter(|&c| ctl.shard.owns(c)) {
        scan.owned += 1;
        match store::read_chunk(out, search, c)? {
            Some(points) => {
                scan.skipped += points.len();
                scan.completed += 1;
                scan.done[c] = true;
                scan.verified += verifier.chosen(c, points.len()).len();
                verifier.add(out, c, points)?;
            }
            None => scan.total += search.chunk_range(c).len(),
        }
    }
    verifier.flush()?;
    Ok(scan)
}

/// The points of chunk `c`, in parallel, counting each in `done` of `total` for the progress
/// callback; stops at the cancel token.
fn evaluate_chunk(
    search: &Search,
    c: usize,
    (cache, runs): (&TheoryCache, &RunCache),
    ctl: &RunControl<'_>,
    (done, total): (&AtomicUsize, usize),
) -> Result<Vec<PointResult>, wingcheck_model::Cancelled> {
    search
        .chunk_range(c)
        .into_par_iter()
        .map(|p| {
            ctl.cancel.check()?;
            let r = search.evaluate_with(p, cache, runs, ctl.controller);
            let d = done.fetch_add(1, Ordering::Relaxed) + 1;
            if let Some(cb) = ctl.progress {
                cb(Progress { done: d, total });
            }
            Ok(r)
        })
        .collect()
}

fn run_in(search: &Search, out: &Path, ctl: &RunControl<'_>) -> Result<RunSummary, SearchError> {
    let start = Instant::now();
    let clock = wingcheck_io::clock::Stopwatch::start();
    let Scan { skipped, owned, mut completed, total, verified, done } = scan(search, out, ctl)?;
    let progress_name = format!("progress-{}-of-{}.json", ctl.shard.k, ctl.shard.n);
    // what is on disk now (a run killed between a chunk and its progress file left it behind)
    wingcheck_io::write_file_atomic(&out.join(&progress_name), progress_text(ctl, owned, completed).as_bytes())?;
    let points_done = AtomicUsize::new(0);
    if let Some(p) = ctl.progress {
        p(Progress { done: 0, total });
    }
    let mut summary = RunSummary {
        out_dir: out.to_path_buf(),
        points_total: search.points(),
        skipped,
        verified,
        ..Default::default()
    };
    let (mut cache, mut runs, mut cache_points) =
        (TheoryCache::new(search.options.lyapunov_elements), RunCache::new(), 0);
    let mut written = 0;
    for c in (0..search.chunks()).filter(|&c| ctl.shard.owns(c)) {
        if ctl.stop_after_chunks == Some(written) {
            break;
        }
        if done[c] {
            continue;
        }
        written += 1;
        // The caches are renewed every CACHE_POINTS points: their entries are keyed by what a
        // point's config shares with others (wing, observer; a, b, … for the verdicts), so a
        // search-long cache would grow with the number of points.
        if cache_points + search.chunk_range(c).len() > CACHE_POINTS {
            (cache, runs, cache_points) = (TheoryCache::new(search.options.lyapunov_elements), RunCache::new(), 0);
        }
        cache_points += search.chunk_range(c).len();
        let points = evaluate_chunk(search, c, (&cache, &runs), ctl, (&points_done, total))?;
        // the chunk and the progress file that counts it, written together
        completed += 1;
        // (staged together, the chunk renamed first: a kill between the two renames leaves the
        // progress file one chunk behind, which the next run rewrites before any work)
        let mut set = wingcheck_io::FileSet::new();
        set.add(&store::chunk_path(out, c), store::chunk_text(search, c, &points).as_bytes())?;
        set.add(&out.join(&progress_name), progress_text(ctl, owned, completed).as_bytes())?;
        set.commit()?;
        summary.evaluated += points.len();
        summary.failed += points.iter().filter(|p| p.status != Status::Ok).count();
        summary.sim_seconds += points.iter().map(|p| p.sim_seconds).sum::<f64>();
        summary.theory_seconds += points.iter().map(|p| p.theory_seconds).sum::<f64>();
    }
    ctl.cancel.check()?;
    if (0..search.chunks()).all(|c| store::chunk_path(out, c).exists()) {
        let (files, failed) = finalize(out)?;
        summary.files = files;
        summary.failed_total = Some(failed);
        summary.complete = true;
    }
    summary.wall_seconds = start.elapsed().as_secs_f64();
    summary.cpu_seconds = clock.elapsed().cpu_seconds;
    Ok(summary)
}

/// The progress file of this shard: `progress-K-of-N.json` with the chunks it owns and has
/// completed (docs/outputs.md).
fn progress_text(ctl: &RunControl<'_>, owned: usize, completed: usize) -> String {
    let progress = serde_json::json!({
        "shard": format!("{}/{}", ctl.shard.k, ctl.shard.n),
        "chunks_owned": owned,
        "chunks_completed": completed,
    });
    serde_json::to_string_pretty(&progress).expect("json") + "\n"
}

/// Combine shard directories into `out`: check that they hold the same search and that every
/// chunk is present somewhere (before writing anything), copy every chunk (the first valid
/// copy found, in the order of `dirs`) and [`finalize`]. On failure nothing is left in `out`
/// that was not there before.
pub fn merge(dirs: &[PathBuf], out: &Path) -> Result<RunSummary, SearchError> {
    merge_with(dirs, out, ChunkCheck::Sample, false)
}

/// [`merge`], recomputing `check`'s points of every chunk copied ([`crate::verify`]) before
/// anything is written; that recomputation is refused above the search's limits
/// ([`crate::verify::estimate`], [`limits::check`]) unless `allow_large`.
pub fn merge_with(
    dirs: &[PathBuf],
    out: &Path,
    check: ChunkCheck,
    allow_large: bool,
) -> Result<RunSummary, SearchError> {
    check_out(out)?;
    let start = Instant::now();
    let first = dirs.first().ok_or(SearchError::MergeNothing)?;
    let text = store::read(&first.join("manifest.json"))?;
    for d in &dirs[1..] {
        if store::read(&d.join("manifest.json"))? != text {
            return Err(mismatch(
                d,
                format!("manifest.json differs from {}'s: not shards of the same search", first.display()),
            ));
        }
    }
    let manifest: Manifest = serde_json::from_str(&text)
        .map_err(|source| SearchError::Manifest { path: first.join("manifest.json"), source })?;
    let search = Search::from_manifest(manifest)?;
    if let Some(name) = &search.options.controller {
        return Err(SearchError::MergeOwnController { name: name.clone() });
    }
    limits::check(&crate::verify::estimate(&search, check, None), allow_large)?;
    let mut sources = Vec::with_capacity(search.chunks());
    let mut missing = Vec::new();
    let (mut verifier, mut verified) = (Verifier::new(&search, check, None), 0);
    for c in 0..search.chunks() {
        let mut found = None;
        for d in dirs {
            if let Some(points) = store::read_chunk(d, &search, c)? {
                verified += verifier.chosen(c, points.len()).len();
                verifier.add(d, c, points)?;
                found = Some(d);
                break;
            }
        }
        match found {
            Some(d) => sources.push(d),
            None => missing.push(c),
        }
    }
    verifier.flush()?;
    drop(verifier);
    if !missing.is_empty() {
        return Err(SearchError::MissingChunks {
            missing: missing.len(),
            total: search.chunks(),
            first: missing.iter().take(8).copied().collect(),
        });
    }
    let found = prepare_out(out, &text)?;
    let copy_and_finalize = || -> Result<(Vec<String>, (usize, usize)), SearchError> {
        for (c, d) in sources.iter().enumerate() {
            let target = store::chunk_path(out, c);
            if store::chunk_path(d, c) != target {
                wingcheck_io::write_file_atomic(&target, store::read(&store::chunk_path(d, c))?.as_bytes())?;
            }
        }
        finalize(out)
    };
    let (files, failed) = copy_and_finalize().inspect_err(|_| clean_up(out, found, true))?;
    Ok(RunSummary {
        out_dir: out.to_path_buf(),
        points_total: search.points(),
        complete: true,
        files,
        failed_total: Some(failed),
        wall_seconds: start.elapsed().as_secs_f64(),
        verified,
        ..Default::default()
    })
}
