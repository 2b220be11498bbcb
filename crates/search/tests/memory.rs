//! The search's memory model against the process's measured peak (issue 46, item 1): the
//! estimate counted one observer signal at 4 f64 per sample while every worker built its own at
//! 6, so a search it accepted passed 4 GB. This binary holds one test, so the process's peak
//! resident set (`VmHWM`, Linux) is the search's plus the test harness's.
//!
//! The long horizon makes the signal dominate: 2e6 integrator steps of 24 bytes and 2e6 + 1
//! observer samples of 48 bytes (144 MB), shared by every worker; each worker's point adds its
//! trace (7 f64 at 2e5 + 1 output samples, 11 MB). Measured at higher cost (closing note of
//! issue 46): t_end = 3e4 s at 1, 2, 3 and 8 threads, peak within the printed estimate.

use wingcheck_model::{apply_overrides, Config};
use wingcheck_search::{run, RunControl, Search, SearchOptions};

/// The process's peak resident set so far (bytes), from /proc/self/status.
fn peak_rss() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024.0)
}

#[test]
fn the_peak_memory_of_a_search_is_within_its_estimate_at_one_and_two_threads() {
    if peak_rss().is_none() {
        eprintln!("no /proc/self/status here: nothing measured");
        return;
    }
    let base = apply_overrides(&Config::paper(), &["horizon.t_end=2000".into()]).unwrap();
    let dir = tempfile::tempdir().unwrap();
    for threads in [1usize, 2] {
        let values: Vec<String> = (1..=threads).map(|b| b.to_string()).collect();
        let search =
            Search::new(base.clone(), &[format!("control.b={}", values.join(","))], SearchOptions::default()).unwrap();
        let w = search.estimate_with_threads(threads);
        // the signal is counted once, at its size (struct layout: [f64; 3] per step, 6 f64 per sample)
        assert_eq!(w.memory.signals, 1.0, "{w:?}");
        assert_eq!(w.memory.signal_bytes, 24.0 * 2e6 + 48.0 * (2e6 + 1.0), "{w:?}");
        let out = dir.path().join(format!("t{threads}"));
        let s = run(&search, &out, RunControl { threads: Some(threads), ..Default::default() }).unwrap();
        assert!(s.complete && s.failed == 0, "{s:?}");
        let peak = peak_rss().unwrap();
        eprintln!("{threads} thread(s): peak {:.1} MB, estimate {:.1} MB", peak / 1e6, w.memory_bytes / 1e6);
        assert!(peak <= w.memory_bytes, "{threads} threads: peak {peak} above the estimate {}", w.memory.text());
        // not vacuous: the estimate is the peak's order (two signals, as every worker built its
        // own before, would pass it)
        assert!(peak >= 0.6 * w.memory_bytes, "{threads} threads: peak {peak}, estimate {}", w.memory.text());
        assert!(peak + w.memory.signal_bytes > w.memory_bytes, "one more signal would exceed the estimate");
    }
}
