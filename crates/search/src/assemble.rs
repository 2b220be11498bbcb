//! Assembling the final files of a complete search directory from its chunk files, streamed.
//!
//! The chunks are read one at a time in index order ([`ChunkStream`]); every point is written
//! to `results.csv`, `results.json`, `failures.csv` and `timings.csv` as it arrives and then
//! dropped. What outlives a point is bounded (see [`Assembly`]):
//!
//! - its two theory verdicts (2 bytes: `boundary.csv` compares grid neighbours along every
//!   axis, and the heatmaps draw the boundaries and the theorem-feasible cells);
//! - on 2-D searches, the three plotted metrics (3 × 16 bytes: the heatmaps need every cell);
//! - the `best_count` best points twice (overall and theorem-feasible) for `best.json`.
//!
//! So memory is O(chunk size + best count) plus 2 bytes per point (50 bytes per point on 2-D
//! searches, whose heatmap SVG texts, one at a time, grow with the number of cells too) —
//! instead of one full [`PointResult`] (≈ 4 kB with its output text) per point.

use std::path::Path;

use crate::metric::Metric;
use crate::point::{PointResult, PointVerdicts, Status};
use crate::refine::{boundaries, boundary_csv};
use crate::store::{self, BestPoints};
use crate::{heatmap_svg, Manifest, Search, SearchError, TheoryCache};
use wingcheck_io::{FileSet, StagedFile};

/// Metrics drawn as heatmaps on 2-D searches, with whether their colour scale is logarithmic.
pub const HEATMAPS: [(Metric, bool); 3] =
    [(Metric::RmsQTip, true), (Metric::RmsThetaTip, true), (Metric::SettlingTime, false)];

/// The points of a complete directory, read chunk by chunk in index order: at most one chunk's
/// points are in memory. A chunk missing or malformed (it was checked before) is an error.
pub struct ChunkStream<'a> {
    dir: &'a Path,
    search: &'a Search,
    next_chunk: usize,
    current: std::vec::IntoIter<PointResult>,
}

impl<'a> ChunkStream<'a> {
    /// Stream the points of `search` from the chunk files in `dir`.
    pub fn new(dir: &'a Path, search: &'a Search) -> ChunkStream<'a> {
        ChunkStream { dir, search, next_chunk: 0, current: Vec::new().into_iter() }
    }
}

impl Iterator for ChunkStream<'_> {
    type Item = Result<PointResult, SearchError>;

    fn next(&mut self) -> Option<Self::Item> {
        loop {
            if let Some(p) = self.current.next() {
                return Some(Ok(p));
            }
            let c = self.next_chunk;
            if c >= self.search.chunks() {
                return None;
            }
            self.next_chunk += 1;
            match store::read_chunk(self.dir, self.search, c) {
                Ok(Some(points)) => self.current = points.into_iter(),
                Ok(None) => {
                    self.next_chunk = self.search.chunks();
                    return Some(Err(SearchError::MissingChunks {
                        missing: 1,
                        total: self.search.chunks(),
                        first: vec![c],
                    }));
                }
                Err(e) => {
                    self.next_chunk = self.search.chunks();
                    return Some(Err(e));
                }
            }
        }
    }
}

/// What the assembly keeps of the points it has streamed (see the module doc), and the
/// per-point files it is writing.
pub struct Assembly {
    /// The verdicts of every point so far, in index order (2 bytes per point).
    pub verdicts: Vec<PointVerdicts>,
    /// On 2-D searches: the values of [`HEATMAPS`] of every point so far, in index order.
    pub heat: Option<[Vec<Option<f64>>; 3]>,
    /// The best points for `best.json`.
    pub best: BestPoints,
    /// Points diverged, points with an error.
    pub failed: (usize, usize),
    csv: StagedFile,
    failures: StagedFile,
    timings: StagedFile,
}

impl Assembly {
    /// Take in the next point (index order): write its rows and keep its bounded summary.
    pub fn add(&mut self, p: &PointResult) -> Result<(), SearchError> {
        if p.index != self.verdicts.len() {
            return Err(SearchError::OutOfOrder {
                path: self.csv.path().to_path_buf(),
                got: p.index,
                expected: self.verdicts.len(),
            });
        }
        self.csv.write(store::results_csv_row(p).as_bytes())?;
        if let Some(row) = store::failures_row(p) {
            self.failures.write(row.as_bytes())?;
        }
        self.timings.write(store::timings_row(p).as_bytes())?;
        self.verdicts.push(p.verdicts());
        if let Some(heat) = &mut self.heat {
            for (values, (metric, _)) in heat.iter_mut().zip(HEATMAPS) {
                values.push(p.metric(metric));
            }
        }
        self.best.add(p);
        match p.status {
            Status::Ok => {}
            Status::Diverged => self.failed.0 += 1,
            Status::Error => self.failed.1 += 1,
        }
        Ok(())
    }
}

