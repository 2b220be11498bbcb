//! `discretisation.basis`: the closed loop stepped in the wing's modal basis (Woodbury solve
//! of diagonal + rank 2, observer signal generated without the plant) against the nodal
//! basis (banded Cholesky of the step matrix, observer integrated with the plant). Same
//! discrete equations and scheme, two independent implementations: every output — all series
//! columns, the fields and the full-rate peaks — must agree to round-off.
//!
//! Basis of the tolerances: the modal basis comes from one SVD (`wingcheck_sim::modal`,
//! M-orthonormal to round-off, frequencies within their measured bound); measured differences
//! are 2e-12–9e-10 relative on the default-size grids (the SI-scale wing the largest); the
//! tolerance 2e-9 is ~2× the largest (it was 2e-8 with the two spliced eigen-solves' basis, which
//! left 4e-9). The refined grids' tolerance is explained where they are run. A wrong scheme or a
//! missed term shows far above that: the trapezoid against TR-BDF2 differs by 2.5e-3 relative
//! in τ1 at the paper point (checked below, so the comparison can fail).

mod common;

use common::paper_with;
use wingcheck_model::{Config, StepBasis};
use wingcheck_sim::{resolved_basis, simulate, Discretisation, RunOptions, SimError, SimOutput};

fn run(cfg: &Config, basis: StepBasis) -> SimOutput {
    let mut c = cfg.clone();
    c.discretisation.basis = basis;
    let out = simulate(&c, RunOptions { fields: true, ..Default::default() }).unwrap();
    assert_eq!(out.stats.basis, basis, "stats name the basis used");
    out
}

/// max_k |x_k − y_k| / max(max_k |y_k|, floor) over a column; `floor` (same units) keeps
/// columns that are ~0 throughout (e.g. g̃ after convergence) from dividing by round-off.
fn rel(x: &[f64], y: &[f64], floor: f64) -> f64 {
    assert_eq!(x.len(), y.len());
    let scale = y.iter().fold(floor, |m, v| m.max(v.abs()));
    x.iter().zip(y).fold(0.0f64, |m, (a, b)| m.max((a - b).abs())) / scale
}

/// Largest relative difference over every output of two runs.
fn difference(modal: &SimOutput, nodal: &SimOutput) -> f64 {
    assert_eq!(modal.series.t, nodal.series.t, "same sample times");
    let mut worst = 0.0f64;
    for ((name, _), (a, b)) in
        wingcheck_sim::Series::COLUMNS.iter().zip(modal.series.columns().into_iter().zip(nodal.series.columns()))
    {
        let d = rel(a, b, 1e-6);
        assert!(d.is_finite(), "{name}");
        worst = worst.max(d);
    }
    let (fm, fn_) = (modal.fields.as_ref().unwrap(), nodal.fields.as_ref().unwrap());
    assert_eq!(fm.z, fn_.z);
    for (rows_m, rows_n) in [(&fm.q, &fn_.q), (&fm.theta, &fn_.theta)] {
        let flat = |r: &Vec<Vec<f64>>| r.iter().flatten().copied().collect::<Vec<f64>>();
        worst = worst.max(rel(&flat(rows_m), &flat(rows_n), 1e-6));
    }
    for (a, b) in modal.peaks.signals().iter().zip(nodal.peaks.signals()) {
        worst = worst.max((a.abs_max - b.abs_max).abs() / b.abs_max.max(1e-6));
    }
    worst
}

const TOLERANCE: f64 = 2e-9;
/// See the refined cases of `modal_and_nodal_bases_agree_on_every_output`.
const REFINED_TOLERANCE: f64 = 5e-7;

