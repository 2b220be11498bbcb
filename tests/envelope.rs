//! The full-rate envelope per output interval (`SimOutput::envelope`): checked against the same
//! run recorded at every observer sample (an independent reading of the same instants), for the
//! chattering explicit observer and the implicit one, in the modal and the nodal basis.

mod common;

use common::paper_with;
use wingcheck_sim::{simulate, RunOptions, SimOutput};

fn run(sets: &[&str]) -> SimOutput {
    simulate(&paper_with(sets), RunOptions::default()).unwrap()
}

/// The coarse run's (min, max) per 10-ms interval against the fine run's samples every 1 ms
/// (each fine sample is an instant the coarse interval records): every fine sample lies in its
/// interval's envelope, and the envelope's extremes are attained by the fine run's own
/// envelopes (the same instants, grouped differently).
fn check(base: &[&str]) {
    let mut coarse_sets = base.to_vec();
    coarse_sets.push("horizon.sample_every=0.01");
    let mut fine_sets = base.to_vec();
    fine_sets.push("horizon.sample_every=0.001");
    let (coarse, fine) = (run(&coarse_sets), run(&fine_sets));
    let every = 10;
    let pick = |o: &SimOutput, c: usize| match c {
        0 => (o.series.tau1.clone(), o.envelope.tau1.clone()),
        1 => (o.series.tau2.clone(), o.envelope.tau2.clone()),
        2 => (o.series.g1.iter().zip(&o.series.g1_hat).map(|(g, h)| g - h).collect(), o.envelope.g1_error.clone()),
        _ => (o.series.g2.iter().zip(&o.series.g2_hat).map(|(g, h)| g - h).collect(), o.envelope.g2_error.clone()),
    };
    for c in 0..4 {
        let (_, env) = pick(&coarse, c);
        let (fine_v, fine_env) = pick(&fine, c);
        assert_eq!(env.len(), coarse.series.len());
        for k in 1..env.len() {
            let (lo, hi) = env[k];
            assert!(lo <= hi);
            // the two runs agree to round-off (the output sampling does not change the steps)
            let tol = 1e-12 * (1.0 + hi.abs().max(lo.abs()));
            for j in (k - 1) * every + 1..=k * every {
                let v = fine_v[j];
                assert!(lo - tol <= v && v <= hi + tol, "{base:?} signal {c}, interval {k}: {v} outside [{lo}, {hi}]");
            }
            let flo = fine_env[(k - 1) * every + 1..=k * every].iter().map(|e| e.0).fold(f64::INFINITY, f64::min);
            let fhi = fine_env[(k - 1) * every + 1..=k * every].iter().map(|e| e.1).fold(f64::NEG_INFINITY, f64::max);
            assert!((flo - lo).abs() <= tol && (fhi - hi).abs() <= tol, "{base:?} signal {c}, interval {k}");
        }
    }
}

#[test]
fn the_envelope_holds_every_instant_of_its_interval() {
    check(&["horizon.t_end=1", "observer.rule=explicit"]);
    check(&[
        "horizon.t_end=1",
        "observer.rule=explicit",
        "discretisation.basis=nodal",
        "discretisation.stepper=trbdf2",
    ]);
    check(&["horizon.t_end=1"]);
    check(&["horizon.t_end=1", "control.kind=dobc", "discretisation.basis=nodal"]);
}

#[test]
fn the_explicit_observer_chatters_inside_each_output_interval() {
    // The aliasing the envelope exists for (issue 21): explicit FTDO at the paper point, τ1
    // switches sign within every late output interval while the 10-ms samples do not.
    let o = run(&["horizon.t_end=2", "observer.rule=explicit"]);
    let late: Vec<&(f64, f64)> = o.envelope.tau1.iter().skip(o.series.len() / 2).collect();
    let spread = late.iter().map(|(lo, hi)| hi - lo).fold(f64::INFINITY, f64::min);
    assert!(spread > 5.0, "smallest late τ1 spread per interval {spread} N");
    let samples = &o.series.tau1[o.series.len() / 2..];
    let (lo, hi) = samples.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(*v), b.max(*v)));
    assert!(hi - lo < 0.5 * spread, "the samples alias: spread {}", hi - lo);
}
