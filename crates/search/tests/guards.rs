//! Work guards and output-directory rules: refused before any work, nothing left behind.

use std::path::Path;

use wingcheck_model::{apply_overrides, Config};
use wingcheck_search::{merge, run, RunControl, Search, SearchError, SearchOptions, Shard, MAX_POINTS};

fn base() -> Config {
    apply_overrides(&Config::paper(), &["horizon.t_end=0.05".into()]).unwrap()
}

fn search(specs: &[&str]) -> Result<Search, SearchError> {
    Search::new(base(), &specs.iter().map(|s| s.to_string()).collect::<Vec<_>>(), SearchOptions::default())
}

#[test]
fn huge_grids_are_refused_with_the_estimate_and_the_flag() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("huge");
    // three lin:100000 axes: 1e15 points, refused even with the override, nothing created
    let s = search(&["control.a=1..2:lin:100000", "control.b=1..2:lin:100000", "control.k1=1..2:lin:100000"]).unwrap();
    let e = run(&s, &out, RunControl { allow_large: true, ..Default::default() }).unwrap_err();
    assert!(matches!(e, SearchError::TooLarge { .. }) && e.to_string().contains("1000000000000000 points"), "{e}");
    assert!(!out.exists());
    // one lin:1000000 axis at the paper's horizon: above the default limits, names the flag
    let s = Search::new(Config::paper(), &["control.a=1..2:lin:1000000".into()], SearchOptions::default()).unwrap();
    let e = run(&s, &out, RunControl::default()).unwrap_err();
    let msg = e.to_string();
    assert!(msg.contains("--allow-large") && msg.contains("core-hours") && msg.contains("1000000 points"), "{msg}");
    assert!(!out.exists());
    assert!(s.points() == MAX_POINTS); // the limit itself: refused on the core-time estimate
}

#[test]
fn threads_are_bounded() {
    let dir = tempfile::tempdir().unwrap();
    let s = search(&["control.a=1,2"]).unwrap();
    for n in [0, 10_000] {
        let e = run(&s, &dir.path().join("t"), RunControl { threads: Some(n), ..Default::default() }).unwrap_err();
        assert!(e.to_string().contains("--threads"), "{e}");
    }
}

#[test]
fn unrepresentable_values_and_windows_outside_the_horizon_are_refused() {
    for spec in ["control.a=1e-400..1:log:3", "control.a=1e-400,1", "control.a=-1e-320..1:lin:2"] {
        let e = search(&[spec]).unwrap_err();
        assert!(e.to_string().contains("smallest normal f64"), "{spec}: {e}");
    }
    let specs = vec!["control.a=1,2".to_string()];
    for w in [(25.0, 30.0), (0.02, 0.06), (0.03, 0.01), (-1.0, 0.01), (0.011, 0.019)] {
        let o = SearchOptions { window: Some(w), ..Default::default() };
        let e = Search::new(base(), &specs, o).unwrap_err();
        assert!(e.to_string().contains("--window"), "{w:?}: {e}");
    }
    // inside, with samples (every 0.01 s): accepted
    let o = SearchOptions { window: Some((0.01, 0.05)), ..Default::default() };
    assert!(Search::new(base(), &specs, o).is_ok());
}

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    v.sort();
    v
}

