//! Kill injection for report replacement: `wingcheck report` is killed (SIGKILL) at several
//! moments while it replaces an existing report; `--out` must always hold a complete report
//! (the old one or the new one), and the next run cleans the dead run's staging directory.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Duration;

const ARGS: [&str; 3] = ["report", "--set", "horizon.t_end=1"];

fn report(out: &Path) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_wingcheck"));
    c.args(ARGS).arg("--out").arg(out).stdout(Stdio::null()).stderr(Stdio::null());
    c
}

/// A complete report: the marker lists every file, each exists, and nothing else is there.
fn assert_complete(out: &Path) {
    let marker = std::fs::read_to_string(out.join(".wingcheck-report")).expect("marker present");
    let (_, list) = marker.split_once("\nfiles:\n").expect("marker lists the files");
    let listed: Vec<&str> = list.lines().filter(|l| !l.is_empty()).collect();
    assert!(listed.contains(&"index.html"), "{listed:?}");
    for f in &listed {
        assert!(out.join(f).is_file(), "{f} listed but missing");
    }
    // every file under the folder (proofs/ included), by its path relative to the folder
    let mut present = Vec::new();
    files_under(out, "", &mut present);
    let mut expected: Vec<String> = listed.iter().map(|s| s.to_string()).collect();
    expected.push(".wingcheck-report".into());
    expected.sort();
    present.sort();
    assert_eq!(present, expected, "files besides the listed ones and the marker");
}

/// The files under `dir`, as `prefix` + their relative paths (`/`-separated).
fn files_under(dir: &Path, prefix: &str, out: &mut Vec<String>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let e = e.unwrap();
        let name = format!("{prefix}{}", e.file_name().to_string_lossy());
        if e.file_type().unwrap().is_dir() {
            files_under(&e.path(), &format!("{name}/"), out);
        } else {
            out.push(name);
        }
    }
}

#[test]
fn out_always_holds_a_complete_report_whenever_report_is_killed() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("r");
    assert!(report(&out).status().unwrap().success());
    assert_complete(&out);
    // Kill points spread over a run (one takes about a second here; the exact moments do not
    // matter: the property must hold at every instant).
    for ms in [30, 150, 300, 500, 700] {
        let mut child = report(&out).spawn().unwrap();
        std::thread::sleep(Duration::from_millis(ms));
        let _ = child.kill();
        let _ = child.wait();
        assert_complete(&out);
    }
    // A last full run succeeds and removes the staging directories the killed runs left.
    assert!(report(&out).status().unwrap().success());
    assert_complete(&out);
    let names: Vec<String> =
        std::fs::read_dir(tmp.path()).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into()).collect();
    assert_eq!(names, ["r"], "stale staging directories left: {names:?}");
}

#[test]
fn a_report_directory_is_replaced_only_if_it_holds_nothing_but_files_the_tool_wrote() {
    let tmp = tempfile::tempdir().unwrap();
    // A marker of an older version without a `files:` list owns nothing but itself: a user's
    // CSV next to it is not deleted (the legacy rule owned every top-level csv/json/svg/html).
    let legacy = tmp.path().join("legacy");
    std::fs::create_dir(&legacy).unwrap();
    std::fs::write(legacy.join(".wingcheck-report"), "wingcheck report\n").unwrap();
    std::fs::write(legacy.join("notes.csv"), "mine").unwrap();
    let o = report(&legacy).stderr(Stdio::piped()).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("notes.csv") && err.contains("does not list"), "{err}");
    assert_eq!(std::fs::read_to_string(legacy.join("notes.csv")).unwrap(), "mine");
    // An empty subdirectory of the user's inside a complete report: refused, kept.
    let out = tmp.path().join("r");
    assert!(report(&out).status().unwrap().success());
    std::fs::create_dir(out.join("mine")).unwrap();
    let o = report(&out).stderr(Stdio::piped()).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("mine/"), "{err}");
    assert!(out.join("mine").is_dir() && out.join("index.html").is_file());
    // Without it the report is replaced.
    std::fs::remove_dir(out.join("mine")).unwrap();
    assert!(report(&out).status().unwrap().success());
    assert_complete(&out);
}
