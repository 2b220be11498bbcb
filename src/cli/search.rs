//! `wingcheck search` and `wingcheck merge`: parameter searches (crates/search).

use std::path::PathBuf;

use clap::Args;
use wingcheck_search::{Progress, RunControl, RunSummary, SearchOptions, Shard};

use super::common::ConfigArgs;

/// Arguments of `wingcheck search`.
#[derive(Debug, Args)]
pub struct SearchArgs {
    #[command(flatten)]
    config: ConfigArgs,
    /// Axis `key=lo..hi:log:N`, `key=lo..hi:lin:N` or `key=v1,v2,...` (repeatable; any config key).
    #[arg(long = "over", value_name = "AXIS", required = true)]
    over: Vec<String>,
    /// Output directory (a killed run restarted with the same arguments resumes).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// Evaluate shard K of N (chunks c with c mod N = K − 1); combine the shards with `wingcheck merge`
    /// (scripts/parallel-search.sh merges them itself).
    #[arg(long, value_name = "K/N", default_value = "1/1")]
    shard: Shard,
    /// Bisect the W ≻ 0 and (32) boundaries to this tolerance (relative on log axes).
    #[arg(long, value_name = "TOL")]
    refine: Option<f64>,
    /// Metric ranking best.json, by its results.csv column name (minimised; prefix `-` to maximise),
    /// e.g. rms_q_tip_m, -lambda_per_s; the name without its unit suffix (rms_q_tip) is accepted too.
    #[arg(long, default_value = "rms_q_tip_m", allow_hyphen_values = true)]
    best: wingcheck_search::Ranking,
    /// Metric window `t0,t1` in s (default: the second half of the horizon).
    #[arg(long, value_name = "T0,T1", value_parser = parse_window)]
    window: Option<(f64, f64)>,
    /// Points per chunk (the unit of resumption and sharding).
    #[arg(long, default_value_t = 32)]
    chunk_size: usize,
    /// Worker threads (default: all cores; at most 4 × the cores).
    #[arg(long)]
    threads: Option<usize>,
    /// Run a search above the work limits (1e6 points or 2 estimated core-hours).
    #[arg(long)]
    allow_large: bool,
    /// Recompute every point of the chunks found on disk before resuming from them (default:
    /// one point per chunk, chosen at random) and refuse a chunk whose results differ.
    #[arg(long)]
    verify_chunks: bool,
}

fn parse_window(s: &str) -> Result<(f64, f64), String> {
    let (a, b) = s.split_once(',').ok_or("expected t0,t1")?;
    Ok((a.trim().parse().map_err(|_| "t0 is not a number")?, b.trim().parse().map_err(|_| "t1 is not a number")?))
}

/// Arguments of `wingcheck merge`.
#[derive(Debug, Args)]
pub struct MergeArgs {
    /// Shard output directories (same search).
    #[arg(required = true, value_name = "DIR")]
    dirs: Vec<PathBuf>,
    /// Output directory for the combined files.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// Recompute every point of every chunk before merging (default: one point per chunk,
    /// chosen at random) and refuse a chunk whose results differ.
    #[arg(long)]
    verify_chunks: bool,
    /// Recompute above the work limits (with --verify-chunks, the whole search's work).
    #[arg(long)]
    allow_large: bool,
}

fn chunk_check(all: bool) -> wingcheck_search::ChunkCheck {
    if all {
        wingcheck_search::ChunkCheck::All
    } else {
        wingcheck_search::ChunkCheck::Sample
    }
}

pub fn run_search(a: SearchArgs) -> anyhow::Result<()> {
    let base = a.config.load()?;
    let options = SearchOptions {
        window: a.window,
        chunk_size: a.chunk_size,
        refine: a.refine,
        best: a.best,
        ..Default::default()
    };
    // the estimate the guard applies, memory buffer by buffer (the search is posed again inside
    // `ops::search`; posing it is cheap)
    let posed = wingcheck_search::Search::new(base.clone(), &a.over, options.clone())?;
    println!("estimated: {}", posed.estimate_for(a.threads).text());
    let shown = super::progress::Progress::new("search");
    let on_progress = |p: Progress| shown.set(p.done as u64, p.total as u64, "points", "");
    let policy = wingcheck_app::WorkPolicy { allow_large: a.allow_large, front: wingcheck_app::Front::Cli };
    let ctl = RunControl {
        shard: a.shard,
        progress: Some(&on_progress),
        threads: a.threads,
        verify: chunk_check(a.verify_chunks),
        ..Default::default()
    };
    let s = wingcheck_app::ops::search(base, &a.over, options, &a.out, policy, ctl)?;
    shown.finish();
    if s.verified > 0 {
        println!("{} points of the chunks found on disk recomputed: the same results", s.verified);
    }
    println!(
        "{} of {} points evaluated ({} already done), {} of them failed, in {:.1} s; simulation {:.1} s, theory {:.1} s (summed over points)",
        s.evaluated, s.points_total, s.skipped, s.failed, s.wall_seconds, s.sim_seconds, s.theory_seconds
    );
    if s.complete {
        println!("results in {}: {}", s.out_dir.display(), s.files.join(", "));
    } else {
        match std::env::var(MERGED_BY) {
            // A driver script merges the shards itself: nothing for a person to do.
            Ok(by) if !by.trim().is_empty() => {
                println!("shard {}/{} done; {} merges the shards", a.shard.k, a.shard.n, by.trim())
            }
            _ => println!(
                "shard {}/{} done; combine the shard directories with `wingcheck merge DIR... --out DIR`",
                a.shard.k, a.shard.n
            ),
        }
    }
    exit_on_failures(&s);
    Ok(())
}

/// Environment variable a driver script sets (to its own name) when it merges the shards itself
/// (`scripts/parallel-search.sh`; under Slurm a person submits the merge job, so the hint stays): a shard then says who merges
/// instead of telling a person to run `wingcheck merge`.
pub const MERGED_BY: &str = "WINGCHECK_MERGED_BY";

/// Exit status of `search` and `merge` when the run finished (the search, or this shard) but
/// some points failed (diverged or error; listed in failures.csv): its own status, distinct
/// from 1 (an error) and 2 (a usage error, clap's), so a script can tell a complete run with
/// failed points from a command that did not run.
pub const EXIT_POINTS_FAILED: i32 = 3;

/// Exit with [`EXIT_POINTS_FAILED`] when some points failed.
fn exit_on_failures(s: &RunSummary) {
    let failed = match s.failed_total {
        Some((diverged, errors)) => {
            if diverged + errors > 0 {
                println!(
                    "{} of {} points failed ({diverged} diverged, {errors} errors): listed with their reasons in {}",
                    diverged + errors,
                    s.points_total,
                    s.out_dir.join("failures.csv").display()
                );
            }
            diverged + errors
        }
        None => s.failed,
    };
    if failed > 0 {
        std::process::exit(EXIT_POINTS_FAILED);
    }
}

pub fn run_merge(a: MergeArgs) -> anyhow::Result<()> {
    let s = wingcheck_search::merge_with(&a.dirs, &a.out, chunk_check(a.verify_chunks), a.allow_large)?;
    println!("{} points of the chunks recomputed: the same results", s.verified);
    println!("merged {} points into {}: {}", s.points_total, s.out_dir.display(), s.files.join(", "));
    exit_on_failures(&s);
    Ok(())
}
