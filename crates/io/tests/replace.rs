//! Directory replacement never loses the previous result: fault-injected renames at every
//! step, simulated crashes (leftovers of a dead process) and foreign files.

use std::cell::Cell;
use std::collections::BTreeSet;
use std::path::Path;

use wingcheck_io::{only_listed_files, recover, write_file_atomic, DirOps, IoError, StagingDir, SystemOps};

/// Real file system, except: exchange reported unsupported if `no_exchange`, and the
/// `fail_at`-th rename (1-based) — and every later one if `fail_rest` — fails.
struct Faulty {
    no_exchange: bool,
    fail_at: usize,
    fail_rest: bool,
    calls: Cell<usize>,
}

impl DirOps for Faulty {
    fn exchange(&self, a: &Path, b: &Path) -> std::io::Result<bool> {
        if self.no_exchange {
            return Ok(false);
        }
        let k = self.calls.get() + 1;
        self.calls.set(k);
        if k == self.fail_at {
            return Err(std::io::Error::other("injected exchange failure"));
        }
        SystemOps.exchange(a, b)
    }
    fn rename(&self, from: &Path, to: &Path) -> std::io::Result<()> {
        let k = self.calls.get() + 1;
        self.calls.set(k);
        if k == self.fail_at || (self.fail_rest && k > self.fail_at) {
            return Err(std::io::Error::other("injected rename failure"));
        }
        std::fs::rename(from, to)
    }
}

fn make(dir: &Path, version: &str) {
    let s = StagingDir::new(dir).unwrap();
    for f in ["a.txt", "b.txt"] {
        s.write(f, format!("{version} {f}").as_bytes()).unwrap();
    }
    s.commit(|_| Ok(())).unwrap();
}

/// "old", "new" or a panic: the directory holds exactly one complete version.
fn version(dir: &Path) -> String {
    let a = std::fs::read_to_string(dir.join("a.txt")).expect("a.txt present");
    let b = std::fs::read_to_string(dir.join("b.txt")).expect("b.txt present");
    let (va, vb) = (a.split(' ').next().unwrap(), b.split(' ').next().unwrap());
    assert_eq!(va, vb, "mixed versions");
    let n = std::fs::read_dir(dir).unwrap().count();
    assert_eq!(n, 2, "exactly the report's files");
    va.to_string()
}

fn siblings(parent: &Path) -> Vec<String> {
    let mut v: Vec<String> =
        std::fs::read_dir(parent).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into()).collect();
    v.sort();
    v
}

fn allowed() -> BTreeSet<String> {
    ["a.txt", "b.txt"].into_iter().map(String::from).collect()
}

#[test]
fn every_injected_failure_leaves_the_old_or_the_new_directory() {
    for no_exchange in [false, true] {
        for fail_at in 1..=3 {
            let tmp = tempfile::tempdir().unwrap();
            let out = tmp.path().join("out");
            make(&out, "old");
            let s = StagingDir::new(&out).unwrap();
            s.write("a.txt", b"new a.txt").unwrap();
            s.write("b.txt", b"new b.txt").unwrap();
            let ops = Faulty { no_exchange, fail_at, fail_rest: false, calls: Cell::new(0) };
            let r = s.commit_with(|d| only_listed_files(d, &allowed()), &ops);
            let v = version(&out);
            match r {
                Ok(()) => assert_eq!(v, "new"),
                Err(e) => {
                    assert_eq!(v, "old", "failed commit must leave the old directory ({e})");
                    assert!(e.to_string().contains("injected"), "{e}");
                }
            }
            assert_eq!(siblings(tmp.path()), ["out"], "no staging or set-aside directory left");
        }
    }
}

