//! Cancellation through the front ends' operations: a set token stops a run, a check, a search
//! and a report with `Cancelled` (the kind a front end maps to KeyboardInterrupt) and writes
//! nothing; a token set during a long run stops it within a few observer samples.

use std::time::{Duration, Instant};

use wingcheck_app::{ops, simulate, AppError, Cancel, ConfigSource, ErrorKind, Front, SimulateRequest, WorkPolicy};

fn policy() -> WorkPolicy {
    WorkPolicy { allow_large: true, front: Front::Python }
}

fn config(sets: &[&str]) -> wingcheck_model::Config {
    ConfigSource { set: sets.iter().map(|s| s.to_string()).collect(), ..Default::default() }.load().unwrap()
}

fn cancelled() -> Cancel {
    let c = Cancel::new();
    c.cancel();
    c
}

#[test]
fn a_set_token_stops_every_operation_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = config(&["horizon.t_end=2"]);
    let out = dir.path().join("run.csv");
    let req = SimulateRequest { out: Some(out.clone()), ..Default::default() };
    let e = simulate::run(&cfg, &req, policy(), None, &cancelled()).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Cancelled, "{e}");
    assert!(!out.exists());
    assert_eq!(ops::check(&cfg, policy(), &cancelled()).unwrap_err().kind(), ErrorKind::Cancelled);
    let ctl = wingcheck_search::RunControl { cancel: cancelled(), ..Default::default() };
    let over = ["control.a=0.1,1".to_string(), "control.b=1,10".to_string()];
    let e = ops::search(cfg.clone(), &over, Default::default(), &dir.path().join("s"), policy(), ctl).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Cancelled, "{e}");
    assert!(!dir.path().join("s").exists(), "a cancelled search removes the directory it created");
    let token = cancelled();
    let opts = wingcheck_report::ReportOptions { cancel: Some(&token), ..Default::default() };
    let e = ops::report(&cfg, &dir.path().join("r"), policy(), &opts).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Cancelled, "{e}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "nothing written");
}

#[test]
fn a_token_set_during_a_long_run_stops_it_promptly() {
    // 400 s of simulated time (≈ 0.4–2 s of computing): the token is read every observer sample
    let cfg = config(&["horizon.t_end=400"]);
    let token = Cancel::new();
    let start = Instant::now();
    let (r, stopped_after) = std::thread::scope(|s| {
        let t = token.clone();
        s.spawn(move || {
            std::thread::sleep(Duration::from_millis(50));
            t.cancel();
        });
        let r = simulate::run(&cfg, &SimulateRequest::default(), policy(), None, &token);
        (r, start.elapsed())
    });
    match r {
        Err(e @ AppError::Sim(_)) => assert_eq!(e.kind(), ErrorKind::Cancelled),
        other => panic!("expected a cancelled run, got {other:?}"),
    }
    assert!(stopped_after < Duration::from_millis(500), "{stopped_after:?}");
}
