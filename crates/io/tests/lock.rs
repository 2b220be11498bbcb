//! The writer-liveness check is a file lock (fs4): a process that holds its lock in a directory
//! is alive for [`owner_alive`] — tested with a real second process — and once it has ended,
//! however it ended (here: killed), its lock can be taken, so its files count as stale.

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use wingcheck_io::{lock_name, owner_alive, remove_stale_locks, DirLock};

const HELPER_DIR: &str = "WINGCHECK_LOCK_TEST_DIR";

/// This test binary run as a child for the helper test `name` alone, with `var` set to `dir`
/// (the helpers do nothing without it).
fn helper(name: &str, var: &str, dir: &std::path::Path, stdout: Stdio) -> std::process::Child {
    Command::new(std::env::current_exe().unwrap())
        .args(["--exact", name, "--nocapture", "--test-threads=1"])
        .env(var, dir)
        .stdout(stdout)
        .spawn()
        .unwrap()
}

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
    let mut child = helper("helper_holds_a_lock_until_killed", HELPER_DIR, dir.path(), Stdio::null());
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
    // Where there are no unnamed files (off Linux, or a file system without O_TMPFILE),
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

/// Run as a child (by `a_writer_killed_at_any_instant_leaves_only_removable_files`): take and
/// drop the lock in the directory without pause until killed.
#[test]
fn helper_takes_and_drops_the_lock_until_killed() {
    let Ok(dir) = std::env::var(SPIN_DIR) else { return };
    println!("spinning");
    loop {
        drop(DirLock::acquire(std::path::Path::new(&dir)).unwrap());
    }
}

const SPIN_DIR: &str = "WINGCHECK_LOCK_SPIN_DIR";

/// On Linux the lock file is born locked and unnamed (`O_TMPFILE`) and then linked to its
/// name, so a kill at any instant leaves nothing a later run must keep: every kill below is
/// followed by `remove_stale_locks`, which must empty the directory at once. (With a staging
/// name, a kill between creation and rename left `.wingcheck-lock-XXXXXX`, kept for 10 s: in
/// the search resume test that was 4 of 12 loaded runs.)
#[cfg(target_os = "linux")]
#[test]
fn a_writer_killed_at_any_instant_leaves_only_removable_files() {
    use std::io::BufRead;
    for round in 0..24u64 {
        let dir = tempfile::tempdir().unwrap();
        let mut child = helper("helper_takes_and_drops_the_lock_until_killed", SPIN_DIR, dir.path(), Stdio::piped());
        let mut line = String::new();
        let mut out = std::io::BufReader::new(child.stdout.take().unwrap());
        while !line.contains("spinning") {
            line.clear();
            assert!(out.read_line(&mut line).unwrap() > 0, "the helper ended before spinning");
        }
        std::thread::sleep(Duration::from_micros(200 + 150 * round));
        child.kill().unwrap();
        child.wait().unwrap();
        remove_stale_locks(dir.path());
        let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
        assert!(left.is_empty(), "round {round}: a killed writer left {left:?}");
    }
}

#[test]
fn a_dead_processs_lock_file_under_this_pid_is_replaced_by_a_held_one() {
    use fs4::FileExt;
    let dir = tempfile::tempdir().unwrap();
    let lock = dir.path().join(lock_name(std::process::id()));
    std::fs::write(&lock, "left by an earlier process with this pid").unwrap();
    let held = DirLock::acquire(dir.path()).unwrap();
    // another open file description of the lock file cannot take it: it is held
    let other = std::fs::File::open(&lock).unwrap();
    assert!(matches!(FileExt::try_lock(&other), Err(fs4::TryLockError::WouldBlock)));
    drop(held);
    assert!(!lock.exists());
}