#[test]
fn a_crash_inside_the_fallback_swap_is_repaired_by_the_next_run() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    make(&out, "old");
    // The state a kill between the fallback's two renames leaves: no `out`, the old directory
    // set aside under the name of a process that no longer exists, and its staging directory.
    let dead = 999_999_999u32; // above Linux's pid_max (4194304), so never a live process
    std::fs::rename(&out, tmp.path().join(format!(".out.wingcheck-old-{dead}-1"))).unwrap();
    std::fs::create_dir(tmp.path().join(format!(".out.wingcheck-staging-{dead}-2"))).unwrap();
    let touched = recover(&out);
    assert_eq!(touched.len(), 2, "{touched:?}");
    assert_eq!(version(&out), "old");
    assert_eq!(siblings(tmp.path()), ["out"]);
    // And when both renames fail in-process, the old one is put back or recovered next time.
    let s = StagingDir::new(&out).unwrap();
    s.write("a.txt", b"new a.txt").unwrap();
    s.write("b.txt", b"new b.txt").unwrap();
    let ops = Faulty { no_exchange: true, fail_at: 2, fail_rest: true, calls: Cell::new(0) };
    assert!(s.commit_with(|_| Ok(()), &ops).is_err());
    // The restore failed too: `out` is missing, the old directory is set aside under our pid.
    assert!(!out.exists());
    let aside: Vec<String> = siblings(tmp.path()).into_iter().filter(|n| n.contains("wingcheck-old")).collect();
    assert_eq!(aside.len(), 1);
    // Our process is alive, so recover() leaves it; once "dead" (renamed to a dead pid) it is restored.
    std::fs::rename(tmp.path().join(&aside[0]), tmp.path().join(format!(".out.wingcheck-old-{dead}-3"))).unwrap();
    recover(&out);
    assert_eq!(version(&out), "old");
}

#[test]
fn foreign_files_are_never_deleted() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    make(&out, "old");
    std::fs::create_dir(out.join("notes")).unwrap();
    std::fs::write(out.join("notes/mine.txt"), "keep me").unwrap();
    let s = StagingDir::new(&out).unwrap();
    s.write("a.txt", b"new a.txt").unwrap();
    let e = s.commit(|d| only_listed_files(d, &allowed())).unwrap_err();
    // the user's directory is named as a whole (no file of the set is in it)
    assert!(matches!(e, IoError::Foreign { .. }) && e.to_string().contains("notes/"), "{e}");
    assert_eq!(std::fs::read_to_string(out.join("notes/mine.txt")).unwrap(), "keep me");
    assert_eq!(std::fs::read_to_string(out.join("a.txt")).unwrap(), "old a.txt");
    assert_eq!(siblings(tmp.path()), ["out"]);
}

#[cfg(unix)]
#[test]
fn files_are_written_with_mode_0644() {
    use std::os::unix::fs::PermissionsExt;
    let tmp = tempfile::tempdir().unwrap();
    let p = tmp.path().join("f.json");
    write_file_atomic(&p, b"{}").unwrap();
    write_file_atomic(&p, b"{\"x\": 1}").unwrap();
    assert_eq!(std::fs::read(&p).unwrap(), b"{\"x\": 1}");
    assert_eq!(std::fs::metadata(&p).unwrap().permissions().mode() & 0o777, 0o644);
    let out = tmp.path().join("d");
    make(&out, "new");
    assert_eq!(std::fs::metadata(out.join("a.txt")).unwrap().permissions().mode() & 0o777, 0o644);
}

#[cfg(target_os = "linux")]
#[test]
fn exchange_is_atomic_where_supported() {
    // Prints (does not assert) whether this file system supports RENAME_EXCHANGE: the fallback
    // is tested above; on ext4/xfs/btrfs/tmpfs the exchange path is taken.
    let tmp = tempfile::tempdir().unwrap();
    let (a, b) = (tmp.path().join("a"), tmp.path().join("b"));
    std::fs::create_dir(&a).unwrap();
    std::fs::write(a.join("x"), "a").unwrap();
    std::fs::create_dir(&b).unwrap();
    let supported = SystemOps.exchange(&a, &b).unwrap();
    eprintln!("RENAME_EXCHANGE supported here: {supported}");
    if supported {
        assert!(b.join("x").is_file() && !a.join("x").exists());
    }
}

#[test]
fn empty_user_subdirectories_are_foreign() {
    // A directory holding only listed files passes; an empty subdirectory (a user's) does not,
    // and is named with a trailing slash (it used to pass the check and be deleted with the old
    // output); a subdirectory holding a listed file passes.
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    std::fs::create_dir_all(dir.join("figs")).unwrap();
    std::fs::write(dir.join("index.json"), "{}").unwrap();
    std::fs::write(dir.join("figs/a.svg"), "<svg/>").unwrap();
    let allowed: BTreeSet<String> = ["index.json", "figs/a.svg"].iter().map(|s| s.to_string()).collect();
    only_listed_files(&dir, &allowed).unwrap();
    std::fs::create_dir(dir.join("mine")).unwrap();
    let e = only_listed_files(&dir, &allowed).unwrap_err().to_string();
    assert!(e.contains("mine/") && e.contains("did not write"), "{e}");
    assert!(dir.join("mine").is_dir());
}
