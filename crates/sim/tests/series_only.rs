//! `RunOptions::series_only` against a full recording of the same run: every column a
//! refinement's metrics read is the full recording's to round-off, and the energy column is an
//! upper bound of the recorded energy.

use wingcheck_model::{apply_overrides, Config};
use wingcheck_sim::{simulate_base, RunOptions, SimOutput, SubStepProbe, MAX_EIGENBASIS_ROUNDOFF};

fn run(cfg: &Config, series_only: bool) -> SimOutput {
    let opts = RunOptions {
        sub_step_probe: SubStepProbe::Off,
        eigenbasis: Some(MAX_EIGENBASIS_ROUNDOFF),
        series_only,
        ..Default::default()
    };
    simulate_base(cfg, opts).unwrap()
}

/// Largest |a − b| relative to max |b| over two columns.
fn relative_gap(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(f64::MIN_POSITIVE);
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max) / scale
}

#[test]
fn a_series_only_run_records_the_full_runs_tips_taus_and_observer() {
    // The explicit FTDO steps in the eigenbasis (the form whose O(N²) reconstruction the
    // option skips): the paper wing, a strongly damped tip (a = 1, b = 3000) and an FD grid.
    let cases: [&[&str]; 3] = [
        &[],
        &["control.a=1", "control.b=3000"],
        &["discretisation.method=fd", "discretisation.grading=0", "discretisation.fd_points=48"],
    ];
    for sets in cases {
        let mut over: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        over.extend(["observer.rule=explicit".to_string(), "discretisation.stepper=exponential".to_string()]);
        let cfg = apply_overrides(&Config::paper(), &over).unwrap();
        let (lean, full) = (run(&cfg, true), run(&cfg, false));
        assert!(lean.stats.eigenbasis_roundoff.is_some(), "{sets:?}: not in the eigenbasis");
        let (l, f) = (&lean.series, &full.series);
        assert_eq!(l.t, f.t, "{sets:?}");
        // Reference: the full recording of the same run. The tip values come from the step's
        // precomputed rows instead of the reconstructed state (equal to round-off); τ and its
        // interval RMS are formed from them; the observer's columns are the same signal.
        for (name, a, b) in [
            ("q_tip", &l.q_tip, &f.q_tip),
            ("theta_tip", &l.theta_tip, &f.theta_tip),
            ("q_tip_rate", &l.q_tip_rate, &f.q_tip_rate),
            ("theta_tip_rate", &l.theta_tip_rate, &f.theta_tip_rate),
            ("tau1", &l.tau1, &f.tau1),
            ("tau2", &l.tau2, &f.tau2),
            ("tau1_rms", &l.tau1_rms, &f.tau1_rms),
            ("tau2_rms", &l.tau2_rms, &f.tau2_rms),
        ] {
            let gap = relative_gap(a, b);
            assert!(gap <= 1e-10, "{sets:?}: {name} differs by {gap:e} relative");
        }
        assert_eq!((&l.g1, &l.g2, &l.g1_hat, &l.g2_hat), (&f.g1, &f.g2, &f.g1_hat, &f.g2_hat), "{sets:?}");
        assert_eq!(lean.gtilde_band_entry, full.gtilde_band_entry, "{sets:?}");
        let peak_gap = relative_gap(
            &[lean.peaks.q_tip.abs_max, lean.peaks.theta_tip.abs_max],
            &[full.peaks.q_tip.abs_max, full.peaks.theta_tip.abs_max],
        );
        assert!(peak_gap <= 1e-10, "{sets:?}: peaks differ by {peak_gap:e}");
        // the energy column: an upper bound, equal at the last output (the state is
        // reconstructed there)
        let last = f.energy.len() - 1;
        for (k, (bound, energy)) in l.energy.iter().zip(&f.energy).enumerate() {
            assert!(*bound >= energy * (1.0 - 1e-10), "{sets:?}: output {k}: {bound} < {energy}");
            if k == last {
                assert!((bound - energy).abs() <= 1e-10 * energy.abs(), "{sets:?}: output {k}");
            }
        }
        // and it is a bound, not the energy: the option did skip the reconstruction
        assert!(l.energy[..last].iter().zip(&f.energy[..last]).any(|(b, e)| b > &(e * (1.0 + 1e-6))), "{sets:?}");
    }
}
