//! Helpers shared by the integration tests.
#![allow(dead_code)]

pub mod characteristic;

use wingcheck_model::{apply_overrides, Config};

/// An SI-scale wing: span 6 m, EI 1e7 N m², GJ 1e6 N m², ρ 100 kg/m, I_p 10 kg m (with the
/// paper's ρx_c unless a test sets it).
pub const SI_WING: [&str; 5] = ["wing.span=6", "wing.ei=1e7", "wing.gj=1e6", "wing.rho=100", "wing.ip=10"];

/// The paper's configuration with `key=value` overrides applied.
pub fn paper_with(sets: &[&str]) -> Config {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    apply_overrides(&Config::paper(), &sets).expect("valid overrides")
}

/// Every full-rate peak of `simulate_with_error(cfg)` with its printed error contains the value
/// of a run on the doubled grid at dt = 1e-5 s (with its own initial layer and sub-step probe):
/// the estimate covers h and dt. A peak whose grid sequence does not converge says so
/// (grid_converged) rather than printing a Richardson bar.
pub fn assert_estimated_peaks_cover_a_finer_run(name: &str, cfg: &Config) {
    use wingcheck_sim::{simulate, simulate_with_error, RunOptions};
    let est = simulate_with_error(cfg, RunOptions::default()).unwrap();
    let mut fine = wingcheck_model::work::refined_in_space(cfg);
    fine.discretisation.dt = 1e-5;
    let reference = simulate(&fine, RunOptions::default()).unwrap();
    for (i, (e, r)) in est.peaks.signals().iter().zip(reference.peaks.signals()).enumerate() {
        let diff = (e.abs_max.value - r.abs_max).abs();
        assert!(
            diff <= e.abs_max.error,
            "{name}, signal {i}: {} ± {} vs finer {} (grid converged: {})",
            e.abs_max.value,
            e.abs_max.error,
            r.abs_max,
            e.grid_converged
        );
    }
}

/// Observed convergence order from errors at successively halved grids: log2(e_k / e_{k+1}).
pub fn orders(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

/// Observed order from three solutions on grids h, h/2, h/4 (no reference needed):
/// log2(|u_h − u_{h/2}| / |u_{h/2} − u_{h/4}|).
pub fn order_from_three(u1: f64, u2: f64, u3: f64) -> f64 {
    ((u1 - u2).abs() / (u2 - u3).abs()).log2()
}

/// Richardson extrapolation of u_{h/2} and u_h for a method of order p.
pub fn richardson(u_coarse: f64, u_fine: f64, p: f64) -> f64 {
    let f = 2f64.powf(p);
    (f * u_fine - u_coarse) / (f - 1.0)
}

/// The Goland wing (Goland 1945, the standard aeroelastic test wing, in SI units as tabulated
/// e.g. by Patil, Hodges & Cesnik 2001): semi-span 6.096 m, mass 35.71 kg/m, bending rigidity
/// 9.77e6 N m², torsional rigidity 0.987e6 N m², chord 1.8288 m with the elastic axis at 33 %
/// and the centre of mass at 43 % of the chord (x_c = 0.1 c = 0.18288 m, ρx_c = 6.531 kg), mass
/// moment of inertia 8.64 kg m about the centre of mass (I_p = 8.64 + ρx_c · x_c ≈ 9.83 kg m
/// about the elastic axis) and the aerodynamic centre at the quarter chord (x_ac = 0.08 c =
/// 0.1463 m).
pub const GOLAND: [&str; 7] = [
    "wing.span=6.096",
    "wing.rho=35.71",
    "wing.rho_xc=6.531",
    "wing.ei=9.77e6",
    "wing.gj=0.987e6",
    "wing.ip=9.83",
    "wing.x_ac=0.1463",
];

/// The five configurations a referee reads the report at (issue 47): the paper's; a = 1,
/// b = 3000 (a = 1 is the paper's already); the explicit observer; the Goland wing; k1 = 3,
/// ξ = 0.3, a = 0.5, b = 100.
pub const READER_CONFIGS: [(&str, &[&str]); 5] = [
    ("paper", &[]),
    ("a = 1, b = 3000", &["control.b=3000"]),
    ("explicit observer", &["observer.rule=explicit"]),
    ("Goland wing", &GOLAND),
    ("k1 = 3, xi = 0.3, a = 0.5, b = 100", &["control.k1=3", "wing.xi=0.3", "control.a=0.5", "control.b=100"]),
];
