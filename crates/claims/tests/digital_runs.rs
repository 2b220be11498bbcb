//! The finite-time rows' digital runs step the closed loop in the modal basis when the
//! simulator would (`wingcheck_sim::resolved_basis`), the nodal stepper otherwise. Both step
//! the same discrete equations (TR-BDF2, or the configured scheme), so a run's measurements
//! must agree between the bases to round-off: the reference is the nodal stepper, an
//! independent implementation of the same equations (a sparse banded solve per stage instead
//! of the Woodbury step on the modes).

use wingcheck_claims::finite_time::reach::{digital_run, DigitalChannel};
use wingcheck_model::{apply_overrides, Config, ObserverRule};
use wingcheck_sim::modal::ModalBasis;
use wingcheck_sim::{resolved_basis, Discretisation};

fn config(sets: &[&str]) -> Config {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    apply_overrides(&Config::paper(), &sets).unwrap()
}

fn modal_basis(cfg: &Config) -> ModalBasis {
    let (_, basis) = resolved_basis(cfg, &Discretisation::new(cfg)).unwrap();
    basis.expect("these wings run in the modal basis")
}

fn largest(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// The tolerances of one channel's comparison, from the nodal run's magnitudes.
///
/// - The plant: modal and nodal states agree within 2e-8 of their scale (the agreement of every
///   simulate output, tests/basis.rs); τ = −k(a x + b v) − ĝ inherits it.
/// - σ: the modal run accumulates σ by the exact identity σ_{n+1} − σ_n = h(ḡ − ĝ_k); the nodal
///   stepper measures σ = s ξ S w − ν from the plant's tip state w (q‴(s), θ′(s)) and ν, whose
///   magnitude grows like ∫ĝ: its round-off is a few ε·(|σ| + |ĝ| t_end); 64 ε of that.
/// - ĝ: the implicit rule turns σ's round-off into ĝ's by 1/T (measured: 2.4e-13 N on g̃ at
///   T = 1e-4 s on the paper's wing, where the bound below is 1.6e-11 N).
struct Tolerance {
    sigma: f64,
    g_hat: f64,
    tau: f64,
}

impl Tolerance {
    fn of(nodal: &DigitalChannel, period: f64, t_end: f64) -> Tolerance {
        let (sigma, g_hat, tau) = (largest(&nodal.sigma), largest(&nodal.g_hat), largest(&nodal.tau));
        assert!(sigma > 0.0 && g_hat > 0.0 && tau > 0.0, "the traces hold the run");
        let sigma_floor = 64.0 * f64::EPSILON * (sigma + g_hat * t_end);
        Tolerance {
            sigma: 2e-8 * sigma + sigma_floor,
            g_hat: 1e-8 * g_hat + sigma_floor / period,
            tau: 2e-8 * tau + sigma_floor / period,
        }
    }
}

fn close(what: &str, modal: f64, nodal: f64, tol: f64) {
    assert!((modal - nodal).abs() <= tol, "{what}: modal {modal:e} against nodal {nodal:e} (tolerance {tol:e})");
}

fn compare(label: &str, modal: &DigitalChannel, nodal: &DigitalChannel, tol: &Tolerance) {
    close(&format!("{label} σ(0)"), modal.sigma0, nodal.sigma0, tol.sigma);
    assert_eq!(modal.reach_s, nodal.reach_s, "{label}: reaching times differ");
    close(&format!("{label} max |σ| after reaching"), modal.sigma_after_max, nodal.sigma_after_max, tol.sigma);
    close(&format!("{label} max |g̃|"), modal.gtilde_max, nodal.gtilde_max, tol.g_hat);
    close(&format!("{label} max ĝ jump"), modal.ghat_jump_max, nodal.ghat_jump_max, tol.g_hat);
    close(&format!("{label} max τ jump"), modal.tau_jump_max, nodal.tau_jump_max, tol.tau);
    assert_eq!(modal.t, nodal.t, "{label}: sample times differ");
    for (k, (m, n)) in modal.sigma.iter().zip(&nodal.sigma).enumerate() {
        close(&format!("{label} σ_{k}"), *m, *n, tol.sigma);
    }
    for (k, (m, n)) in modal.g_hat.iter().zip(&nodal.g_hat).enumerate() {
        close(&format!("{label} ĝ_{k}"), *m, *n, tol.g_hat);
    }
    for (k, (m, n)) in modal.tau.iter().zip(&nodal.tau).enumerate() {
        close(&format!("{label} τ_{k}"), *m, *n, tol.tau);
    }
}

const T_END: f64 = 1.2;

#[test]
fn digital_runs_agree_in_the_modal_and_the_nodal_basis() {
    let wings: &[&[&str]] = &[
        &[],
        &["control.a=3", "control.b=0.2", "wing.xi=0.003", "control.k1=3"],
        &["initial.shape=cantilever", "observer.nu1_0=0.3", "observer.nu2_0=-0.2"],
        // an SI-scale wing
        &["wing.span=6", "wing.ei=1e7", "wing.gj=1e6", "wing.rho=100", "wing.ip=10", "wing.rho_xc=5"],
    ];
    let mut compared = 0;
    for sets in wings {
        let cfg = config(sets);
        let basis = modal_basis(&cfg);
        for rule in [ObserverRule::Implicit, ObserverRule::Explicit] {
            // the hold periods of the ledger (1e-2, 1e-3, 1e-4 s) and one more
            for period in [1e-2, 1e-3, 5e-4, 1e-4] {
                let modal = digital_run(&cfg, Some(&basis), rule, period, T_END, 0.5, Some(0.0)).unwrap();
                let nodal = digital_run(&cfg, None, rule, period, T_END, 0.5, Some(0.0)).unwrap();
                for (c, (m, n)) in modal.channels.iter().zip(&nodal.channels).enumerate() {
                    let tol = Tolerance::of(n, period, T_END);
                    compare(&format!("{sets:?} {rule:?} T = {period} channel {c}"), m, n, &tol);
                    assert_eq!(m.t.len(), (T_END / period).round() as usize + 1, "every sample is traced");
                    compared += 1;
                }
            }
        }
    }
    assert_eq!(compared, 64);
}

/// The comparison is not vacuous: the modal run of another scheme (trapezoid against the
/// nodal TR-BDF2, 1e-4 apart in tests/basis.rs) fails it.
#[test]
fn the_comparison_sees_another_scheme() {
    let cfg = config(&[]);
    let trapezoid = config(&["discretisation.stepper=trapezoid"]);
    let modal = digital_run(&trapezoid, Some(&modal_basis(&cfg)), ObserverRule::Implicit, 1e-3, T_END, 0.5, Some(0.0));
    let nodal = digital_run(&cfg, None, ObserverRule::Implicit, 1e-3, T_END, 0.5, Some(0.0)).unwrap();
    let (m, n) = (&modal.unwrap().channels[0], &nodal.channels[0]);
    let tol = Tolerance::of(n, 1e-3, T_END);
    let caught = std::panic::catch_unwind(|| compare("trapezoid against TR-BDF2", m, n, &tol));
    assert!(caught.is_err(), "the comparison did not see another scheme");
}

/// A run the modal driver stops as diverging (the explicit rule with κ_lin·T > 2 is unstable by
/// design) is measured by the nodal stepper, as it always was: the same numbers, whatever the
/// basis the simulator would use.
#[test]
fn a_diverging_digital_run_is_measured_as_the_nodal_stepper_measures_it() {
    let cfg = config(&["observer.kappa1=300", "observer.kappa4=300"]);
    let basis = modal_basis(&cfg);
    let modal = digital_run(&cfg, Some(&basis), ObserverRule::Explicit, 1e-2, T_END, 0.5, None).unwrap();
    let nodal = digital_run(&cfg, None, ObserverRule::Explicit, 1e-2, T_END, 0.5, None).unwrap();
    assert_eq!(modal, nodal);
    // it did diverge: the jumps of ĝ over the chatter window are huge
    assert!(nodal.channels[0].ghat_jump_max > 1e6 || !nodal.channels[0].ghat_jump_max.is_finite());
}
