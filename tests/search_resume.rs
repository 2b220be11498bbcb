//! A killed search restarted with the same arguments resumes (issue 25, class 6), whenever it
//! was killed — in its first milliseconds (before or while writing its manifest), during the
//! chunks, during the final assembly — and the resumed directory holds exactly the files of an
//! uninterrupted run, byte for byte; two identical searches started together both finish.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Duration;

const BIN: &str = env!("CARGO_BIN_EXE_wingcheck");
const ARGS: [&str; 8] =
    ["search", "--over", "control.a=1e-3,1e-2,0.1,1", "--set", "horizon.t_end=0.2", "--chunk-size", "1", "--threads"];

fn search(out: &Path) -> Command {
    let mut c = Command::new(BIN);
    c.args(ARGS).arg("1").arg("--out").arg(out).stdout(Stdio::null()).stderr(Stdio::piped());
    c
}

/// Every file under `dir` (relative paths) with its bytes, but for the files holding wall
/// times (their names only).
fn contents(dir: &Path) -> Vec<(String, Vec<u8>)> {
    fn walk(root: &Path, dir: &Path, out: &mut Vec<(String, Vec<u8>)>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(root, &p, out);
            } else {
                let rel = p.strip_prefix(root).unwrap().to_string_lossy().to_string();
                // wall times: timings.csv, the progress files and each chunk's per-point timings
                let timed = rel == "timings.csv" || rel.starts_with("progress-") || rel.starts_with("chunks/");
                out.push((rel, if timed { Vec::new() } else { std::fs::read(&p).unwrap() }));
            }
        }
    }
    let mut v = Vec::new();
    walk(dir, dir, &mut v);
    v.sort();
    v
}

fn clean_run(root: &Path) -> PathBuf {
    let dir = root.join("clean");
    let o = search(&dir).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    dir
}

/// A pid that no process has (checked in /proc).
fn dead_pid() -> u32 {
    (1_000_000..4_000_000u32).rev().find(|p| !Path::new(&format!("/proc/{p}")).exists()).unwrap()
}

#[test]
fn a_killed_run_restarted_with_the_same_arguments_resumes() {
    let root = tempfile::tempdir().unwrap();
    let want = contents(&clean_run(root.path()));
    // killed at moments from before the manifest exists to the final assembly
    for (k, ms) in [0u64, 1, 2, 3, 4, 5, 6, 8, 12, 20, 60, 150, 400].into_iter().enumerate() {
        let dir = root.path().join(format!("killed-{k}"));
        let mut child = search(&dir).spawn().unwrap();
        std::thread::sleep(Duration::from_millis(ms));
        let _ = child.kill();
        let _ = child.wait();
        let o = search(&dir).output().unwrap();
        assert!(o.status.success(), "killed after {ms} ms, then: {}", String::from_utf8_lossy(&o.stderr));
        assert_eq!(contents(&dir), want, "killed after {ms} ms: the resumed directory differs");
    }
    // a kill during the final assembly or a chunk write leaves temp files of a dead process:
    // the next run removes them
    let dir = root.path().join("temps");
    assert!(search(&dir).status().unwrap().success());
    let pid = dead_pid();
    std::fs::write(dir.join(format!(".results.csv.set-tmp-{pid}")), "partial").unwrap();
    std::fs::write(dir.join(format!("chunks/.chunk-00002.jsonl.tmp-{pid}")), "partial").unwrap();
    assert!(search(&dir).status().unwrap().success());
    assert_eq!(contents(&dir), want);
}

#[test]
fn two_identical_searches_started_together_both_finish() {
    let root = tempfile::tempdir().unwrap();
    let want = contents(&clean_run(root.path()));
    // several rounds of four at once: the window between one run's look at the directory and
    // another's manifest landing in it is a few microseconds wide
    for round in 0..6 {
        let dir = root.path().join(format!("together-{round}"));
        let runs: Vec<_> = (0..4).map(|_| search(&dir).spawn().unwrap()).collect();
        for c in runs {
            let o = c.wait_with_output().unwrap();
            assert!(o.status.success(), "round {round}: {}", String::from_utf8_lossy(&o.stderr));
        }
        assert_eq!(contents(&dir), want, "round {round}");
    }
}

#[test]
fn a_different_search_started_together_is_refused_and_the_first_one_kept() {
    let root = tempfile::tempdir().unwrap();
    let want = contents(&clean_run(root.path()));
    for round in 0..4 {
        let dir = root.path().join(format!("rivals-{round}"));
        let ours = search(&dir).spawn().unwrap();
        let mut rival = Command::new(BIN);
        rival
            .args(["search", "--over", "control.b=1,10", "--set", "horizon.t_end=0.2", "--out"])
            .arg(&dir)
            .stdout(Stdio::null())
            .stderr(Stdio::piped());
        let rival = rival.spawn().unwrap();
        let (a, b) = (ours.wait_with_output().unwrap(), rival.wait_with_output().unwrap());
        // exactly one of them owns the directory, and it holds that search's files only
        assert!(
            a.status.success() != b.status.success(),
            "round {round}: both or neither finished: {} / {}",
            String::from_utf8_lossy(&a.stderr),
            String::from_utf8_lossy(&b.stderr)
        );
        let refused = if a.status.success() { &b } else { &a };
        let why = String::from_utf8_lossy(&refused.stderr);
        assert!(why.contains("use another --out") || why.contains("use a new or empty --out"), "round {round}: {why}");
        if a.status.success() {
            assert_eq!(contents(&dir), want, "round {round}: the first search's files changed");
        }
    }
}