/// Whether a search gets heatmaps: two axes of at least two values each.
fn has_heatmaps(search: &Search) -> bool {
    search.grid.axes.len() == 2 && search.grid.dims().iter().all(|&n| n >= 2)
}

/// Assemble the final files of a complete directory from `manifest.json` and the chunk files,
/// in index order: `results.csv`, `results.json`, `best.json`, `failures.csv`,
/// `boundary.csv`, heatmaps (2-D searches) and `timings.csv`, written all or nothing, in
/// bounded memory (module doc). Returns the file names written and the number of failed
/// points (diverged, error).
pub fn finalize(dir: &Path) -> Result<(Vec<String>, (usize, usize)), SearchError> {
    // temp files of a run killed during an earlier assembly (or a chunk write)
    wingcheck_io::remove_stale_temps(dir);
    wingcheck_io::remove_stale_temps(&dir.join(store::CHUNK_DIR));
    let path = dir.join("manifest.json");
    let manifest: Manifest = serde_json::from_str(&store::read(&path)?)
        .map_err(|source| SearchError::Manifest { path: path.clone(), source })?;
    let search = Search::from_manifest(manifest)?;
    // every chunk present and complete before anything is written (each read, checked, dropped)
    let mut missing = Vec::new();
    for c in 0..search.chunks() {
        if store::read_chunk(dir, &search, c)?.is_none() {
            missing.push(c);
        }
    }
    if !missing.is_empty() {
        return Err(SearchError::MissingChunks {
            missing: missing.len(),
            total: search.chunks(),
            first: missing.iter().take(8).copied().collect(),
        });
    }
    let points = ChunkStream::new(dir, &search);
    assemble(dir, &search, points)
}

/// Write the final files of `search` into `dir` from `points` (every point, in index order),
/// consumed lazily: each point is written and dropped before the next is pulled.
pub fn assemble(
    dir: &Path,
    search: &Search,
    points: impl Iterator<Item = Result<PointResult, SearchError>>,
) -> Result<(Vec<String>, (usize, usize)), SearchError> {
    let keys: Vec<String> = search.grid.axes.iter().map(|a| a.key.clone()).collect();
    let o = &search.options;
    let mut set = FileSet::new();
    let mut csv = set.open(&dir.join("results.csv"))?;
    csv.write(store::results_csv_header(&keys).as_bytes())?;
    let mut json = set.open(&dir.join("results.json"))?;
    let mut failures = set.open(&dir.join("failures.csv"))?;
    failures.write(store::failures_header(&keys).as_bytes())?;
    let mut timings = set.open(&dir.join("timings.csv"))?;
    timings.write(store::timings_header().as_bytes())?;
    let n = search.points();
    let mut acc = Assembly {
        verdicts: Vec::with_capacity(n),
        heat: has_heatmaps(search).then(|| std::array::from_fn(|_| Vec::with_capacity(n))),
        best: BestPoints::new(o.best, o.best_count),
        failed: (0, 0),
        csv,
        failures,
        timings,
    };
    let stream = points.map(|p| p.and_then(|p| acc.add(&p).map(|()| p)));
    let json_path = json.path().to_path_buf();
    let provenance = crate::records::provenance(search);
    store::write_results_json(json.writer(), &json_path, &keys, &provenance, stream)?;
    json.finish()?;
    if acc.verdicts.len() != n {
        return Err(SearchError::PointCount {
            dir: dir.join(store::CHUNK_DIR),
            assembled: acc.verdicts.len(),
            expected: n,
        });
    }
    let Assembly { verdicts, heat, best, failed, csv, failures, timings } = acc;
    for f in [csv, failures, timings] {
        f.finish()?;
    }
    set.add(&dir.join("best.json"), best.json(&keys).as_bytes())?;
    set.add(&dir.join("provenance.json"), provenance.to_json().as_bytes())?;
    drop(best);
    let cache = TheoryCache::new(o.lyapunov_elements);
    let rows = boundaries(search, &verdicts, &cache, o.refine);
    set.add(&dir.join("boundary.csv"), boundary_csv(&search.grid, &rows).as_bytes())?;
    let mut names = vec!["results.csv", "results.json", "best.json", "provenance.json", "failures.csv", "boundary.csv"]
        .into_iter()
        .map(String::from)
        .collect::<Vec<_>>();
    if let Some(heat) = heat {
        for (values, (metric, log)) in heat.into_iter().zip(HEATMAPS) {
            let name = format!("heatmap-{metric}.svg");
            set.add(&dir.join(&name), heatmap_svg(search, values, &verdicts, metric, log, &rows)?.as_bytes())?;
            names.push(name);
        }
    }
    names.push("timings.csv".into());
    let committed = set.commit()?;
    debug_assert_eq!(committed.len(), names.len());
    Ok((names, failed))
}
