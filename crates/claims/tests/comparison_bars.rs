//! The ± of the ftdo-vs-dobc row's simulated values (from the doubled grid and dt/2) against a
//! much finer run of the same loop: four times the elements and a quarter of the step. Every
//! metric of the configured run lies within its ± of the fine run's value; so do ζ3, ζ4.

use wingcheck_claims::comparison::{measured, metrics, Metrics};
use wingcheck_claims::{CheckSettings, Study};
use wingcheck_model::{apply_overrides, Config};

/// (name, value, error) of every metric (settling times where the run settles).
fn fields(m: &Metrics, e: &Metrics) -> Vec<(&'static str, Option<f64>, Option<f64>)> {
    let v = |x: f64, dx: f64| (Some(x), Some(dx));
    let list = [
        ("rms_q_full", v(m.rms_q_full, e.rms_q_full)),
        ("rms_q_late", v(m.rms_q_late, e.rms_q_late)),
        ("peak_q", v(m.peak_q, e.peak_q)),
        ("rms_theta_full", v(m.rms_theta_full, e.rms_theta_full)),
        ("rms_theta_late", v(m.rms_theta_late, e.rms_theta_late)),
        ("peak_theta", v(m.peak_theta, e.peak_theta)),
        ("settle_q", (m.settle_q, e.settle_q)),
        ("settle_theta", (m.settle_theta, e.settle_theta)),
        ("rms_tau1", v(m.rms_tau1, e.rms_tau1)),
        ("peak_tau1", v(m.peak_tau1, e.peak_tau1)),
        ("rms_tau2", v(m.rms_tau2, e.rms_tau2)),
        ("peak_tau2", v(m.peak_tau2, e.peak_tau2)),
        ("rms_gtilde1_late", v(m.rms_gtilde_late[0], e.rms_gtilde_late[0])),
        ("rms_gtilde2_late", v(m.rms_gtilde_late[1], e.rms_gtilde_late[1])),
    ];
    list.into_iter().map(|(n, (x, dx))| (n, x, dx)).collect()
}

#[test]
fn every_bar_covers_a_run_on_four_times_the_elements_at_a_quarter_step() {
    let settings = CheckSettings::default();
    let cases: [&[&str]; 5] = [
        &["control.kind=ftdo", "observer.rule=explicit"],
        &["control.kind=ftdo"],
        &["control.kind=dobc"],
        &["control.kind=ftdo", "control.a=0.5", "control.b=20", "wing.xi=0.3"],
        &["control.kind=dobc", "discretisation.method=fd", "discretisation.grading=0", "control.k1=3"],
    ];
    for sets in cases {
        let mut over: Vec<String> = vec!["horizon.t_end=4".into()];
        over.extend(sets.iter().map(|s| s.to_string()));
        let cfg: Config = apply_overrides(&Config::paper(), &over).unwrap();
        let study = Study::new();
        let (m, e) = measured(&study, &cfg, &settings).unwrap();
        let mut fine = cfg.clone();
        fine.discretisation.elements *= 4;
        fine.discretisation.fd_points = 4 * (fine.discretisation.fd_points - 1) + 1;
        fine.discretisation.dt /= 4.0;
        let reference = metrics(&study.simulate(&fine).unwrap(), &settings);
        let zero = metric_zero();
        for ((name, x, dx), (_, r, _)) in fields(&m, &e).into_iter().zip(fields(&reference, &zero)) {
            match (x, dx, r) {
                (Some(x), Some(dx), Some(r)) => {
                    println!("{sets:?} {name}: {x:.6e} ± {dx:.1e}, fine {r:.6e} (off by {:.1e})", (x - r).abs());
                    assert!((x - r).abs() <= dx, "{sets:?} {name}: {x:e} ± {dx:e} misses the fine run's {r:e}");
                }
                (None, _, None) => {}
                other => panic!("{sets:?} {name}: settles in one run only: {other:?}"),
            }
        }
    }
}