#[test]
fn modal_and_nodal_bases_agree_on_every_output() {
    let cases: &[&[&str]] = &[
        &[],
        &["control.kind=dobc"],
        &["control.kind=pd", "initial.shape=cantilever"],
        &["control.kind=none"],
        &["observer.rule=explicit", "discretisation.dt=0.0005"],
        &["control.a=0.05", "control.b=3", "control.k1=10", "wing.xi=0.05"],
        &["discretisation.method=fd", "discretisation.fd_points=24", "discretisation.grading=0"],
        // an SI-scale wing
        &["wing.span=6", "wing.ei=1e7", "wing.gj=1e6", "wing.rho=100", "wing.ip=10", "wing.rho_xc=5"],
    ];
    // refined grids (576 and 768 unknowns), where the modal basis of two spliced eigen-solves
    // was refused (mass defect 2.3e-4 at 192 graded elements): measured 4.2e-8 (FE 192 graded),
    // 1.4e-8 (FE 192 uniform), 1.0e-7 (FD 384), largest in q'''(s), which integrates
    // τ1 + g1 ≈ 0. It is the nodal run's round-off: it grows like h⁻⁴ (FD 96, 192, 384: 2.3e-10,
    // 5.5e-9, 1.0e-7), as the condition of the nodal step matrix S = M/α + (ξ + α)K does, and
    // with the number of steps (9.4e-8 at dt = 2.5e-4 s on FE 192 graded: 4× the steps, 2.2× the
    // difference), while two modal bases from different methods (the SVD and the two spliced
    // eigen-solves it replaced, FD 192) agree to 6e-13. Tolerance ≈ 5× the largest.
    let refined: &[&[&str]] = &[
        &["discretisation.elements=192"],
        &["discretisation.elements=192", "discretisation.grading=0"],
        &["discretisation.method=fd", "discretisation.fd_points=384", "discretisation.grading=0"],
    ];
    let cases = cases.iter().map(|c| (c, TOLERANCE)).chain(refined.iter().map(|c| (c, REFINED_TOLERANCE)));
    for (sets, tolerance) in cases {
        for scheme in ["trbdf2", "trapezoid"] {
            let stepper = format!("discretisation.stepper={scheme}");
            let mut all: Vec<&str> = vec!["horizon.t_end=2"];
            all.extend(sets.iter());
            all.push(&stepper);
            let cfg = paper_with(&all);
            let d = difference(&run(&cfg, StepBasis::Modal), &run(&cfg, StepBasis::Nodal));
            println!("{sets:?} {scheme}: {d:.2e}");
            assert!(d <= tolerance, "{sets:?} ({scheme}): modal and nodal differ by {d:e}");
        }
    }
    // The comparison detects a different scheme (so it is not vacuous).
    let cfg = paper_with(&["horizon.t_end=2"]);
    let mut trapezoid = cfg.clone();
    trapezoid.discretisation.stepper = wingcheck_model::TimeScheme::Trapezoid;
    let d = difference(&run(&cfg, StepBasis::Modal), &run(&trapezoid, StepBasis::Nodal));
    assert!(d > 1e-4, "TR-BDF2 vs trapezoid only {d:e} apart?");
}

#[test]
fn auto_basis_is_modal_up_to_the_limit_and_nodal_above() {
    let basis_of = |cfg: &Config| resolved_basis(cfg, &Discretisation::new(cfg)).unwrap().0;
    assert_eq!(basis_of(&paper_with(&[])), StepBasis::Modal);
    // FE 48 elements (144 unknowns: the error estimate's refinement) and FD 96 intervals
    // (192) are modal too
    assert_eq!(basis_of(&paper_with(&["discretisation.elements=48"])), StepBasis::Modal);
    assert_eq!(basis_of(&paper_with(&["discretisation.method=fd", "discretisation.grading=0"])), StepBasis::Modal);
    // above MODAL_AUTO_UNKNOWNS, modal where its setup is repaid by the cheaper steps: the
    // default 20-s run at FE 192 and 370 elements (576, 1 110 unknowns; the cost model's
    // crossover for its 42 222 steps is ≈ 1 140), nodal at 400 (1 200) and for a 0.5-s run at
    // 370 (22 722 steps with the initial layer's: crossover ≈ 840)
    let fine = paper_with(&["discretisation.elements=192"]);
    assert!(Discretisation::new(&fine).dim() > wingcheck_model::MODAL_AUTO_UNKNOWNS);
    assert!(fine.expected_modal() && paper_with(&["discretisation.elements=370"]).expected_modal());
    assert!(!paper_with(&["discretisation.elements=400"]).expected_modal());
    let short = paper_with(&["discretisation.elements=370", "horizon.t_end=0.5"]);
    assert!(!short.expected_modal());
    assert_eq!(basis_of(&fine), StepBasis::Modal);
    assert_eq!(basis_of(&short), StepBasis::Nodal);
    // the explicit FTDO, whose modal basis would mean the exponential scheme's dense steps,
    // stays nodal TR-BDF2 above MODAL_AUTO_UNKNOWNS
    assert_eq!(basis_of(&paper_with(&["discretisation.elements=192", "observer.rule=explicit"])), StepBasis::Nodal);
    // an explicit choice is kept
    assert_eq!(basis_of(&paper_with(&["discretisation.basis=nodal"])), StepBasis::Nodal);
    // a modal basis above the hard limit is refused with the reason, not attempted
    let forced = paper_with(&["discretisation.elements=1025", "discretisation.basis=modal", "horizon.t_end=0.01"]);
    let err = simulate(&forced, RunOptions::default()).unwrap_err();
    assert!(matches!(err, SimError::NoModalBasis { .. }), "{err}");
    let err = err.to_string();
    assert!(err.contains("unknowns") && err.contains("modal"), "{err}");
}

#[test]
fn modal_runs_are_bit_identical() {
    let cfg = paper_with(&["horizon.t_end=1", "observer.rule=explicit"]);
    let (a, b) = (run(&cfg, StepBasis::Modal), run(&cfg, StepBasis::Modal));
    assert_eq!(a.series, b.series);
    assert_eq!(a.fields, b.fields);
    assert_eq!(a.peaks, b.peaks);
}
