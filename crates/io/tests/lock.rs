//! The writer-liveness check is a file lock (fs4): a process that holds its lock in a directory
//! is alive for [`owner_alive`] — tested with a real second process — and once it has ended,
//! however it ended (here: killed), its lock can be taken, so its files count as stale.

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use wingcheck_io::{lock_name, owner_alive, remove_stale_locks, DirLock};

const HELPER_DIR: &str = "WINGCHECK_LOCK_TEST_DIR";

/// Run as a child (by `a_live_writer_is_alive_and_a_killed_one_is_not`): hold the lock in the
/// directory, say so on stdout, and sleep until killed.
#[test]
fn helper_holds_a_lock_until_killed() {
    let Ok(dir) = std::env::var(HELPER_DIR) else { return };
    let _lock = DirLock::acquire(std::path::Path::new(&dir)).unwrap();
    println!("locked");
    std::thread::sleep(Duration::from_secs(60));
}

#[test]
fn a_live_writer_is_alive_and_a_killed_one_is_not() {
    let dir = tempfile::tempdir().unwrap();
    let mut child = Command::new(std::env::current_exe().unwrap())
        .args(["--exact", "helper_holds_a_lock_until_killed", "--nocapture", "--test-threads=1"])
        .env(HELPER_DIR, dir.path())
        .stdout(Stdio::null())
        .spawn()
        .unwrap();
    let pid = child.id();
    let lock = dir.path().join(lock_name(pid));
    let start = Instant::now();
    while !lock.exists() {
        assert!(start.elapsed() < Duration::from_secs(30), "the helper did not take its lock");
        std::thread::sleep(Duration::from_millis(10));
    }
    assert!(owner_alive(dir.path(), pid), "a process holding its lock is alive");
    remove_stale_locks(dir.path());
    assert!(lock.exists(), "a live writer's lock file is kept");
    child.kill().unwrap();
    child.wait().unwrap();
    // killed: the lock file is left behind, but nobody holds it any more
    assert!(lock.exists());
    assert!(!owner_alive(dir.path(), pid), "a killed writer is not alive");
    remove_stale_locks(dir.path());
    assert!(!lock.exists(), "a dead writer's lock file is removed");
    // a pid without a lock file never wrote here (or is gone): not alive; this process always is
    assert!(!owner_alive(dir.path(), 999_999_999));
    assert!(owner_alive(dir.path(), std::process::id()));
}

#[test]
fn the_lock_is_shared_within_a_process_and_removed_with_its_last_holder() {
    let dir = tempfile::tempdir().unwrap();
    let lock = dir.path().join(lock_name(std::process::id()));
    let a = DirLock::acquire(dir.path()).unwrap();
    let b = DirLock::acquire(dir.path()).unwrap(); // a second thread's writer: no self-deadlock
    assert!(lock.exists());
    drop(a);
    assert!(lock.exists(), "still held by the second holder");
    drop(b);
    assert!(!lock.exists(), "removed with the last holder");
    let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert!(names.is_empty(), "nothing left behind: {names:?}");
}

#[test]
fn a_lock_file_killed_before_its_rename_counts_as_a_lock_and_goes_once_old() {
    // DirLock::acquire creates `.wingcheck-lock-XXXXXX`, locks it, renames it to lock_name(pid):
    // a kill in between leaves the temporary name, which is neither the user's file nor kept
    // forever
    let dir = tempfile::tempdir().unwrap();
    let staging = dir.path().join(".wingcheck-lock-Ab12Cd");
    std::fs::write(&staging, "").unwrap();
    assert!(wingcheck_io::is_lock_file(".wingcheck-lock-Ab12Cd"));
    assert!(wingcheck_io::is_lock_file(&lock_name(42)));
    assert!(!wingcheck_io::is_lock_file("wingcheck-lock-Ab12Cd"));
    // fresh: it may be another process's lock between creation and locking
    remove_stale_locks(dir.path());
    assert!(staging.exists(), "a fresh staging lock file is kept");
    let f = std::fs::File::options().write(true).open(&staging).unwrap();
    f.set_modified(std::time::SystemTime::now() - Duration::from_secs(60)).unwrap();
    drop(f);
    remove_stale_locks(dir.path());
    assert!(!staging.exists(), "an old unheld staging lock file is removed");
}
