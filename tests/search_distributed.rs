//! Real distributed searches: shards run as separate processes by GNU parallel
//! (`scripts/parallel-search.sh`) and by a Slurm job array (`scripts/slurm-search.sh`, only
//! if a Slurm cluster answers `sinfo`), merged, must be byte-identical to a single run.

use std::path::Path;
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_wingcheck");

/// A small search crossing both theory boundaries: 3 × 3 points, 0.2-s horizon, chunks of 2.
const ARGS: [&str; 10] = [
    "--over",
    "control.a=1e-4..1:log:3",
    "--over",
    "control.b=0.5,1,4",
    "--set",
    "horizon.t_end=0.2",
    "--chunk-size",
    "2",
    "--refine",
    "1e-3",
];

/// Every deterministic file (timings.csv and the progress/log files hold wall times).
const FILES: [&str; 9] = [
    "manifest.json",
    "results.csv",
    "results.json",
    "best.json",
    "failures.csv",
    "boundary.csv",
    "heatmap-rms_q_tip.svg",
    "heatmap-rms_theta_tip.svg",
    "heatmap-settling_time.svg",
];

fn single_run(root: &Path) -> std::path::PathBuf {
    let single = root.join("single");
    let out = Command::new(BIN).arg("search").args(ARGS).arg("--out").arg(&single).output().unwrap();
    assert!(out.status.success(), "single run: {}", String::from_utf8_lossy(&out.stderr));
    single
}

fn assert_same(a: &Path, b: &Path) {
    for f in FILES {
        let x = std::fs::read(a.join(f)).unwrap_or_else(|e| panic!("{f} in {}: {e}", a.display()));
        let y = std::fs::read(b.join(f)).unwrap_or_else(|e| panic!("{f} in {}: {e}", b.display()));
        assert!(x == y, "{f} differs between {} and {}", a.display(), b.display());
    }
}

fn available(tool: &str, arg: &str) -> bool {
    Command::new(tool).arg(arg).output().is_ok_and(|o| o.status.success())
}

fn script(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts").join(name)
}

#[test]
fn gnu_parallel_shards_merge_to_the_single_run() {
    if !available("parallel", "--version") {
        println!("skipped: GNU parallel is not installed (Debian package `parallel`; .ci/run installs it)");
        return;
    }
    let root = tempfile::tempdir().unwrap();
    let dist = root.path().join("dist");
    // 3 shards of 5 chunks: shard 1 gets chunks 0, 3; shard 2: 1, 4; shard 3: 2
    let out = Command::new(script("parallel-search.sh"))
        .arg("3")
        .arg(&dist)
        .args(ARGS)
        .env("WINGCHECK", BIN)
        .env("JOBS", "2")
        .output()
        .unwrap();
    assert!(out.status.success(), "{}\n{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    let log = std::fs::read_to_string(dist.join("parallel-joblog.txt")).unwrap();
    assert_eq!(log.lines().count(), 4, "three jobs ran under parallel: {log}");
    for k in 1..=3 {
        assert!(dist.join(format!("shard-{k}/chunks")).is_dir());
        assert!(!dist.join(format!("shard-{k}/results.csv")).exists(), "a shard alone is incomplete");
    }
    assert_same(&single_run(root.path()), &dist.join("all"));
}

#[test]
fn slurm_job_array_shards_merge_to_the_single_run() {
    // `sinfo` waits for an absent controller: bound the probe with coreutils' timeout
    let answers = Command::new("timeout").args(["3", "sinfo"]).output().is_ok_and(|o| o.status.success());
    if !available("sinfo", "--version") || !answers {
        println!("skipped: no Slurm cluster answers `sinfo` (scripts/slurm-search.sh is not exercised)");
        return;
    }
    let root = tempfile::tempdir().unwrap();
    let dist = root.path().join("slurm");
    let out = Command::new("sbatch")
        .args(["--parsable", "--wait", "--array=1-3", "--time=5"])
        .arg(format!("--output={}/slurm-%A_%a.out", root.path().display()))
        .arg(format!("--export=ALL,WINGCHECK={BIN}"))
        .arg(script("slurm-search.sh"))
        .arg(&dist)
        .args(ARGS)
        .output()
        .unwrap();
    assert!(out.status.success(), "sbatch: {}", String::from_utf8_lossy(&out.stderr));
    let shards: Vec<_> = (1..=3).map(|k| dist.join(format!("shard-{k}"))).collect();
    let merged = Command::new(BIN).arg("merge").args(&shards).arg("--out").arg(dist.join("all")).output().unwrap();
    assert!(merged.status.success(), "merge: {}", String::from_utf8_lossy(&merged.stderr));
    assert_same(&single_run(root.path()), &dist.join("all"));
}
