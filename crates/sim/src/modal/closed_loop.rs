//! The closed loop in the modal basis as a linear system with held inputs: its coefficients
//! ([`LoopCoefficients`]), its matrix A (Ẋ = AX) and output rows ([`closed_loop`]) in the state
//! X = (p, ζ, w, u) of [`super::exact`]'s documentation, with [`INPUTS`] held inputs u. The
//! dense exponential scheme ([`super::exact`]) and the one in the loop's eigenbasis
//! ([`super::diagonal`]) both step this system; the set-ups kept between runs are keyed by its
//! coefficients ([`super::memo`]).

use faer::Mat;

use super::ModalBasis;

/// Number of held inputs in the state: ḡ1 − ĝ1, ḡ2 − ĝ2, φ̄, ĝ1, ĝ2.
pub(crate) const INPUTS: usize = 5;

/// What the closed loop's coefficients are: gains k_c (N/m, N m/rad), a, b, ξ, EI/GJ, signs.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LoopCoefficients {
    pub(crate) gain: [f64; 2],
    pub(crate) a: f64,
    pub(crate) b: f64,
    pub(crate) xi: f64,
    pub(crate) stiff: [f64; 2],
    pub(crate) sign: [f64; 2],
}

/// The closed loop's matrix A (Ẋ = AX) in X = (p, ζ, w, u) and its output rows c_c (τ_c = c_cᵀX),
/// for modes with frequencies `omega` and `tip_states` = 2 (ξ > 0) or 0.
pub(crate) fn closed_loop(
    basis: &ModalBasis,
    co: &LoopCoefficients,
    omega: &[f64],
    tip_states: usize,
) -> (Mat<f64>, [Vec<f64>; 2]) {
    let n = basis.len();
    let len = 2 * n + tip_states + INPUTS;
    let (w0, u0) = (2 * n, 2 * n + tip_states);
    let u = &basis.tip;
    // Tip values in X: x_c = Σ U_cj p_j/ω_j, v_c = Σ U_cj ζ_j; the tip force
    // f_c = −k_c(a x_c + b v_c) + (ḡ_c − ĝ_c).
    let force_row = |c: usize| -> Vec<f64> {
        let mut row = vec![0.0; len];
        for j in 0..n {
            row[j] = -co.gain[c] * co.a * u[c][j] / omega[j];
            row[n + j] = -co.gain[c] * co.b * u[c][j];
        }
        row[u0 + c] = 1.0;
        row
    };
    let force = [force_row(0), force_row(1)];
    let mut a = Mat::<f64>::zeros(len, len);
    for i in 0..n {
        a[(i, n + i)] = omega[i];
        a[(n + i, i)] = -omega[i];
        a[(n + i, n + i)] = -co.xi * basis.omega2[i];
        for (c, row) in force.iter().enumerate() {
            for (j, r) in row.iter().enumerate() {
                a[(n + i, j)] += u[c][i] * r;
            }
        }
        a[(n + i, u0 + 2)] = basis.load[i];
    }
    if tip_states == 2 {
        for (c, row) in force.iter().enumerate() {
            let scale = co.sign[c] / (co.xi * co.stiff[c]);
            for (j, r) in row.iter().enumerate() {
                a[(w0 + c, j)] += scale * r;
            }
            a[(w0 + c, w0 + c)] -= 1.0 / co.xi;
        }
    }
    // τ_c = f_c − (ḡ_c − ĝ_c) − ĝ_c
    let outputs = [0, 1].map(|c| {
        let mut row = force[c].clone();
        row[u0 + c] = 0.0;
        row[u0 + 3 + c] = -1.0;
        row
    });
    (a, outputs)
}
