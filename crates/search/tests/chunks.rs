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
        (true, |l| l["metrics"][0] = "inf".into(), "metric lambda2_J_s = \"inf\" is not a finite number"),
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

/// Issue 46, item 4: an edit that was re-hashed (the point lines' SHA-256 recomputed, as a forger
/// who knows the format would) is caught by recomputing the chunk's points: every point with
/// `ChunkCheck::All` (`--verify-chunks`), one chosen at random per chunk by default — so an edit
/// of every point of a chunk is always caught, and a single edited point with probability
/// 1/(points per chunk) per run. Nothing is merged or resumed from a refused chunk.
#[test]
fn an_edited_and_rehashed_chunk_is_caught_by_recomputing_its_points() {
    use wingcheck_search::{merge_with, ChunkCheck};
    let root = tempfile::tempdir().unwrap();
    let ours = search(&[]);
    let (a, b) = shards(&ours, root.path());
    let out = root.path().join("merged");
    // every point's lambda2 changed (0.032 → 0.5 in the reproduction): the default check
    let dir = root.path().join("all-edited");
    copy_dir(&b, &dir);
    tamper(&dir, 1, true, |l| l["metrics"][0] = "0.5".into());
    // the first metric, λ2, named by its results.csv column
    let edited = format!("{} = 0.5", wingcheck_search::METRICS[0]);
    refused_merge(&[a.clone(), dir.clone()], &out, &["chunk-00001.jsonl", "recomputes differently", &edited]);
    // resuming the edited shard refuses it too, before any work, and keeps it
    let before = std::fs::read(store::chunk_path(&dir, 1)).unwrap();
    let e = run(&ours, &dir, RunControl { shard: Shard { k: 2, n: 2 }, ..Default::default() }).unwrap_err();
    assert!(e.to_string().contains("recomputes differently"), "{e}");
    assert_eq!(std::fs::read(store::chunk_path(&dir, 1)).unwrap(), before, "the chunk is kept as it was");
    // one point of two edited: --verify-chunks always catches it, in a merge and in a resume
    let one = root.path().join("one-edited");
    copy_dir(&b, &one);
    let path = store::chunk_path(&one, 1);
    let text = std::fs::read_to_string(&path).unwrap();
    let (head, body) = text.split_once('\n').unwrap();
    let mut lines: Vec<Value> = body.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    lines[1]["metrics"][0] = "0.5".into();
    let body: String = lines.iter().map(|l| serde_json::to_string(l).unwrap() + "\n").collect();
    let mut header: Value = serde_json::from_str(head).unwrap();
    header["sha256"] = sha256_hex(body.as_bytes()).into();
    std::fs::write(&path, serde_json::to_string(&header).unwrap() + "\n" + &body).unwrap();
    let e = merge_with(&[a.clone(), one.clone()], &out, ChunkCheck::All, false).unwrap_err().to_string();
    assert!(e.contains("point 3 recomputes differently") && e.contains(&edited), "{e}");
    assert!(!out.exists());
    let ctl = RunControl { shard: Shard { k: 2, n: 2 }, verify: ChunkCheck::All, ..Default::default() };
    assert!(run(&ours, &one, ctl).unwrap_err().to_string().contains("point 3 recomputes differently"));
    // the default check recomputes one point per chunk; over runs it picks both (a fresh random
    // choice each time), so the edit is caught by some of 40 merges (escape 2^-40)
    let caught = (0..40)
        .filter(|_| {
            let r = merge_with(&[a.clone(), one.clone()], &out, ChunkCheck::Sample, false);
            let _ = std::fs::remove_dir_all(&out);
            r.is_err_and(|e| e.to_string().contains("point 3 recomputes differently"))
        })
        .count();
    assert!(caught > 0 && caught < 40, "caught {caught} of 40");
    // the untouched shards merge, every point recomputed the same, bit for bit
    let s = merge_with(&[a, b], &out, ChunkCheck::All, false).unwrap();
    assert!(s.complete && s.verified == 4, "{s:?}");
}

/// Issue 46, item 6: `progress-K-of-N.json` stayed at 4 of 5 chunks after a kill between a
/// chunk's write and its own, followed by a complete resume. The two are now written together,
/// and a run rewrites the file from the chunks it finds before any work.
#[test]
fn the_progress_file_counts_the_chunks_on_disk_after_a_resume() {
    let root = tempfile::tempdir().unwrap();
    let s = search(&[]);
    let dir = root.path().join("s");
    let progress = || -> Value {
        serde_json::from_str(&std::fs::read_to_string(dir.join("progress-1-of-1.json")).unwrap()).unwrap()
    };
    run(&s, &dir, RunControl { stop_after_chunks: Some(1), ..Default::default() }).unwrap();
    assert_eq!(progress()["chunks_completed"], 1, "written with its chunk");
    // a kill between the chunk's rename and the progress file's: one behind
    let stale = progress().to_string().replace("\"chunks_completed\":1", "\"chunks_completed\":0");
    std::fs::write(dir.join("progress-1-of-1.json"), stale).unwrap();
    assert_eq!(progress()["chunks_completed"], 0);
    assert!(run(&s, &dir, RunControl::default()).unwrap().complete);
    assert_eq!((progress()["chunks_completed"].clone(), progress()["chunks_owned"].clone()), (2.into(), 2.into()));
    // a complete directory rerun: the same count, from the chunks found
    std::fs::write(dir.join("progress-1-of-1.json"), "{}").unwrap();
    assert!(run(&s, &dir, RunControl::default()).unwrap().complete);
    assert_eq!(progress()["chunks_completed"], 2);
}
