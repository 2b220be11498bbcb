//! Real distributed searches: shards run as separate processes by GNU parallel
//! (`scripts/parallel-search.sh`) and by a Slurm job array (`scripts/slurm-search.sh`), merged,
//! must be byte-identical to a single run — once with docs/search.md's commands exactly as written
//! there (with `wingcheck` on PATH, as `cargo install --path .` leaves it), once on a small
//! search; and the scripts' exit statuses.
//!
//! The tests that need GNU parallel or a running Slurm are `#[ignore]`d, so a plain
//! `cargo test` reports them as ignored rather than passed; `.ci/run` installs both (a
//! single-node Slurm, `scripts/local-slurm.sh`) and runs them with `--ignored`, where a missing
//! or broken tool fails the test.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

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
    "heatmap-rms_q_tip_m.svg",
    "heatmap-rms_theta_tip_rad.svg",
    "heatmap-settling_time_s.svg",
];

fn checkout() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn script(name: &str) -> PathBuf {
    checkout().join("scripts").join(name)
}

fn text(o: &Output) -> String {
    format!(
        "status {:?}\n{}\n{}",
        o.status.code(),
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

fn single_run(root: &Path, args: &[String]) -> PathBuf {
    let single = root.join("single");
    let out = Command::new(BIN).arg("search").args(args).arg("--out").arg(&single).output().unwrap();
    assert!(out.status.success(), "single run: {}", text(&out));
    single
}

fn assert_same(a: &Path, b: &Path) {
    for f in FILES {
        let x = std::fs::read(a.join(f)).unwrap_or_else(|e| panic!("{f} in {}: {e}", a.display()));
        let y = std::fs::read(b.join(f)).unwrap_or_else(|e| panic!("{f} in {}: {e}", b.display()));
        assert!(x == y, "{f} differs between {} and {}", a.display(), b.display());
    }
}

/// Panics (the test fails) unless `tool arg` runs and succeeds.
fn require(tool: &str, args: &[&str], what: &str) {
    let ok = Command::new(tool).args(args).output().is_ok_and(|o| o.status.success());
    assert!(ok, "`{tool} {}` does not answer: {what}", args.join(" "));
}

fn strings(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

/// A directory holding `wingcheck` (a link to this build) for PATH, as `cargo install --path .`
/// leaves one in ~/.cargo/bin, and the PATH with it first.
fn installed(root: &Path) -> String {
    let bin = root.join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    std::os::unix::fs::symlink(BIN, bin.join("wingcheck")).unwrap();
    format!("{}:{}", bin.display(), std::env::var("PATH").unwrap_or_default())
}

/// A working directory with the checkout's `scripts/` in it, so docs/search.md's relative paths
/// hold and its `runs/` land in the temporary directory.
fn workdir(root: &Path) -> PathBuf {
    let dir = root.join("work");
    std::fs::create_dir_all(&dir).unwrap();
    std::os::unix::fs::symlink(checkout().join("scripts"), dir.join("scripts")).unwrap();
    dir
}

/// docs/search.md's lines of the distributed route that start with `prefix` (trailing `# …`
/// comments removed), in order.
fn readme_lines(prefix: &str) -> Vec<String> {
    let readme = std::fs::read_to_string(checkout().join("docs/search.md")).unwrap();
    let section = readme.split("Distributed runs").nth(1).expect("docs/search.md has a 'Distributed runs' section");
    let block = section.split("```sh").nth(1).and_then(|b| b.split("```").next()).expect("a sh block");
    let lines: Vec<String> = block
        .lines()
        .map(|l| l.split("   #").next().unwrap().trim().to_string())
        .filter(|l| l.starts_with(prefix))
        .collect();
    assert!(!lines.is_empty(), "no line of docs/search.md starts with {prefix:?}");
    lines
}

/// The words of a docs/search.md line after the script's name `script` and `skip` more words (N, OUT):
/// its search arguments, without the closing `)` of a `$(…)`.
fn search_args(line: &str, script: &str, skip: usize) -> Vec<String> {
    let words: Vec<&str> = line.split_whitespace().collect();
    let at = words.iter().position(|w| w.ends_with(script)).expect("the script's word") + 1 + skip;
    words[at..].iter().map(|w| w.trim_end_matches(')').to_string()).collect()
}

fn bash(dir: &Path, path: &str, script: &str) -> Output {
    Command::new("bash")
        .args(["-euo", "pipefail", "-c", script])
        .current_dir(dir)
        .env("PATH", path)
        .env_remove("WINGCHECK")
        .output()
        .unwrap()
}

/// PATH without any directory that holds a `wingcheck`, as on a machine where it was built
/// (`cargo build --release`) but never installed.
fn path_without_wingcheck() -> String {
    let path = std::env::var("PATH").unwrap_or_default();
    let kept: Vec<&str> = path.split(':').filter(|d| !Path::new(d).join("wingcheck").exists()).collect();
    kept.join(":")
}

#[test]
#[ignore = "needs GNU parallel: .ci/run installs it and runs this with --ignored"]
fn the_documented_gnu_parallel_route_as_written_matches_the_single_run() {
    require("parallel", &["--version"], "install GNU parallel (Debian package `parallel`)");
    let root = tempfile::tempdir().unwrap();
    let (path, dir) = (installed(root.path()), workdir(root.path()));
    let line = readme_lines("scripts/parallel-search.sh").remove(0);
    let out = bash(&dir, &path, &line);
    assert!(out.status.success(), "{line}: {}", text(&out));
    let all = dir.join(line.split_whitespace().nth(2).unwrap()).join("all");
    assert_same(&single_run(root.path(), &search_args(&line, "parallel-search.sh", 2)), &all);
}

#[test]
#[ignore = "needs a running Slurm (scripts/local-slurm.sh): .ci/run starts one and runs this with --ignored"]
fn the_documented_slurm_route_as_written_matches_the_single_run_without_an_install() {
    require("timeout", &["5", "sinfo"], "no Slurm controller answers (start one with scripts/local-slurm.sh)");
    // Not installed: the scripts fall back to the release build (scripts/find-wingcheck.sh),
    // found through CARGO_TARGET_DIR, which the job array and the merge job inherit.
    let root = tempfile::tempdir().unwrap();
    let dir = workdir(root.path());
    let target = Path::new(BIN).parent().and_then(Path::parent).expect("BIN is <target>/release/wingcheck");
    let (array, merge) = (readme_lines("jid=$(sbatch").remove(0), readme_lines("sbatch --dependency").remove(0));
    let mut cmd = Command::new("bash");
    cmd.args(["-euo", "pipefail", "-c", &format!("{array}\n{merge}")]).current_dir(&dir);
    cmd.env("PATH", path_without_wingcheck()).env_remove("WINGCHECK").env("CARGO_TARGET_DIR", target);
    let out = cmd.output().unwrap();
    assert!(out.status.success(), "{array}\n{merge}\n{}", text(&out));
    // the merge job's "Submitted batch job N": wait for it (the array's tasks come before it)
    let stdout = String::from_utf8_lossy(&out.stdout);
    let job = stdout.split_whitespace().last().expect("sbatch printed the job id").to_string();
    let start = Instant::now();
    while Command::new("squeue").args(["-h", "-j", &job]).output().is_ok_and(|o| !o.stdout.is_empty()) {
        assert!(start.elapsed() < Duration::from_secs(600), "merge job {job} still queued after 600 s");
        std::thread::sleep(Duration::from_millis(500));
    }
    let out = array.split_whitespace().skip_while(|w| !w.ends_with("slurm-search.sh")).nth(1).unwrap();
    let all = dir.join(out).join("all");
    assert!(all.join("results.csv").exists(), "no merged results; job logs in {}", dir.display());
    assert_same(&single_run(root.path(), &search_args(&array, "slurm-search.sh", 1)), &all);
}

#[test]
#[ignore = "needs GNU parallel: .ci/run installs it and runs this with --ignored"]
fn gnu_parallel_shards_merge_to_the_single_run() {
    require("parallel", &["--version"], "install GNU parallel (Debian package `parallel`)");
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
    assert!(out.status.success(), "{}", text(&out));
    let log = std::fs::read_to_string(dist.join("parallel-joblog.txt")).unwrap();
    assert_eq!(log.lines().count(), 4, "three jobs ran under parallel: {log}");
    for k in 1..=3 {
        assert!(dist.join(format!("shard-{k}/chunks")).is_dir());
        assert!(!dist.join(format!("shard-{k}/results.csv")).exists(), "a shard alone is incomplete");
    }
    assert_same(&single_run(root.path(), &strings(&ARGS)), &dist.join("all"));
}

#[test]
#[ignore = "needs GNU parallel: .ci/run installs it and runs this with --ignored"]
fn gnu_parallel_route_stops_on_a_failed_shard() {
    require("parallel", &["--version"], "install GNU parallel (Debian package `parallel`)");
    let root = tempfile::tempdir().unwrap();
    let dist = root.path().join("dist");
    let out = Command::new(script("parallel-search.sh"))
        .args(["2".as_ref(), dist.as_os_str(), "--ovr".as_ref(), "control.a=1,2".as_ref()])
        .env("WINGCHECK", BIN)
        .output()
        .unwrap();
    // the shards' usage error (clap's 2) is the script's status, and nothing is merged
    assert_eq!(out.status.code(), Some(2), "{}", text(&out));
    assert!(String::from_utf8_lossy(&out.stderr).contains("a shard failed"), "{}", text(&out));
    assert!(!dist.join("all").exists());
}

#[test]
#[ignore = "needs a running Slurm (scripts/local-slurm.sh): .ci/run starts one and runs this with --ignored"]
fn slurm_job_array_shards_merge_to_the_single_run() {
    require("timeout", &["5", "sinfo"], "no Slurm controller answers (start one with scripts/local-slurm.sh)");
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
    assert!(out.status.success(), "sbatch: {}", text(&out));
    let shards: Vec<_> = (1..=3).map(|k| dist.join(format!("shard-{k}"))).collect();
    let merged = Command::new(BIN).arg("merge").args(&shards).arg("--out").arg(dist.join("all")).output().unwrap();
    assert!(merged.status.success(), "merge: {}", text(&merged));
    assert_same(&single_run(root.path(), &strings(&ARGS)), &dist.join("all"));
}

/// `scripts/slurm-search.sh` run as task `k` of an array of `n` (the variables Slurm sets).
fn slurm_task(k: usize, n: usize, args: &[&str]) -> Command {
    let mut c = Command::new(script("slurm-search.sh"));
    c.args(args).env("SLURM_ARRAY_TASK_ID", k.to_string()).env("SLURM_ARRAY_TASK_COUNT", n.to_string());
    c.env_remove("SLURM_ARRAY_TASK_MIN").env_remove("SLURM_ARRAY_TASK_MAX").env_remove("SHARDS");
    c
}

/// Two points, one of which diverges (explicit sampling with κ1·T = 100: forward Euler of
/// σ̇ = −κ1σ + … is unstable for κ1·T > 2).
const ONE_FAILS: [&str; 6] =
    ["--over", "observer.kappa1=0.8,1e5", "--set", "observer.rule=explicit", "--set", "horizon.t_end=0.2"];

#[test]
fn some_failed_points_have_their_own_exit_status_and_complete_a_slurm_task() {
    let root = tempfile::tempdir().unwrap();
    // wingcheck itself: 3 (complete, some points failed), not clap's 2
    let direct =
        Command::new(BIN).arg("search").args(ONE_FAILS).arg("--out").arg(root.path().join("d")).output().unwrap();
    assert_eq!(direct.status.code(), Some(3), "{}", text(&direct));
    // a Slurm task whose shard completed with a failed point did its job: 0 (COMPLETED)
    let out = slurm_task(1, 1, &[root.path().join("s").to_str().unwrap()])
        .args(ONE_FAILS)
        .env("WINGCHECK", BIN)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", text(&out));
    let failures = std::fs::read_to_string(root.path().join("s/shard-1/failures.csv")).unwrap();
    assert_eq!(failures.lines().count(), 2, "{failures}");
}

#[test]
fn a_slurm_task_never_masks_a_usage_error() {
    let root = tempfile::tempdir().unwrap();
    let out_dir = root.path().join("s");
    // a misspelt option: clap's usage error (2) is the task's status, so Slurm shows FAILED
    let out = slurm_task(1, 2, &[out_dir.to_str().unwrap(), "--ovr", "control.a=1,2"])
        .env("WINGCHECK", BIN)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "{}", text(&out));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--ovr"), "{}", text(&out));
    // the script's own usage error too
    let out = slurm_task(1, 2, &[]).env("WINGCHECK", BIN).output().unwrap();
    assert_eq!(out.status.code(), Some(2), "{}", text(&out));
}

/// A copy of the scripts in `root/checkout/scripts`, optionally with a release build there.
fn copied_checkout(root: &Path, with_build: bool) -> PathBuf {
    let c = root.join("checkout");
    std::fs::create_dir_all(c.join("scripts")).unwrap();
    for f in ["slurm-search.sh", "find-wingcheck.sh", "parallel-search.sh"] {
        std::fs::copy(script(f), c.join("scripts").join(f)).unwrap();
    }
    if with_build {
        std::fs::create_dir_all(c.join("target/release")).unwrap();
        std::os::unix::fs::symlink(BIN, c.join("target/release/wingcheck")).unwrap();
    }
    c
}

#[test]
fn the_scripts_find_a_fresh_checkouts_build_or_say_how_to_get_one() {
    let root = tempfile::tempdir().unwrap();
    // PATH without any wingcheck, no WINGCHECK, no CARGO_TARGET_DIR
    let path = "/usr/local/bin:/usr/bin:/bin";
    let run = |c: &Path, out: &Path| {
        Command::new("bash")
            .arg(c.join("scripts/slurm-search.sh"))
            .arg(out)
            .args(["--over", "control.a=1,2", "--set", "horizon.t_end=0.05"])
            .env("PATH", path)
            .env_remove("WINGCHECK")
            .env_remove("CARGO_TARGET_DIR")
            .env("SLURM_ARRAY_TASK_ID", "1")
            .env("SLURM_ARRAY_TASK_COUNT", "1")
            .output()
            .unwrap()
    };
    let bare = copied_checkout(&root.path().join("bare"), false);
    let out = run(&bare, &root.path().join("o1"));
    assert_eq!(out.status.code(), Some(1), "{}", text(&out));
    assert!(String::from_utf8_lossy(&out.stderr).contains("cargo install --locked --path ."), "{}", text(&out));
    // after `cargo build --release` in the checkout: target/release/wingcheck is used
    let built = copied_checkout(&root.path().join("built"), true);
    let out = run(&built, &root.path().join("o2"));
    assert!(out.status.success(), "{}", text(&out));
    assert!(root.path().join("o2/shard-1/results.csv").exists());
}
