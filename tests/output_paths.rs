//! Output and input paths (issue 46, items 5 and 6), through the binary: every path is taken as
//! an `OsStr` (a non-UTF-8 argument crashed `report`, exit 101); every output is checked — type,
//! name length with the staging directory's suffix, symlinks — before any work starts; special
//! files are never opened for reading nor replaced; `schema --out` refuses files it did not
//! write. Each refusal is a clean exit 1 naming the path, within a second, and leaves what was
//! there as it was.

#![cfg(unix)]

use std::ffi::OsStr;
use std::os::unix::ffi::OsStrExt;
use std::path::Path;
use std::process::{Command, Output};
use std::time::{Duration, Instant};

fn wingcheck(args: &[&OsStr]) -> (Output, Duration) {
    let start = Instant::now();
    let o = Command::new(env!("CARGO_BIN_EXE_wingcheck")).args(args).output().expect("binary runs");
    (o, start.elapsed())
}

fn os(s: &str) -> &OsStr {
    OsStr::new(s)
}

/// Exit 1, before any work (well under a second), the message containing every `mention`.
fn refused_at_once(args: &[&OsStr], mentions: &[&str]) {
    let (o, took) = wingcheck(args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    for m in mentions {
        assert!(err.contains(m), "{m:?} missing from: {err}");
    }
    assert!(took < Duration::from_secs(1), "{args:?} refused only after {took:?}");
}

fn mkfifo(p: &Path) -> bool {
    Command::new("mkfifo").arg(p).status().map(|s| s.success()).unwrap_or(false)
}

#[test]
fn report_takes_non_utf8_paths() {
    let dir = tempfile::tempdir().unwrap();
    let bad = |name: &[u8]| dir.path().join(OsStr::from_bytes(name));
    // a non-UTF-8 --config that does not exist: named (lossily), exit 1
    let config = bad(b"\xff.json");
    refused_at_once(&[os("report"), os("--config"), config.as_os_str()], &["cannot read config", "No such file"]);
    // a non-UTF-8 --out under a regular file: refused before any work, the file untouched
    let blocker = dir.path().join("blocker");
    std::fs::write(&blocker, "mine").unwrap();
    let out = blocker.join(OsStr::from_bytes(b"\xfe-report"));
    refused_at_once(&[os("report"), os("--out"), out.as_os_str()], &["is a regular file, not a directory"]);
    assert_eq!(std::fs::read(&blocker).unwrap(), b"mine");
}

#[test]
fn special_files_are_never_opened_or_replaced() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("run.csv");
    if !mkfifo(&fifo) {
        eprintln!("mkfifo not available: nothing tested");
        return;
    }
    // simulate --out a FIFO: it used to be replaced by a regular file
    refused_at_once(&[os("simulate"), os("--out"), fifo.as_os_str()], &["is a FIFO"]);
    assert!(std::os::unix::fs::FileTypeExt::is_fifo(&std::fs::symlink_metadata(&fifo).unwrap().file_type()));
    // a FIFO as --config: never opened (opening it for reading would block)
    refused_at_once(&[os("config"), os("--config"), fifo.as_os_str()], &["FIFO"]);
    // a FIFO named manifest.json in a search directory: search used to hang on it
    let s = dir.path().join("s");
    std::fs::create_dir(&s).unwrap();
    assert!(mkfifo(&s.join("manifest.json")));
    let args = ["search", "--set", "horizon.t_end=0.05", "--over", "control.a=1,2", "--out"];
    let mut argv: Vec<&OsStr> = args.iter().map(|a| os(a)).collect();
    argv.push(s.as_os_str());
    refused_at_once(&argv, &["manifest.json", "FIFO"]);
    let names: Vec<_> = std::fs::read_dir(&s).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(names, vec![OsStr::new("manifest.json").to_owned()], "nothing else written");
}

#[test]
fn outputs_are_checked_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    // a name that fits NAME_MAX but not with the staging directory's suffix: certify used to
    // fail with "File name too long" after 3.6 s of arithmetic
    let long = dir.path().join("x".repeat(250));
    refused_at_once(&[os("certify"), os("--out"), long.as_os_str()], &["250 bytes long", "at most 215"]);
    refused_at_once(&[os("report"), os("--out"), long.as_os_str()], &["250 bytes long"]);
    // a symlinked --out: refused at once (3.3-3.6 s of work before), the target untouched
    let target = dir.path().join("target");
    std::fs::create_dir(&target).unwrap();
    std::fs::write(target.join("notes.txt"), "mine").unwrap();
    let link = dir.path().join("link");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    refused_at_once(&[os("certify"), os("--out"), link.as_os_str()], &["symbolic link"]);
    assert_eq!(std::fs::read_to_string(target.join("notes.txt")).unwrap(), "mine");
    assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
}

#[test]
fn schema_refuses_a_directory_it_did_not_write_and_rewrites_its_own() {
    let dir = tempfile::tempdir().unwrap();
    let mine = dir.path().join("mine");
    std::fs::create_dir(&mine).unwrap();
    std::fs::write(mine.join("config.schema.json"), "{\"mine\": 1}").unwrap();
    // it used to overwrite the user's config.schema.json silently
    refused_at_once(&[os("schema"), os("--out"), mine.as_os_str()], &["not a schema directory", ".wingcheck-schema"]);
    assert_eq!(std::fs::read_to_string(mine.join("config.schema.json")).unwrap(), "{\"mine\": 1}");
    // its own directory (with the marker) is written and rewritten, byte-identical
    let own = dir.path().join("own");
    let (o, _) = wingcheck(&[os("schema"), os("--out"), own.as_os_str()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let first = std::fs::read(own.join("config.schema.json")).unwrap();
    let (o, _) = wingcheck(&[os("schema"), os("--out"), own.as_os_str()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(std::fs::read(own.join("config.schema.json")).unwrap(), first);
}
