//! Determinism: merged shards, interrupted-and-resumed runs and different thread counts all
//! give byte-identical result files.

use std::path::Path;

use wingcheck_model::{apply_overrides, Config};
use wingcheck_search::{merge, run, RunControl, Search, SearchError, SearchOptions, Shard};

/// Files that must be identical (timings.csv and progress files hold wall times).
const FILES: [&str; 8] = [
    "manifest.json",
    "results.csv",
    "results.json",
    "best.json",
    "boundary.csv",
    "heatmap-rms_q_tip_m.svg",
    "heatmap-rms_theta_tip_rad.svg",
    "heatmap-settling_time_s.svg",
];

/// 3 × 4 grid over (a, b) crossing both theory boundaries, 0.3-s horizon, chunks of 2
/// (6 chunks), with refinement.
fn search() -> Search {
    let base = apply_overrides(&Config::paper(), &["horizon.t_end=0.3".into()]).unwrap();
    Search::new(
        base,
        &["control.a=1e-4..1:log:3".into(), "control.b=0.5,1,2,4".into()],
        SearchOptions { chunk_size: 2, refine: Some(1e-3), ..Default::default() },
    )
    .unwrap()
}

fn assert_same(a: &Path, b: &Path) {
    for f in FILES {
        let x = std::fs::read(a.join(f)).unwrap_or_else(|e| panic!("{f} in {}: {e}", a.display()));
        let y = std::fs::read(b.join(f)).unwrap_or_else(|e| panic!("{f} in {}: {e}", b.display()));
        assert!(x == y, "{f} differs between {} and {}", a.display(), b.display());
    }
}

fn pool(n: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new().num_threads(n).build().unwrap()
}

#[test]
fn shards_merge_resume_and_threads_agree() {
    let s = search();
    assert_eq!(s.chunks(), 6);
    let root = tempfile::tempdir().unwrap();
    let single = root.path().join("single");
    let sum = pool(2).install(|| run(&s, &single, RunControl::default())).unwrap();
    assert!(sum.complete && sum.evaluated == 12 && sum.skipped == 0);

    // 1 thread: a local pool, and RunControl::threads
    let one = root.path().join("one-thread");
    pool(1).install(|| run(&s, &one, RunControl::default())).unwrap();
    assert_same(&single, &one);
    let one_b = root.path().join("one-thread-option");
    run(&s, &one_b, RunControl { threads: Some(1), ..Default::default() }).unwrap();
    assert_same(&single, &one_b);

    // three shards in separate directories, merged
    let mut dirs = Vec::new();
    for k in 1..=3 {
        let d = root.path().join(format!("shard{k}"));
        let sum = run(&s, &d, RunControl { shard: Shard { k, n: 3 }, ..Default::default() }).unwrap();
        assert!(!sum.complete, "a single shard does not hold every chunk");
        assert_eq!(sum.evaluated, 4, "2 chunks of 2 points per shard");
        dirs.push(d);
    }
    let merged = root.path().join("merged");
    // merging an incomplete set is an error naming the missing chunks
    match merge(&dirs[..2], &merged) {
        Err(SearchError::MissingChunks { missing, total, first }) => {
            assert_eq!((missing, total, first), (2, 6, vec![2, 5]));
        }
        other => panic!("expected MissingChunks, got {other:?}"),
    }
    let m = merge(&dirs, &merged).unwrap();
    assert!(m.complete);
    assert_same(&single, &merged);

    // interrupted after 2 chunks, then restarted
    let resumed = root.path().join("resumed");
    let first = run(&s, &resumed, RunControl { stop_after_chunks: Some(2), ..Default::default() }).unwrap();
    assert!(!first.complete && first.evaluated == 4);
    assert!(!resumed.join("results.csv").exists());
    let second = run(&s, &resumed, RunControl::default()).unwrap();
    assert!(second.complete);
    assert_eq!((second.skipped, second.evaluated), (4, 8), "finished chunks are not recomputed");
    assert_same(&single, &resumed);

    // a different search in the same directory is refused
    let other = Search::new(
        s.base.clone(),
        &["control.a=1e-4..1:log:4".into(), "control.b=0.5,1,2,4".into()],
        SearchOptions { chunk_size: 2, refine: Some(1e-3), ..Default::default() },
    )
    .unwrap();
    assert!(matches!(run(&other, &single, RunControl::default()), Err(SearchError::Mismatch { .. })));
}

#[test]
fn result_files_have_the_documented_shape() {
    let s = search();
    let dir = tempfile::tempdir().unwrap();
    let seen = std::sync::Mutex::new(Vec::new());
    let progress = |p: wingcheck_search::Progress| seen.lock().unwrap().push((p.done, p.total));
    run(&s, dir.path(), RunControl { progress: Some(&progress), ..Default::default() }).unwrap();
    let mut seen = seen.into_inner().unwrap();
    seen.sort();
    assert_eq!(seen.first(), Some(&(0, 12)));
    assert_eq!(seen.last(), Some(&(12, 12)));

    let csv = std::fs::read_to_string(dir.path().join("results.csv")).unwrap();
    let mut lines = csv.lines();
    let head = lines.next().unwrap();
    // docs/outputs.md: axis keys as `section__key`, status columns, unit-suffixed metrics
    assert!(
        head.starts_with(
            "index,control__a,control__b,status,w_decided,w_positive_definite,feasible_32_decided,feasible_32,\
             theorem_feasible,settled,missing_metrics,lambda2_J_s,"
        ),
        "{head}"
    );
    assert!(head.ends_with(",energy_t_end_J,message"));
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), 12);
    // point 5 = (a index 1, b index 1): a = √(1e-4·1) = 0.01 up to rounding, b = 1
    assert!(rows[5].starts_with("5,0.01"), "{}", rows[5]);
    let cols = head.split(',').count();
    assert!(rows.iter().all(|r| r.split(',').count() == cols), "no commas inside ok rows' fields");
    assert!(rows.iter().all(|r| !r.ends_with(',')), "an ok point's message is `none`, not empty");

    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("results.json")).unwrap()).unwrap();
    assert_eq!(json["points"].as_array().unwrap().len(), 12);
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("manifest.json")).unwrap()).unwrap();
    assert_eq!(manifest["base_config_sha256"], wingcheck_claims::config_sha256(&s.base));
    assert_eq!(manifest["axis_specs"][1], "control.b=0.5,1,2,4");
    // the paper's base point (implicit FTDO): `auto` resolves to TR-BDF2
    assert_eq!(manifest["time_scheme"], "trbdf2");
    let svg = std::fs::read_to_string(dir.path().join("heatmap-rms_q_tip_m.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
}
