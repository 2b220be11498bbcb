//! Chunks proven to be this search's own before they are resumed from or merged: the search is
//! deterministic (a point's results are a pure function of its configuration, bit for bit, on
//! any thread count), so a chunk's points can be recomputed and compared.
//!
//! What is detected (docs/outputs.md, "Chunks"): the header and digest checks of [`crate::chunk`]
//! refuse a chunk of another search, of another tool version, an edit that was not re-hashed,
//! off-grid values and non-finite metrics. An edit that was re-hashed (a forger who knows the
//! format) is caught by recomputation: [`ChunkCheck::All`] (`--verify-chunks`) recomputes every
//! point of every chunk found on disk and refuses the chunk at the first point whose status,
//! message, verdicts or metrics differ in a single bit; [`ChunkCheck::Sample`] (the default)
//! recomputes [`SAMPLE_POINTS`] point(s) per chunk, chosen at random anew by every run, so an
//! edit of m of a chunk's n points escapes one run with probability 1 − m/n (a chunk edited
//! throughout never escapes). The wall times (`timings.csv`) are not deterministic and are not
//! checked.

use std::hash::BuildHasher;
use std::path::Path;

use rayon::prelude::*;

use crate::chunk::PointDifference;
use crate::metric::METRICS;
use crate::modal::RunCache;
use crate::point::PointResult;
use crate::{Search, SearchError, TheoryCache};

/// How many of a chunk's points a resume or merge recomputes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ChunkCheck {
    /// [`SAMPLE_POINTS`] point(s) per chunk, chosen at random by every run.
    #[default]
    Sample,
    /// Every point (`--verify-chunks`): the cost of recomputing the chunks found.
    All,
}

/// Points per chunk [`ChunkCheck::Sample`] recomputes.
pub const SAMPLE_POINTS: usize = 1;

/// The work of recomputing `check`'s points of every chunk of `search` on `threads` worker
/// threads (`None`: the current rayon pool's): the search's own estimate ([`crate::limits`]),
/// for every point with [`ChunkCheck::All`], for [`SAMPLE_POINTS`] per chunk otherwise (the
/// memory is the search's either way: the same signals, bases and per-thread runs).
pub fn estimate(search: &Search, check: ChunkCheck, threads: Option<usize>) -> crate::WorkEstimate {
    let mut w = search.estimate_for(threads);
    if check == ChunkCheck::Sample {
        let points = (search.chunks() * SAMPLE_POINTS).min(search.points()) as u128;
        // the part of the core time that is not per point (g_hmax's grids) is kept
        w.core_seconds -= w.point_seconds * (w.points - points) as f64;
        w.points = points;
    }
    w
}

/// Sampled points recomputed side by side before the next batch is read.
const BATCH: usize = 256;

/// Collects the points to recompute, chunk by chunk, and recomputes them in parallel batches
/// (on the current rayon pool), refusing the first chunk whose recomputed point differs.
pub struct Verifier<'a> {
    search: &'a Search,
    check: ChunkCheck,
    seed: std::collections::hash_map::RandomState,
    theory: TheoryCache,
    runs: RunCache,
    /// (chunk file, the chunk's stored point) awaiting recomputation.
    pending: Vec<(String, PointResult)>,
    /// The search's controller of the user's, if it has one ([`crate::RunControl::controller`]).
    controller: Option<wingcheck_sim::ControllerFactory<'a>>,
}

impl<'a> Verifier<'a> {
    /// A verifier for `search` (under `controller`, the search's own if it has one) with its
    /// own caches.
    pub fn new(
        search: &'a Search,
        check: ChunkCheck,
        controller: Option<wingcheck_sim::ControllerFactory<'a>>,
    ) -> Verifier<'a> {
        Verifier {
            search,
            check,
            seed: std::collections::hash_map::RandomState::new(),
            theory: TheoryCache::new(search.options.lyapunov_elements),
            runs: RunCache::new(),
            pending: Vec::new(),
            controller,
        }
    }

    /// The positions within a chunk of `len` points to recompute for chunk `c`.
    pub fn chosen(&self, c: usize, len: usize) -> Vec<usize> {
        match self.check {
            ChunkCheck::All => (0..len).collect(),
            ChunkCheck::Sample => {
                let first = self.seed.hash_one(c) as usize % len.max(1);
                (0..SAMPLE_POINTS.min(len)).map(|k| (first + k) % len).collect()
            }
        }
    }

    /// Queue chunk `c` (read from `dir`, its points `stored`) for recomputation; recomputes a
    /// full batch at once.
    pub fn add(&mut self, dir: &Path, c: usize, stored: Vec<PointResult>) -> Result<(), SearchError> {
        let path = crate::store::chunk_path(dir, c).display().to_string();
        let chosen = self.chosen(c, stored.len());
        let mut stored: Vec<Option<PointResult>> = stored.into_iter().map(Some).collect();
        for i in chosen {
            if let Some(p) = stored[i].take() {
                self.pending.push((path.clone(), p));
            }
        }
        if self.pending.len() >= BATCH {
            self.flush()?;
        }
        Ok(())
    }

    /// Recompute every queued point; the first difference refuses its chunk.
    pub fn flush(&mut self) -> Result<(), SearchError> {
        let pending = std::mem::take(&mut self.pending);
        let (search, theory, runs, controller) = (self.search, &self.theory, &self.runs, self.controller);
        let bad = pending.par_iter().find_map_first(|(path, stored)| {
            let fresh = search.evaluate_with(stored.index, theory, runs, controller);
            difference(stored, &fresh).map(|why| SearchError::Chunk {
                path: path.clone(),
                reason: crate::chunk::ChunkProblem::Recomputed { index: stored.index, why },
            })
        });
        bad.map_or(Ok(()), Err)
    }
}

/// How a stored point differs from its recomputation (the deterministic fields, bit for bit),
/// or `None`.
pub fn difference(stored: &PointResult, fresh: &PointResult) -> Option<PointDifference> {
    if stored.values != fresh.values {
        return Some(PointDifference::Values { stored: stored.values.clone(), fresh: fresh.values.clone() });
    }
    if stored.status != fresh.status || stored.message != fresh.message {
        return Some(PointDifference::Status {
            stored: stored.status,
            stored_message: stored.message.clone(),
            fresh: fresh.status,
            fresh_message: fresh.message.clone(),
        });
    }
    if stored.verdicts() != fresh.verdicts() {
        return Some(PointDifference::Verdicts { stored: stored.verdicts(), fresh: fresh.verdicts() });
    }
    for (name, (a, b)) in METRICS.iter().zip(stored.metrics.iter().zip(&fresh.metrics)) {
        // the chunk writes a metric that is not finite as absent
        let b = b.filter(|x| x.is_finite());
        if a.map(f64::to_bits) != b.map(f64::to_bits) {
            return Some(PointDifference::Metric { name: name.to_string(), stored: *a, fresh: b });
        }
    }
    None
}
