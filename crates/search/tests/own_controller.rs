//! The search steps any controller (issue 43): a point's run under a controller of the user's
//! (a factory, as `simulate` takes it) gives the built-in's numbers where it implements the
//! same law.

use wingcheck_control::{BoundaryLaw, BuiltIn, ControlError, Controller, Erased, Held, TipMeasurement};
use wingcheck_model::{apply_overrides, Config};
use wingcheck_search::{modal::RunCache, Metric, RunControl, Search, SearchOptions, TheoryCache};
use wingcheck_sim::{BoxedController, ControllerFactory};

/// Law (15) without an observer, written outside the built-ins: the point's own k, a, b (read
/// at reset from the point's configuration) and no held input.
struct OwnPd {
    law: BoundaryLaw,
}

impl Controller for OwnPd {
    type Error = ControlError;
    fn continuous(&self) -> BoundaryLaw {
        self.law
    }
    fn reset(&mut self, cfg: &Config) -> Result<(), ControlError> {
        let c = &cfg.control;
        self.law = BoundaryLaw { gains: [c.k1, c.k2], a: c.a, b: c.b };
        Ok(())
    }
    fn sample(&mut self, _tip: &TipMeasurement) -> Result<Held, ControlError> {
        Ok(Held { input: [0.0; 2], sigma: [0.0; 2] })
    }
}

fn own_pd() -> BoxedController {
    Box::new(OwnPd { law: BoundaryLaw { gains: [0.0; 2], a: 0.0, b: 0.0 } })
}

fn search(kind: &str, controller: Option<&str>) -> Search {
    let base = apply_overrides(&Config::paper(), &["horizon.t_end=2".into(), format!("control.kind={kind}")]).unwrap();
    let specs = ["control.a=0.5,1".to_string(), "control.b=1,3000".to_string()];
    let options = SearchOptions { controller: controller.map(str::to_string), ..Default::default() };
    Search::new(base, &specs, options).unwrap()
}

#[test]
fn an_own_pd_gives_the_builtin_pd_points_bit_for_bit() {
    // Reference: the built-in PD's search points. The same law in the same modal loop, with
    // held input −0 sampled from the state for the own one and 0 from the observer signal for
    // the built-in: the same bits (crates/sim/tests/foreign_modal.rs), so every metric is equal.
    let s = search("pd", None);
    let (cache, runs) = (TheoryCache::new(s.options.lyapunov_elements), RunCache::new());
    for p in 0..s.points() {
        let reference = s.evaluate(p, &cache, &runs);
        let own = s.evaluate_with(p, &cache, &runs, Some(&own_pd));
        assert_eq!(own.status, reference.status, "{}", own.message);
        assert_eq!(own.metrics, reference.metrics, "point {p} ({:?})", own.values);
        assert!(own.metric(Metric::RmsQTip).is_some());
    }
}

#[test]
fn a_builtin_observer_handed_over_reproduces_its_points() {
    // Reference: the built-in implicit FTDO's points (the precomputed observer signal). Handed
    // over, the same observer integrates ν from the quadratures the driver hands it: equal to
    // round-off (7e-15 relative in simulate, crates/sim/tests/foreign_modal.rs); bound 1e-9.
    let s = search("ftdo", None);
    let (cache, runs) = (TheoryCache::new(s.options.lyapunov_elements), RunCache::new());
    for p in 0..s.points() {
        let cfg = apply_overrides(&s.base, &s.grid.overrides(p)).unwrap();
        let make = move || -> BoxedController { Box::new(Erased(BuiltIn::of(&cfg))) };
        let reference = s.evaluate(p, &cache, &runs);
        let own = s.evaluate_with(p, &cache, &runs, Some(&make));
        for m in [Metric::RmsQTip, Metric::MaxQTip, Metric::RmsThetaTip, Metric::Tau1Rms] {
            let (a, b) = (own.metric(m).unwrap(), reference.metric(m).unwrap());
            assert!((a - b).abs() <= 1e-9 * b.abs(), "point {p} {m:?}: {a} vs {b}");
        }
    }
}

#[test]
fn a_whole_search_runs_the_named_controller_and_refuses_a_mismatch() {
    // Reference: the built-in PD's whole search (results.csv equal: the same points' bits), and
    // the manifest records the controller's name (another name is another search).
    let (dir_ref, dir_own) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    wingcheck_search::run(&search("pd", None), dir_ref.path(), RunControl::default()).unwrap();
    let own = search("pd", Some("own PD"));
    let factory: ControllerFactory<'_> = &own_pd;
    let ctl = RunControl { controller: Some(factory), ..Default::default() };
    let sum = wingcheck_search::run(&own, dir_own.path(), ctl).unwrap();
    assert!(sum.complete);
    let read = |d: &tempfile::TempDir, f: &str| std::fs::read_to_string(d.path().join(f)).unwrap();
    assert_eq!(read(&dir_own, "results.csv"), read(&dir_ref, "results.csv"));
    assert!(read(&dir_own, "manifest.json").contains("\"controller\": \"own PD\""));
    assert!(!read(&dir_ref, "manifest.json").contains("\"controller\""));
    let e = wingcheck_search::run(&own, tempfile::tempdir().unwrap().path(), RunControl::default()).unwrap_err();
    assert!(e.to_string().contains("own PD") && e.to_string().contains("none was handed over"), "{e}");
    let ctl = RunControl { controller: Some(factory), ..Default::default() };
    let e = wingcheck_search::run(&search("pd", None), tempfile::tempdir().unwrap().path(), ctl).unwrap_err();
    assert!(e.to_string().contains("name none"), "{e}");
}
