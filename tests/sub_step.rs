//! Sub-step transients after the later jumps of the held estimate: with the explicit FTDO the
//! estimate jumps every sample period, and with strong tip damping each jump sets off a tip
//! transient that peaks microseconds later, far inside a 1-ms step. The exponential scheme's
//! probe evaluates the exact solution inside the first step after every jump; the full-rate
//! peaks must then be the dt → 0 values within their stated errors, after the initial layer as
//! well as inside it.

mod common;

use common::paper_with;
use wingcheck_model::Config;
use wingcheck_sim::{layer, simulate, simulate_base, simulate_with_error, RunOptions, SimOutput, SubStepProbe};

/// Large-b configurations (b/a from 3.5e3 to 1e5, FE and FD), explicit FTDO, exponential scheme,
/// over 6 sample periods (4 jumps after the 2-period initial layer).
fn configs() -> Vec<(&'static str, Config)> {
    let base = [
        "horizon.t_end=0.006",
        "horizon.sample_every=0.001",
        "observer.rule=explicit",
        "discretisation.stepper=exponential",
    ];
    let with = |extra: &[&str]| {
        let mut sets = base.to_vec();
        sets.extend_from_slice(extra);
        paper_with(&sets)
    };
    vec![
        ("FE, a = 1, b = 3500", with(&["control.a=1", "control.b=3500"])),
        ("FE, a = 0.01, b = 1000", with(&["control.a=0.01", "control.b=1000"])),
        (
            "FD, a = 0.1, b = 1000",
            with(&["control.a=0.1", "control.b=1000", "discretisation.method=fd", "discretisation.grading=0"]),
        ),
    ]
}

/// An independent reference: the plain exponential scheme at `dt` (no probe, no layer
/// resolution), its peaks read at the step ends only.
fn plain(cfg: &Config, dt: f64) -> SimOutput {
    let mut c = cfg.clone();
    c.discretisation.dt = dt;
    simulate_base(&c, RunOptions { sub_step_probe: SubStepProbe::Off, ..Default::default() }).unwrap()
}

#[test]
fn probed_peaks_are_the_fine_step_values_within_their_error() {
    for (name, cfg) in configs() {
        let out = simulate(&cfg, RunOptions::default()).unwrap();
        let l = out.initial_layer.expect("simulate resolves the layer");
        // the reference: step ends at dt = 1e-7 s, 10⁴ × finer; its own sampling error is the
        // change to dt = 8e-8 s (a step-end maximum converges to the true one from below; the
        // two grids share few instants — with 5e-8 s, whose instants include all of 1e-7 s's,
        // both read the θ̇ peak at the same instant 1.9 µs after the jump, 2e-6 below the
        // maximum the probe finds at 1.92 µs, and their difference said 5e-15)
        let (reference, finer) = (plain(&cfg, 1e-7), plain(&cfg, 8e-8));
        let mut probed = 0;
        // the time step's own error at the step ends (the held step means of ḡ and φ̄), as the
        // error estimate takes it: Richardson on the run at dt/2
        let mut half = cfg.clone();
        half.discretisation.dt /= 2.0;
        let half = simulate(&half, RunOptions::default()).unwrap();
        for (i, (((p, r), f), h)) in out
            .peaks
            .signals()
            .iter()
            .zip(reference.peaks.signals())
            .zip(finer.peaks.signals())
            .zip(half.peaks.signals())
            .enumerate()
        {
            let inside_a_step = p.sub_step_error > 0.0;
            if !inside_a_step && p.t > l.t_end {
                continue; // a step-end peak after the layer: the error estimate's, tested below
            }
            let reference_error = 2.0 * (f.abs_max - r.abs_max).abs();
            let in_layer = if p.t <= l.t_end { l.errors[i] } else { 0.0 };
            let time_step = wingcheck_sim::RICHARDSON_2 * (p.abs_max - h.abs_max).abs();
            let stated = in_layer + time_step + p.sub_step_error + layer::PEAK_ROUND_OFF * p.abs_max;
            let diff = (p.abs_max - f.abs_max).abs();
            probed += usize::from(inside_a_step);
            assert!(
                diff <= stated + reference_error,
                "{name}, signal {i}: {} (t = {}) vs dt = 8e-8 {} (t = {}): off by {diff:e}, stated {stated:e} + \
                 reference {reference_error:e}",
                p.abs_max,
                p.t,
                f.abs_max,
                f.t
            );
            // honest and still useful: a probed peak's bar within 10 × its actual error
            // (measured 1.7–3.8 ×)
            if inside_a_step {
                assert!(stated <= 10.0 * diff.max(reference_error), "{name}, signal {i}: {stated:e} vs {diff:e}");
            }
        }
        assert!(probed > 0, "{name}: no peak inside a step to check");
        let after = |o: &SimOutput| o.peaks.theta_tip_rate;
        // the case that motivated it: at a = 1, b = 3500 the θ̇ peak comes 2 µs after the jump
        // at t = 3 ms, past the layer; the plain scheme at dt = 1 ms misses it by 10 % (measured
        // 2.057e-3 against 2.278e-3 rad/s)
        if name.starts_with("FE, a = 1,") {
            let unprobed = plain(&cfg, cfg.discretisation.dt);
            assert!(after(&out).t > l.t_end, "{name}: {:?}", after(&out));
            assert!(
                after(&out).abs_max > 1.05 * after(&unprobed).abs_max,
                "{name}: probed {:?} vs plain {:?}",
                after(&out),
                after(&unprobed)
            );
            assert!(out.stats.sub_step_probes[1] > 0, "{:?}", out.stats);
        }
    }
}

