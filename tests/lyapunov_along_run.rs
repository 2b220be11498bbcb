//! The Lyapunov function along a run, W(t) = b·E(t) + a·⟨x, Mv⟩, which the UUB row draws
//! against the bound (35): the simulator's ⟨x, Mv⟩ column (nodal: the mass matrix's form;
//! modal: η·ζ) against an analytic solution of the discrete scheme, and the row's numbers.

mod common;

use common::paper_with;
use wingcheck_sim::modal::ModalBasis;
use wingcheck_sim::{simulate, RunOptions, Stepper};

/// The free, undamped, uncontrolled and undisturbed wing (the energy tests' conservative case).
const FREE: [&str; 10] = [
    "disturbance.distributed.mean=0",
    "disturbance.distributed.cos_amp=0",
    "disturbance.distributed.sin_amp=0",
    "disturbance.tip_bending.mean=0",
    "disturbance.tip_torsion.mean=0",
    "disturbance.tip_bending.amp=0",
    "disturbance.tip_torsion.amp=0",
    "wing.xi=0",
    "control.kind=none",
    "discretisation.stepper=trapezoid",
];

/// ⟨x, Mv⟩ after n trapezoidal steps of h from x(0) = Φη0, v(0) = 0, exactly: the trapezoidal
/// rule on η̈_i = −ω_i²η_i is the Cayley rotation of (ω_iη_i, ζ_i) by the angle ϑ_i with
/// tan(ϑ_i/2) = ω_ih/2 per step, so ω_iη_i = ω_iη0_i cos(nϑ_i), ζ_i = −ω_iη0_i sin(nϑ_i) and
/// ⟨x, Mv⟩ = Σ η_iζ_i = −½ Σ ω_i η0_i² sin(2nϑ_i) (ΦᵀMΦ = I).
fn discrete_exact(basis: &ModalBasis, h: f64, n: usize) -> f64 {
    basis
        .omega2
        .iter()
        .zip(&basis.eta0)
        .map(|(w2, e0)| {
            let w = w2.sqrt();
            let angle = 2.0 * (0.5 * w * h).atan();
            -0.5 * w * e0 * e0 * (2.0 * n as f64 * angle).sin()
        })
        .sum()
}

#[test]
fn displacement_momentum_follows_the_discrete_modal_solution() {
    for method in ["fe", "fd"] {
        let mut sets: Vec<String> = FREE.iter().map(|s| s.to_string()).collect();
        sets.push(format!("discretisation.method={method}"));
        if method == "fd" {
            sets.push("discretisation.grading=0".into());
        }
        let refs: Vec<&str> = sets.iter().map(String::as_str).collect();
        let cfg = paper_with(&refs);
        let basis = ModalBasis::new(&cfg).expect("modal basis");
        let h = cfg.discretisation.dt;
        let per_sample = cfg.steps_per_sample();
        // the nodal stepper (mass-matrix form) sample by sample over 3 s
        let mut st = Stepper::new(&cfg).unwrap();
        assert_eq!(st.sample().displacement_momentum, 0.0, "{method}: v(0) = 0");
        let scale = basis.omega2.iter().zip(&basis.eta0).map(|(w2, e)| 0.5 * w2.sqrt() * e * e).sum::<f64>();
        let mut worst: f64 = 0.0;
        for k in 1..=3000 {
            st.advance_sample();
            let exact = discrete_exact(&basis, h, k * per_sample);
            worst = worst.max((st.sample().displacement_momentum - exact).abs() / scale);
        }
        println!("{method}: max |⟨x, Mv⟩ − exact| / Σ½ω η0² = {worst:.2e} over 3 s");
        // measured 2.9e-11 (FE) and 9.7e-10 (FD): the modal basis's own round-off (orthonormal to
        // ≤ 1e-9 in M on these grids, see
        // ModalBasis's tolerances) and the angles' phase round-off over 3000·steps
        assert!(worst < 1e-8, "{method}: ⟨x, Mv⟩ off the discrete modal solution by {worst:e}");
        assert!(scale > 0.0);
    }
}

#[test]
fn both_bases_record_the_same_displacement_momentum() {
    // the closed loop off the default point: modal (η·ζ) against nodal (xᵀMv) `simulate`
    // series, the same discrete equations in two bases (agreement to round-off)
    let sets = ["control.a=1", "control.b=3000", "wing.xi=0.2", "horizon.t_end=4"];
    let run = |basis: &str| {
        let mut s: Vec<&str> = sets.to_vec();
        let b = format!("discretisation.basis={basis}");
        s.push(&b);
        simulate(&paper_with(&s), RunOptions::default()).expect("run").series
    };
    let (modal, nodal) = (run("modal"), run("nodal"));
    let top = nodal.displacement_momentum.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(top > 0.0);
    for (k, (m, n)) in modal.displacement_momentum.iter().zip(&nodal.displacement_momentum).enumerate() {
        // the bases agree to ≤ 4e-9 relative on FE wings (sim::modal's module docs)
        assert!((m - n).abs() <= 1e-8 * top, "sample {k}: modal {m} vs nodal {n} (max {top})");
    }
}

#[test]
fn the_uub_row_draws_w_against_its_bound_from_the_run_it_names() {
    // at an off-default point: W(0) of the run is b × its initial elastic energy (v(0) = 0),
    // the plot's first W value; the ratio is W/bound maximised over the run's samples
    let cfg = paper_with(&["control.a=0.5", "control.b=100", "wing.xi=0.3", "horizon.t_end=5"]);
    let ledger = wingcheck_claims::check_all(&cfg).expect("ledger");
    let row = ledger.rows.iter().find(|r| r.id == wingcheck_claims::ClaimId::Uub).expect("the UUB row");
    let wingcheck_claims::Evidence::Uub(e) = &row.evidence else {
        panic!("the UUB row at this point has evidence: {:?}", row.verdict)
    };
    let plot = row.plots.iter().find(|p| p.name == "uub-lyapunov-vs-bound").expect("the W plot");
    let w_line = plot.lines.iter().find(|l| l.label.starts_with("simulated W")).expect("the W line");
    let bound_line = plot.lines.iter().find(|l| l.label.starts_with("bound (35)")).expect("the bound line");
    // plot values are drawing data at 6 significant digits (chart::data::PLOT_DIGITS)
    assert!((w_line.y[0] - e.w0_of_run.value).abs() <= 1e-5 * e.w0_of_run.value);
    let mut run_cfg = cfg.clone();
    run_cfg.control.a = e.evaluated_at_a.value;
    run_cfg.control.b = e.evaluated_at_b.value;
    let out = simulate(&run_cfg, RunOptions::default()).expect("the operating run");
    let b_e0 = run_cfg.control.b * out.series.energy[0];
    assert!((e.w0_of_run.value - b_e0).abs() <= 1e-12 * b_e0, "W(0) {} vs b·E(0) {b_e0}", e.w0_of_run.value);
    // the bound starts at W(0) + ε/λ
    let start = e.w0_of_run.value + e.epsilon.value / e.lambda.value;
    assert!((bound_line.y[0] - start).abs() <= 1e-5 * start, "bound(0) {} vs {start}", bound_line.y[0]);
    let ratio = w_line.y.iter().zip(&bound_line.y).map(|(w, b)| w / b).fold(0.0, f64::max);
    assert!(ratio <= e.max_w_over_bound35.value * (1.0 + 1e-5) + 1e-300);
}
