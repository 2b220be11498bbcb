//! `discretisation.basis`: the closed loop stepped in the wing's modal basis (Woodbury solve
//! of diagonal + rank 2, observer signal generated without the plant) against the nodal
//! basis (banded Cholesky of the step matrix, observer integrated with the plant). Same
//! discrete equations and scheme, two independent implementations: every output — all series
//! columns, the fields and the full-rate peaks — must agree to round-off.
//!
//! Basis of the tolerances: the modal basis comes from a dense symmetric eigenproblem whose ω²
//! span ~10 decades on FE wings; measured differences are 1e-11–4e-9 relative on FE wings and
//! ≤ 3e-12 on FD wings (diagonal M); the tolerance 2e-8 is ~5× the largest. A wrong scheme or a
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

const TOLERANCE: f64 = 2e-8;

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
    for sets in cases {
        for scheme in ["trbdf2", "trapezoid"] {
            let stepper = format!("discretisation.stepper={scheme}");
            let mut all: Vec<&str> = vec!["horizon.t_end=2"];
            all.extend(sets.iter());
            all.push(&stepper);
            let cfg = paper_with(&all);
            let d = difference(&run(&cfg, StepBasis::Modal), &run(&cfg, StepBasis::Nodal));
            println!("{sets:?} {scheme}: {d:.2e}");
            assert!(d <= TOLERANCE, "{sets:?} ({scheme}): modal and nodal differ by {d:e}");
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
    let fine = paper_with(&["discretisation.elements=128"]);
    assert!(Discretisation::new(&fine).dim() > wingcheck_model::MODAL_AUTO_UNKNOWNS);
    assert_eq!(basis_of(&fine), StepBasis::Nodal);
    // an explicit choice is kept
    assert_eq!(basis_of(&paper_with(&["discretisation.basis=nodal"])), StepBasis::Nodal);
    // a basis that fails its orthonormality check (FE 192 graded elements: measured mass
    // defect 2.3e-4 > 1e-6) is refused with the reason when asked for
    let mut forced = paper_with(&["discretisation.elements=192", "horizon.t_end=0.01"]);
    forced.discretisation.basis = StepBasis::Modal;
    let err = simulate(&forced, RunOptions::default()).unwrap_err();
    assert!(matches!(err, SimError::NoModalBasis { .. }), "a typed refusal, not a numerical failure: {err}");
    let err = err.to_string();
    assert!(err.contains("orthonormal"), "{err}");
    // a modal basis above the hard limit is refused with the reason, not attempted
    let forced = paper_with(&["discretisation.elements=256", "discretisation.basis=modal", "horizon.t_end=0.01"]);
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