#[test]
fn the_screen_finds_what_the_whole_fine_grid_finds() {
    // Reference: the same runs probing every fine point of every output (no screen); the screen
    // may only skip what cannot raise a peak. Over 0.1 s: 100 jumps, past the transient of the
    // estimate.
    let mut cases = configs();
    cases.push(("paper point, explicit", paper_with(&["observer.rule=explicit"])));
    for (name, mut cfg) in cases {
        cfg.horizon.t_end = 0.1;
        cfg.horizon.sample_every = 0.01;
        let run = |probe| simulate_base(&cfg, RunOptions { sub_step_probe: probe, ..Default::default() }).unwrap();
        let (screened, exhaustive) = (run(SubStepProbe::Screened), run(SubStepProbe::Exhaustive));
        for (i, (s, e)) in screened.peaks.signals().iter().zip(exhaustive.peaks.signals()).enumerate() {
            assert_eq!(s.abs_max, e.abs_max, "{name}, signal {i}: screened {s:?} vs whole grid {e:?}");
        }
        assert_eq!(screened.series, exhaustive.series, "{name}: the probe changes no trajectory");
    }
}

#[test]
fn estimated_peaks_cover_a_finer_grid_and_step_after_later_jumps() {
    // Every full-rate peak with its printed error (grid, dt, layer, sub-step, round-off)
    // contains the value of a run on the doubled grid at dt = 1e-5 s.
    for (name, cfg) in configs() {
        common::assert_estimated_peaks_cover_a_finer_run(name, &cfg);
    }
}