/// ζ3, ζ4 (sup |g̃| of the FTDO run, mu-conditions) within their ± of the fine run's.
#[test]
fn the_zeta_bars_cover_the_fine_run() {
    for sets in [&["horizon.t_end=4"][..], &["horizon.t_end=4", "observer.rule=explicit", "wing.xi=0.3"]] {
        let over: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        let cfg: Config = apply_overrides(&Config::paper(), &over).unwrap();
        let study = Study::new();
        let bounds = study.disturbance_bounds(&cfg).unwrap();
        let errors = study.zeta_errors(&cfg).unwrap();
        let mut fine = cfg.clone();
        fine.control.kind = wingcheck_model::ControllerKind::Ftdo;
        fine.discretisation.elements *= 4;
        fine.discretisation.dt /= 4.0;
        let out = study.simulate(&fine).unwrap();
        for (ch, zeta) in [bounds.zeta3, bounds.zeta4].into_iter().enumerate() {
            let r = wingcheck_sim::metrics::observer_error_sup(&out, ch);
            println!("{sets:?} ζ{}: {zeta:e} ± {:e}, fine {r:e}", ch + 3, errors[ch]);
            assert!((zeta - r).abs() <= errors[ch], "{sets:?} ζ{}: {zeta:e} ± {:e} misses {r:e}", ch + 3, errors[ch]);
        }
    }
}

fn metric_zero() -> Metrics {
    Metrics {
        rms_q_full: 0.0,
        rms_q_late: 0.0,
        peak_q: 0.0,
        rms_theta_full: 0.0,
        rms_theta_late: 0.0,
        peak_theta: 0.0,
        settle_q: Some(0.0),
        settle_theta: Some(0.0),
        rms_tau1: 0.0,
        peak_tau1: 0.0,
        rms_tau2: 0.0,
        peak_tau2: 0.0,
        rms_gtilde_full: [0.0; 2],
        rms_gtilde_late: [0.0; 2],
        gtilde_settle: [Some(0.0); 2],
    }
}

/// The finite-time rows' digital-run values (band entry, σ after it, g̃, ĝ and τ jumps per
/// sample) within their ± of the same runs on four times the elements at a quarter of the step.
#[test]
fn the_digital_run_bars_cover_the_fine_runs() {
    let settings = CheckSettings::default();
    let cfg: Config = apply_overrides(&Config::paper(), &["horizon.t_end=2".to_string()]).unwrap();
    let base = wingcheck_claims::finite_time::digital_runs(&cfg, &settings).unwrap();
    let mut fine_cfg = cfg.clone();
    fine_cfg.discretisation.elements *= 4;
    fine_cfg.discretisation.dt /= 4.0;
    let fine = wingcheck_claims::finite_time::digital_runs(&fine_cfg, &settings).unwrap();
    assert_eq!(base.t_end, fine.t_end, "the horizon follows from the disturbances and gains only");
    for ((b, f), errors) in base.runs.iter().zip(fine.runs.iter()).zip(base.errors.iter()) {
        for ch in 0..2 {
            let (x, r, e) = (&b.channels[ch], &f.channels[ch], &errors[ch]);
            let values = [
                ("sigma_after_max", x.sigma_after_max, r.sigma_after_max, e.sigma_after_max),
                ("gtilde_max", x.gtilde_max, r.gtilde_max, e.gtilde_max),
                ("ghat_jump_max", x.ghat_jump_max, r.ghat_jump_max, e.ghat_jump_max),
                ("tau_jump_max", x.tau_jump_max, r.tau_jump_max, e.tau_jump_max),
            ];
            for (name, v, reference, error) in values {
                println!("{} T = {} ch {ch} {name}: {v:e} ± {error:e}, fine {reference:e}", b.rule.name(), b.period);
                assert!((v - reference).abs() <= error, "{} T = {} ch {ch} {name}", b.rule.name(), b.period);
            }
            if let (Some(t), Some(tr)) = (x.reach_s, r.reach_s) {
                assert!((t - tr).abs() <= e.reach_s.unwrap(), "{} T = {} ch {ch} reach", b.rule.name(), b.period);
            }
        }
    }
}