#[test]
fn directories_that_are_not_a_search_are_refused_and_failures_leave_nothing() {
    let root = tempfile::tempdir().unwrap();
    let s = Search::new(base(), &["control.a=1,2,3,4".into()], SearchOptions { chunk_size: 1, ..Default::default() })
        .unwrap();
    // a directory with a user's file: refused, untouched
    let user = root.path().join("user");
    std::fs::create_dir(&user).unwrap();
    std::fs::write(user.join("notes.txt"), "mine").unwrap();
    let e = run(&s, &user, RunControl::default()).unwrap_err();
    assert!(e.to_string().contains("not a wingcheck search directory"), "{e}");
    assert_eq!(names(&user), ["notes.txt"]);
    // merge into it: refused too
    let shard = root.path().join("shard1");
    run(&s, &shard, RunControl { shard: Shard { k: 1, n: 2 }, ..Default::default() }).unwrap();
    let other = root.path().join("shard2");
    run(&s, &other, RunControl { shard: Shard { k: 2, n: 2 }, ..Default::default() }).unwrap();
    let e = merge(&[shard.clone(), other.clone()], &user).unwrap_err();
    assert!(e.to_string().contains("not a wingcheck search directory"), "{e}");
    assert_eq!(names(&user), ["notes.txt"]);
    // merge with a shard missing: an error, and no output directory at all
    let out = root.path().join("merged");
    let e = merge(std::slice::from_ref(&shard), &out).unwrap_err();
    assert!(matches!(e, SearchError::MissingChunks { missing: 2, total: 4, .. }), "{e}");
    assert!(!out.exists());
    // an empty directory is accepted
    let empty = root.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    let sum = merge(&[shard, other], &empty).unwrap();
    assert!(sum.complete && empty.join("results.csv").exists());
}

#[test]
fn a_failed_write_of_the_final_files_leaves_no_partial_result_set() {
    let root = tempfile::tempdir().unwrap();
    let s = Search::new(base(), &["control.a=1,2".into()], SearchOptions::default()).unwrap();
    let dir = root.path().join("s");
    // a complete run, its final files then removed: finalising has everything it needs
    run(&s, &dir, RunControl::default()).unwrap();
    for n in names(&dir) {
        if n != "manifest.json" && n != "chunks" {
            std::fs::remove_file(dir.join(n)).unwrap();
        }
    }
    // Fault injection (works as root too, unlike a read-only directory): the staging name of
    // the second file, results.json, is taken by a directory, so writing it fails after
    // results.csv has been staged — as a full disk would.
    let blocker = format!(".results.json.set-tmp-{}", std::process::id());
    std::fs::create_dir(dir.join(&blocker)).unwrap();
    let e = wingcheck_search::finalize(&dir).unwrap_err();
    // the error names the full path (it used to name only the file)
    assert!(e.to_string().contains(&dir.join("results.json").display().to_string()), "{e}");
    assert_eq!(names(&dir), [blocker.as_str(), "chunks", "manifest.json"], "no final file and no temp file left");
    std::fs::remove_dir(dir.join(&blocker)).unwrap();
    assert!(wingcheck_search::finalize(&dir).is_ok());
}

#[test]
fn the_estimate_takes_the_costliest_value_of_each_axis() {
    // paper horizon 20 s: dt = 1e-4 gives 200 000 steps (observer sample 1 ms = 10 steps);
    // 32 FE elements give 96 unknowns (3 per element)
    let specs = vec!["discretisation.dt=1e-3,1e-4".to_string(), "discretisation.elements=16,32".to_string()];
    let s = Search::new(Config::paper(), &specs, SearchOptions::default()).unwrap();
    let w = s.estimate();
    assert_eq!((w.points, w.steps_per_point, w.unknowns), (4, 200_000, 96));
    // every point is charged the costliest corner (dt = 1e-4 and 32 elements): 4 × that
    // corner's single-point estimate
    let corner = Search::new(
        apply_overrides(&Config::paper(), &["discretisation.dt=1e-4".into(), "discretisation.elements=32".into()])
            .unwrap(),
        &["control.a=1".into()],
        SearchOptions::default(),
    )
    .unwrap()
    .estimate();
    assert_eq!(w.point_seconds, corner.point_seconds, "{w:?} vs {corner:?}");
    assert!(w.core_seconds >= 4.0 * corner.point_seconds, "{w:?} vs {corner:?}");
}

