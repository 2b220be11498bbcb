//! The finite-time rows' digital runs step the closed loop in the modal basis when the
//! simulator would (`wingcheck_sim::resolved_basis`), the nodal stepper otherwise. Both step
//! the same discrete equations (TR-BDF2, or the configured scheme), so a run's measurements
//! must agree between the bases to round-off: the reference is the nodal stepper, an
//! independent implementation of the same equations (a sparse banded solve per stage instead
//! of the Woodbury step on the modes).

use wingcheck_claims::finite_time::reach::{digital_run, DigitalChannel};
use wingcheck_model::{apply_overrides, Config, ObserverRule};
use wingcheck_sim::{resolved_basis, Discretisation};

fn config(sets: &[&str]) -> Config {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    apply_overrides(&Config::paper(), &sets).unwrap()
}

/// |modal − nodal| ≤ 2e-8 × the scale of the quantity's column (its largest magnitude over
/// the run), the tolerance of the modal/nodal agreement of every simulate output
/// (tests/basis.rs). Beyond the last bits the difference is the nodal stepper's: it measures
/// σ = s ξ S w − ν from the plant's tip state w (q‴(s), θ′(s), through a stiff solve), the
/// modal run accumulates σ by the exact identity σ_{n+1} − σ_n = h(ḡ − ĝ_k), and the implicit
/// rule amplifies σ's round-off by 1/T in ĝ and τ. Measured: 2.4e-13 N on g̃ at T = 1e-4 s on
/// the paper's wing; 1.5e-10 N on a τ jump of the SI-scale wing.
fn close(what: &str, modal: f64, nodal: f64, scale: f64) {
    let tol = 2e-8 * scale;
    assert!((modal - nodal).abs() <= tol, "{what}: modal {modal:e} against nodal {nodal:e} (tolerance {tol:e})");
}

fn largest(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

fn compare(label: &str, modal: &DigitalChannel, nodal: &DigitalChannel) {
    let (sigma, g_hat, tau) = (largest(&nodal.sigma), largest(&nodal.g_hat), largest(&nodal.tau));
    assert!(sigma > 0.0 && g_hat > 0.0 && tau > 0.0, "{label}: the traces hold the run");
    close(&format!("{label} σ(0)"), modal.sigma0, nodal.sigma0, sigma);
    assert_eq!(modal.reach_s, nodal.reach_s, "{label}: reaching times differ");
    close(&format!("{label} max |σ| after reaching"), modal.sigma_after_max, nodal.sigma_after_max, sigma);
    close(&format!("{label} max |g̃|"), modal.gtilde_max, nodal.gtilde_max, g_hat);
    close(&format!("{label} max ĝ jump"), modal.ghat_jump_max, nodal.ghat_jump_max, g_hat);
    close(&format!("{label} max τ jump"), modal.tau_jump_max, nodal.tau_jump_max, tau);
    assert_eq!(modal.t, nodal.t, "{label}: sample times differ");
    for (k, (m, n)) in modal.sigma.iter().zip(&nodal.sigma).enumerate() {
        close(&format!("{label} σ_{k}"), *m, *n, sigma);
    }
    for (k, (m, n)) in modal.g_hat.iter().zip(&nodal.g_hat).enumerate() {
        close(&format!("{label} ĝ_{k}"), *m, *n, g_hat);
    }
    for (k, (m, n)) in modal.tau.iter().zip(&nodal.tau).enumerate() {
        close(&format!("{label} τ_{k}"), *m, *n, tau);
    }
}

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
        let (_, basis) = resolved_basis(&cfg, &Discretisation::new(&cfg)).unwrap();
        let basis = basis.expect("these wings run in the modal basis");
        for rule in [ObserverRule::Implicit, ObserverRule::Explicit] {
            for period in [1e-3, 5e-4] {
                let modal = digital_run(&cfg, Some(&basis), rule, period, 1.2, 0.5, Some(0.0)).unwrap();
                let nodal = digital_run(&cfg, None, rule, period, 1.2, 0.5, Some(0.0)).unwrap();
                for (c, (m, n)) in modal.channels.iter().zip(&nodal.channels).enumerate() {
                    compare(&format!("{sets:?} {rule:?} T = {period} channel {c}"), m, n);
                    assert_eq!(m.t.len(), (1.2 / period).round() as usize + 1, "every sample is traced");
                    compared += 1;
                }
            }
        }
    }
    assert_eq!(compared, 32);
}

/// The comparison is not vacuous: another hold period changes the measurements far beyond
/// the tolerance.
#[test]
fn the_comparison_sees_a_different_run() {
    let cfg = config(&[]);
    let (_, basis) = resolved_basis(&cfg, &Discretisation::new(&cfg)).unwrap();
    let modal = digital_run(&cfg, basis.as_ref(), ObserverRule::Implicit, 1e-3, 1.2, 0.5, None).unwrap();
    let nodal = digital_run(&cfg, None, ObserverRule::Implicit, 5e-4, 1.2, 0.5, None).unwrap();
    let (m, n) = (&modal.channels[0], &nodal.channels[0]);
    assert!((m.gtilde_max - n.gtilde_max).abs() > 1e-8 * n.gtilde_max.abs() + 1e-10);
}
