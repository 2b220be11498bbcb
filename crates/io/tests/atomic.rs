//! The atomic writes: a create never overwrites, a set of files is not visible before its
//! commit (and a failed staging leaves no destination touched), the bytes land bit for bit,
//! and temp files of a dead writer are recognised and removed.

use std::path::Path;

use wingcheck_io::{create_file_atomic, is_temp, remove_stale_temps, write_file_atomic, FileSet, IoError};

/// Names in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().to_string()).collect();
    v.sort();
    v
}

/// Every byte value, and lengths around the buffer sizes: compared with what is read back.
fn awkward_bytes(len: usize) -> Vec<u8> {
    (0..len).map(|i| (i * 131 % 256) as u8).collect()
}

#[test]
fn a_create_refuses_an_existing_file_and_leaves_it_intact() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("manifest.json");
    create_file_atomic(&path, b"first").unwrap();
    let e = create_file_atomic(&path, b"second").unwrap_err();
    assert!(matches!(&e, IoError::Exists { path: p } if p == &path), "{e}");
    assert!(e.to_string().contains("manifest.json") && e.to_string().contains("already exists"), "{e}");
    assert_eq!(std::fs::read(&path).unwrap(), b"first");
    assert_eq!(names(dir.path()), ["manifest.json"], "no temp file or lock left");
}

#[test]
fn concurrent_creates_make_exactly_one_winner() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("m");
    let wins: usize = std::thread::scope(|s| {
        let runs: Vec<_> = (0..8u8)
            .map(|k| {
                let path = &path;
                s.spawn(move || create_file_atomic(path, &[k; 64]).is_ok())
            })
            .collect();
        runs.into_iter().map(|h| usize::from(h.join().unwrap())).sum()
    });
    assert_eq!(wins, 1);
    let got = std::fs::read(&path).unwrap();
    assert!(got.len() == 64 && got.iter().all(|&b| b == got[0]), "one writer's bytes, whole");
    assert_eq!(names(dir.path()), ["m"]);
}

#[test]
fn writes_are_bit_identical_and_mode_0644() {
    let dir = tempfile::tempdir().unwrap();
    for len in [0, 1, 8191, 8192, 8193, 100_000] {
        let bytes = awkward_bytes(len);
        let (a, b, c) = (dir.path().join("a"), dir.path().join("b"), dir.path().join("c"));
        write_file_atomic(&a, &bytes).unwrap();
        let _ = std::fs::remove_file(&b);
        create_file_atomic(&b, &bytes).unwrap();
        let mut set = FileSet::new();
        let mut f = set.open(&c).unwrap();
        for piece in bytes.chunks(777) {
            f.write(piece).unwrap();
        }
        f.finish().unwrap();
        set.commit().unwrap();
        for p in [&a, &b, &c] {
            assert_eq!(std::fs::read(p).unwrap(), bytes, "{} at {len} bytes", p.display());
            #[cfg(unix)]
            {
                use std::os::unix::fs::PermissionsExt;
                assert_eq!(std::fs::metadata(p).unwrap().permissions().mode() & 0o777, 0o644);
            }
        }
    }
    assert_eq!(names(dir.path()), ["a", "b", "c"]);
}

#[test]
fn a_set_is_invisible_until_committed_and_replaces_old_files() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.csv"), dir.path().join("sub").join("b.json"));
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    std::fs::write(&a, "old a").unwrap();
    let mut set = FileSet::new();
    set.add(&a, b"new a").unwrap();
    set.add(&b, b"new b").unwrap();
    assert_eq!(std::fs::read(&a).unwrap(), b"old a", "staged, not yet committed");
    assert!(!b.exists());
    assert_eq!(set.commit().unwrap(), [a.clone(), b.clone()]);
    assert_eq!(std::fs::read(&a).unwrap(), b"new a");
    assert_eq!(std::fs::read(&b).unwrap(), b"new b");
    assert_eq!(names(dir.path()), ["a.csv", "sub"]);
    assert_eq!(names(&dir.path().join("sub")), ["b.json"]);
}

#[test]
fn a_set_whose_second_directory_is_missing_leaves_the_first_file_untouched() {
    let dir = tempfile::tempdir().unwrap();
    let first = dir.path().join("chunk");
    std::fs::write(&first, "old").unwrap();
    let mut set = FileSet::new();
    set.add(&first, b"new").unwrap();
    let e = set.add(&dir.path().join("missing").join("progress.json"), b"p").unwrap_err();
    assert!(e.to_string().contains("missing"), "the error names the path: {e}");
    drop(set);
    assert_eq!(std::fs::read(&first).unwrap(), b"old", "no destination was touched");
    assert_eq!(names(dir.path()), ["chunk"], "the first file's temp file is removed");
}

#[test]
fn a_set_refuses_a_destination_that_is_not_a_regular_file_before_renaming_any() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a"), dir.path().join("b"));
    let mut set = FileSet::new();
    set.add(&a, b"a").unwrap();
    set.add(&b, b"b").unwrap();
    std::fs::create_dir(&b).unwrap(); // appears between staging and commit
    assert!(set.commit().is_err());
    assert!(!a.exists(), "nothing renamed");
    assert_eq!(names(dir.path()), ["b"]);
}

#[test]
fn a_failed_write_leaves_the_old_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("x");
    std::fs::write(&path, "old").unwrap();
    // the directory of a path that is a file: the temp file cannot be made
    let e = write_file_atomic(&path.join("y"), b"new").unwrap_err();
    assert!(matches!(e, IoError::Io { .. } | IoError::BadOutput { .. }), "{e}");
    assert_eq!(std::fs::read(&path).unwrap(), b"old");
    assert_eq!(names(dir.path()), ["x"]);
}

#[test]
fn temp_files_of_a_dead_writer_are_removed_and_those_of_this_process_kept() {
    let dir = tempfile::tempdir().unwrap();
    // a pid no process has (checked in /proc where there is one)
    let dead = (1_000_000..4_000_000u32).rev().find(|p| !Path::new(&format!("/proc/{p}")).exists()).unwrap();
    let me = std::process::id();
    let names_in = [
        format!(".a.tmp-{dead}"),
        format!(".a.tmp-{dead}-7"),
        format!(".b.set-tmp-{dead}"),
        format!(".c.tmp-{me}-3"),
        "keep.tmp-1".to_string(),
        ".d.tmp-x".to_string(),
    ];
    for n in &names_in {
        std::fs::write(dir.path().join(n), "partial").unwrap();
    }
    assert!(names_in[..4].iter().all(|n| is_temp(n)));
    assert!(!is_temp("keep.tmp-1") && !is_temp(".d.tmp-x") && !is_temp("results.csv"));
    remove_stale_temps(dir.path());
    assert_eq!(names(dir.path()), [format!(".c.tmp-{me}-3"), ".d.tmp-x".into(), "keep.tmp-1".into()]);
}