#[test]
fn memory_is_estimated_and_every_value_of_a_list_axis_counts() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("s");
    // t_end = 1e5 s at dt = 1 ms: 1e8 steps, whose observer signal is 3 f64 per step (2.4 GB)
    // plus 6 f64 per observer sample k = 0..=1e8 (4.8 GB: ĝ, σ, g of both channels), and the
    // point's trace of 7 f64 at 1e7 + 1 output samples (0.56 GB): above the 4 GiB limit, refused
    // before any work (it used to run and reach 2.2 GB RSS while `simulate` refused the same
    // horizon; the estimate counted 4 f64 per sample, issue 46).
    let long = apply_overrides(&Config::paper(), &["horizon.t_end=1e5".into()]).unwrap();
    let s = Search::new(long, &["control.a=1".into()], SearchOptions::default()).unwrap();
    let w = s.estimate_with_threads(1);
    assert_eq!(w.memory.signal_bytes, 24.0 * 1e8 + 48.0 * (1e8 + 1.0), "{w:?}");
    assert_eq!(w.memory.signals, 1.0, "one signal, whatever the threads: {w:?}");
    assert!(w.memory.per_thread >= 56.0 * (1e7 + 1.0), "{w:?}");
    assert!(w.memory_bytes > 7.7e9 && w.memory_bytes < 7.9e9, "{w:?}");
    let e = run(&s, &out, RunControl::default()).unwrap_err().to_string();
    assert!(e.contains("GiB of memory") && e.contains("--allow-large"), "{e}");
    assert!(!out.exists());
    // one costly value listed last in a list of 300: counted (the estimate read only the first
    // 256 values). 0.05 s is 50 steps; 1e5 s is 1e8.
    let mut values = vec!["0.05"; 299];
    values.push("1e5");
    let spec = format!("horizon.t_end={}", values.join(","));
    let s = Search::new(base(), &[spec], SearchOptions::default()).unwrap();
    let w = s.estimate_with_threads(1);
    assert_eq!(w.steps_per_point, 100_000_000, "{w:?}");
    let e = run(&s, &out, RunControl::default()).unwrap_err().to_string();
    assert!(e.contains("--allow-large"), "{e}");
    assert!(!out.exists());
    // a list over a key the cost does not depend on is estimated from one value
    let many: Vec<String> = (1..=300).map(|k| format!("{k}")).collect();
    let s = Search::new(base(), &[format!("control.a={}", many.join(","))], SearchOptions::default()).unwrap();
    assert_eq!(s.estimate().steps_per_point, 50);
}

/// `merge` recomputes chunks' points ([`wingcheck_search::verify`]): one per chunk by default,
/// all with `--verify-chunks`. That work is the search's, guarded by the search's estimate
/// before any chunk is read: a directory of a search above the memory limit (started with
/// `--allow-large`) is refused unless the merge is given it too.
#[test]
fn merge_recomputation_is_guarded_by_the_searchs_estimate() {
    use wingcheck_search::{merge_with, ChunkCheck};
    let dir = tempfile::tempdir().unwrap();
    let (shard, out) = (dir.path().join("shard"), dir.path().join("merged"));
    // t_end = 1e5 s: 7.8 GB (memory_is_estimated_and_every_value_of_a_list_axis_counts); the run
    // stops before its first chunk, leaving the manifest only
    let long = apply_overrides(&Config::paper(), &["horizon.t_end=1e5".into()]).unwrap();
    let s = Search::new(long, &["control.a=1".into()], SearchOptions::default()).unwrap();
    run(&s, &shard, RunControl { allow_large: true, stop_after_chunks: Some(0), ..Default::default() }).unwrap();
    for check in [ChunkCheck::Sample, ChunkCheck::All] {
        let start = std::time::Instant::now();
        let e = merge_with(std::slice::from_ref(&shard), &out, check, false).unwrap_err().to_string();
        assert!(e.contains("GiB of memory") && e.contains("--allow-large") && e.contains("1 points"), "{e}");
        assert!(start.elapsed().as_secs_f64() < 2.0, "refused before any work: {:?}", start.elapsed());
        assert!(!out.exists());
    }
    // allowed, the merge goes on to find the chunk missing (nothing recomputed, nothing written)
    let e = merge_with(std::slice::from_ref(&shard), &out, ChunkCheck::All, true).unwrap_err();
    assert!(matches!(e, SearchError::MissingChunks { .. }), "{e}");
    assert!(!out.exists());
}
