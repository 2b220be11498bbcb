//! `report` finishes on a one-worker thread pool (a one-core machine, or `RAYON_NUM_THREADS=1`).
//! The ledger's rows used to run beside each other on OS threads of their own; the report runs
//! the ledger on a pool worker, which then blocked joining a thread whose ω₁ enclosure waited
//! for a free worker — forever, with one worker (and with two, when two reports ran at once in
//! one process). Its own test binary, so the global pool can be fixed at one worker; a watchdog
//! turns a hang into a failure.

use std::sync::mpsc;
use std::time::Duration;

use wingcheck_model::{apply_overrides, Config};
use wingcheck_report::{write_report, ReportOptions};

#[test]
fn a_report_finishes_on_one_worker() {
    rayon::ThreadPoolBuilder::new().num_threads(1).build_global().expect("the first use of the global pool");
    let cfg = apply_overrides(&Config::paper(), &["horizon.t_end=4".to_string()]).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("report");
    let (done, finished) = mpsc::channel();
    let worker = {
        let out = out.clone();
        std::thread::spawn(move || {
            let r = write_report(&cfg, &out, &ReportOptions::default()).map(|_| ());
            let _ = done.send(r.map_err(|e| e.to_string()));
        })
    };
    // a 4-s horizon report takes ≈ 3 s on one worker of a 2-core machine; 10 min is a hang
    match finished.recv_timeout(Duration::from_secs(600)) {
        Ok(r) => r.expect("report renders"),
        Err(_) => panic!("the report did not finish within 10 minutes on one worker (a hang)"),
    }
    worker.join().unwrap();
    assert!(out.join("index.html").exists());
}
