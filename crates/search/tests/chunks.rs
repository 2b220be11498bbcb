//! Chunks carry their search's identity and a digest (issue 25, class 5): resume, merge and
//! assembly refuse a chunk of another search (same axes, another base config), one of another
//! tool version, an edited one (whether or not the forger re-hashed it), off-grid values and
//! metrics that are not finite — naming the file, merging nothing and losing nothing.

use std::path::{Path, PathBuf};

use serde_json::Value;
use wingcheck_model::{apply_overrides, Config};
use wingcheck_search::chunk::sha256_hex;
use wingcheck_search::{merge, run, store, RunControl, Search, SearchOptions, Shard};

fn search(sets: &[&str]) -> Search {
    let mut all = vec!["horizon.t_end=0.05".to_string()];
    all.extend(sets.iter().map(|s| s.to_string()));
    let base = apply_overrides(&Config::paper(), &all).unwrap();
    Search::new(base, &["control.a=1,2,3,4".into()], SearchOptions { chunk_size: 2, ..Default::default() }).unwrap()
}

/// Shard 1 of 2 (chunk 0) and shard 2 of 2 (chunk 1) of `s` under `root`.
fn shards(s: &Search, root: &Path) -> (PathBuf, PathBuf) {
    let (a, b) = (root.join("shard1"), root.join("shard2"));
    run(s, &a, RunControl { shard: Shard { k: 1, n: 2 }, ..Default::default() }).unwrap();
    run(s, &b, RunControl { shard: Shard { k: 2, n: 2 }, ..Default::default() }).unwrap();
    (a, b)
}

/// Rewrite chunk `c` in `dir`: `edit` changes the point lines (as JSON values); with `rehash`
/// the header's digest is recomputed, as a forger who knows the format would.
fn tamper(dir: &Path, c: usize, rehash: bool, edit: impl Fn(&mut Value)) {
    let path = store::chunk_path(dir, c);
    let text = std::fs::read_to_string(&path).unwrap();
    let (head, body) = text.split_once('\n').unwrap();
    let mut lines: Vec<Value> = body.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    lines.iter_mut().for_each(&edit);
    let body: String = lines.iter().map(|l| serde_json::to_string(l).unwrap() + "\n").collect();
    let mut header: Value = serde_json::from_str(head).unwrap();
    if rehash {
        header["sha256"] = sha256_hex(body.as_bytes()).into();
    }
    std::fs::write(&path, serde_json::to_string(&header).unwrap() + "\n" + &body).unwrap();
}

/// Whether the forger re-hashes, the edit of every point line, what the refusal must mention.
type Tamper = (bool, fn(&mut Value), &'static str);

fn refused_merge(dirs: &[PathBuf], out: &Path, mentions: &[&str]) {
    let e = merge(dirs, out).unwrap_err().to_string();
    for m in mentions {
        assert!(e.contains(m), "{m:?} missing: {e}");
    }
    assert!(!out.exists(), "a refused merge left {}", out.display());
}

#[test]
fn a_chunk_of_another_search_is_refused_by_merge_and_resume() {
    let root = tempfile::tempdir().unwrap();
    let ours = search(&[]);
    let (a, b) = shards(&ours, root.path());
    // the same axes and chunking over another base config (ξ = 0.3): its chunk 1 put in place
    // of ours (it used to merge with exit 0 and print its points into results.csv)
    let theirs = search(&["wing.xi=0.3"]);
    let other = root.path().join("other");
    run(&theirs, &other, RunControl::default()).unwrap();
    std::fs::copy(store::chunk_path(&other, 1), store::chunk_path(&b, 1)).unwrap();
    let out = root.path().join("merged");
    refused_merge(&[a.clone(), b.clone()], &out, &["chunk-00001.jsonl", "another search"]);
    // resuming shard 2 refuses it too, and keeps it (nothing is recomputed over it)
    let e = run(&ours, &b, RunControl { shard: Shard { k: 2, n: 2 }, ..Default::default() }).unwrap_err();
    assert!(e.to_string().contains("another search"), "{e}");
    assert!(store::chunk_path(&b, 1).exists());
    // a chunk of another tool version
    run(&ours, &b, RunControl::default()).unwrap_err(); // still the foreign chunk 1
    let good = root.path().join("good");
    run(&ours, &good, RunControl::default()).unwrap();
    let path = store::chunk_path(&good, 0);
    let text =
        std::fs::read_to_string(&path).unwrap().replacen("\"tool\":\"wingcheck ", "\"tool\":\"wingcheck 0.0.0-", 1);
    std::fs::write(&path, text).unwrap();
    let e = wingcheck_search::finalize(&good).unwrap_err().to_string();
    assert!(e.contains("written by wingcheck 0.0.0-"), "{e}");
}

#[test]
fn edited_chunks_off_grid_values_and_non_finite_metrics_are_refused() {
    let root = tempfile::tempdir().unwrap();
    let ours = search(&[]);
    let (a, b) = shards(&ours, root.path());
    let out = root.path().join("merged");
    let cases: [Tamper; 5] = [
        (false, |l| l["status"] = "diverged".into(), "do not hash"),
        (true, |l| l["values"][0] = "3.5".into(), "the grid has"),
        (true, |l| l["metrics"][9] = "NaN".into(), "metric rms_q_tip_m = \"NaN\" is not a finite number"),
        (true, |l| l["metrics"][0] = "inf".into(), "metric lambda2_Wu = \"inf\" is not a finite number"),
        (true, |l| l["message"] = "".into(), "status"),
    ];
    for (rehash, edit, mention) in cases {
        let dir = root.path().join("edited");
        let _ = std::fs::remove_dir_all(&dir);
        copy_dir(&b, &dir);
        tamper(&dir, 1, rehash, |l| {
            if mention == "status" {
                l["status"] = "error".into();
            }
            edit(l)
        });
        refused_merge(&[a.clone(), dir.clone()], &out, &["chunk-00001.jsonl", mention]);
    }
    // the untouched shards still merge
    assert!(merge(&[a, b], &out).unwrap().complete);
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to.join(store::CHUNK_DIR)).unwrap();
    std::fs::copy(from.join("manifest.json"), to.join("manifest.json")).unwrap();
    for e in std::fs::read_dir(from.join(store::CHUNK_DIR)).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), to.join(store::CHUNK_DIR).join(e.file_name())).unwrap();
    }
}