#[test]
fn a_scheme_without_the_probe_is_checked_by_an_exponential_twin() {
    // TR-BDF2 has no probe: under the error estimate an exponential twin probes for it, and
    // the peaks' ± must then cover the dt → 0 value (the plain exponential scheme at dt = 5e-8
    // s) of the transient the TR-BDF2 steps miss after the jump at t = 3 ms.
    let (name, mut cfg) = configs().remove(0);
    cfg.discretisation.stepper = wingcheck_model::TimeScheme::Trbdf2;
    let est = simulate_with_error(&cfg, RunOptions::default()).unwrap();
    assert!(
        matches!(est.sub_step_check, wingcheck_sim::SubStepCheck::Twin { raised } if raised > 0),
        "{name}: {:?}",
        est.sub_step_check
    );
    let reference = plain(&cfg, 5e-8);
    let (e, r) = (est.peaks.theta_tip_rate.abs_max, reference.peaks.theta_tip_rate.abs_max);
    // the step ends miss it (measured: TR-BDF2's peak 10 % low)
    assert!(e.value < 0.95 * r, "{name}: TR-BDF2 {} vs {r}", e.value);
    assert!((e.value - r).abs() <= e.error, "{name}: {} ± {} vs dt = 5e-8 {r}", e.value, e.error);
    // an exponential base run needs no twin
    let exponential = simulate_with_error(&configs().remove(0).1, RunOptions::default()).unwrap();
    assert_eq!(exponential.sub_step_check, wingcheck_sim::SubStepCheck::Probed);
}

/// The meshes of the refinement the error estimate makes and a referee tries: FD 96–384
/// intervals, FE 24–192 elements graded and uniform.
const MESHES: [(&str, &[&str]); 7] = [
    ("FD 96", &["discretisation.method=fd", "discretisation.grading=0", "discretisation.fd_points=96"]),
    ("FD 192", &["discretisation.method=fd", "discretisation.grading=0", "discretisation.fd_points=192"]),
    ("FD 384", &["discretisation.method=fd", "discretisation.grading=0", "discretisation.fd_points=384"]),
    ("FE 24 graded", &["discretisation.elements=24"]),
    ("FE 96 graded", &["discretisation.elements=96"]),
    ("FE 192 graded", &["discretisation.elements=192"]),
    ("FE 192 uniform", &["discretisation.elements=192", "discretisation.grading=0"]),
];

#[test]
fn probed_peaks_are_a_microsecond_run_s_on_every_mesh() {
    // a = 1, b = 3500, explicit FTDO, the exponential scheme: every full-rate peak of q(s),
    // θ(s), q̇(s), θ̇(s), τ1, τ2 after the initial layer, over the jump at t = 3 ms (its tip
    // transient peaks 0.5–2.4 µs later, finer meshes sooner) and the next, at dt = 1 ms with
    // the probe against the same mesh at dt = 1e-6 s (with its own probe: the transient spans
    // several of its steps, which it probes while an output is still rising at a step's end;
    // its step ends alone are 0.15–8 % low on these meshes). Reference tolerance: the issue's
    // 1e-4 relative (measured ≤ 4.8e-6 on all seven meshes, FE 96 graded's τ2; 1.4e-4 on FD 384 and 0.15–0.8 % on FD
    // 96–192 before the probe's grid was refined and followed the transient past one step).
    for (name, mesh) in MESHES {
        let mut sets = vec![
            "horizon.t_end=0.004",
            "horizon.sample_every=0.001",
            "observer.rule=explicit",
            "discretisation.stepper=exponential",
            "control.a=1",
            "control.b=3500",
        ];
        sets.extend_from_slice(mesh);
        let cfg = paper_with(&sets);
        let coarse = simulate_base(&cfg, RunOptions::default()).unwrap();
        let mut fine = cfg.clone();
        fine.discretisation.dt = 1e-6;
        let fine = simulate_base(&fine, RunOptions::default()).unwrap();
        for (i, (p, f)) in
            coarse.peaks_after_layer.signals().iter().zip(fine.peaks_after_layer.signals()).enumerate().take(6)
        {
            let rel = (p.abs_max - f.abs_max).abs() / f.abs_max;
            println!("{name}, signal {i}: {:.7e} (t = {:.7}) vs {:.7e}: {rel:.1e}", p.abs_max, p.t, f.abs_max);
            assert!(rel <= 1e-4, "{name}, signal {i}: {p:?} vs dt = 1e-6 s {f:?}");
        }
        // the transient is there to be found: θ̇(s) peaks inside the step after the jump
        assert!(coarse.peaks_after_layer.theta_tip_rate.sub_step_error > 0.0, "{name}");
    }
}
