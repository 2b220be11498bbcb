//! The characteristic determinant of the uniform coupled bending–torsion cantilever's free
//! vibration: an independent reference for the wing's frequencies (the exact roots of the
//! continuous problem, no discretisation).

use wingcheck_model::Config;

/// e^A of a 6×6 matrix: Taylor series (30 terms) after scaling by 2^-m with ‖A‖/2^m ≤ 1/2,
/// then m squarings.
pub fn expm(a: &[[f64; 6]; 6]) -> [[f64; 6]; 6] {
    let norm = a.iter().map(|r| r.iter().map(|x| x.abs()).sum::<f64>()).fold(0.0, f64::max);
    let m = (norm / 0.5).log2().ceil().max(0.0) as i32;
    let s = 0.5f64.powi(m);
    let mut term = [[0.0; 6]; 6];
    let mut sum = [[0.0; 6]; 6];
    for i in 0..6 {
        term[i][i] = 1.0;
        sum[i][i] = 1.0;
    }
    let mul = |x: &[[f64; 6]; 6], y: &[[f64; 6]; 6]| {
        let mut z = [[0.0; 6]; 6];
        for i in 0..6 {
            for k in 0..6 {
                for j in 0..6 {
                    z[i][j] += x[i][k] * y[k][j];
                }
            }
        }
        z
    };
    let scaled = a.map(|r| r.map(|x| x * s));
    for k in 1..30 {
        term = mul(&term, &scaled).map(|r| r.map(|x| x / k as f64));
        for i in 0..6 {
            for j in 0..6 {
                sum[i][j] += term[i][j];
            }
        }
    }
    for _ in 0..m {
        sum = mul(&sum, &sum);
    }
    sum
}

/// The characteristic determinant of the free vibration at ω, in x = z/s ∈ [0, 1]: the ODE
/// q'''' = s⁴ω²(ρq − ρx_c θ)/EI, θ'' = s²ω²(ρx_c q − I_p θ)/GJ (from the model's PDE with
/// q, θ ∝ e^{iωt}) for y = (q, q', q'', q''', θ, θ'); the clamp leaves q''(0), q'''(0), θ'(0)
/// free, the free tip needs q''(1) = q'''(1) = θ'(1) = 0: D(ω) = det of that 3×3 block of e^A.
pub fn char_det(cfg: &Config, omega: f64) -> f64 {
    let w = &cfg.wing;
    let (al, be) = (w.span.powi(4) * omega * omega / w.ei, w.span.powi(2) * omega * omega / w.gj);
    let mut a = [[0.0; 6]; 6];
    a[0][1] = 1.0;
    a[1][2] = 1.0;
    a[2][3] = 1.0;
    a[3][0] = al * w.rho;
    a[3][4] = -al * w.rho_xc;
    a[4][5] = 1.0;
    a[5][0] = be * w.rho_xc;
    a[5][4] = -be * w.ip;
    let e = expm(&a);
    let (r, c) = ([2, 3, 5], [2, 3, 5]);
    let m = |i: usize, j: usize| e[r[i]][c[j]];
    m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)) - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0))
        + m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0))
}

/// Lowest root of D: scan up from 1 % of the smaller uncoupled frequency (ω₁ lies below both
/// by interlacing) in 0.5 % steps to the first sign change, then bisect to round-off.
pub fn omega1_reference(cfg: &Config) -> f64 {
    let w = &cfg.wing;
    let bending = 1.875104068711961f64.powi(2) / w.span.powi(2) * (w.ei / w.rho).sqrt();
    let torsion = std::f64::consts::FRAC_PI_2 / w.span * (w.gj / w.ip).sqrt();
    let mut lo = 0.01 * bending.min(torsion);
    let d0 = char_det(cfg, lo);
    let mut hi = lo;
    while char_det(cfg, hi).signum() == d0.signum() {
        lo = hi;
        hi *= 1.005;
        assert!(hi < 1.01 * bending.min(torsion), "no root below the uncoupled frequencies");
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if char_det(cfg, mid).signum() == d0.signum() {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The `count` lowest roots of D, ascending: a scan from 1 % of the smaller uncoupled
/// fundamental frequency in relative steps of 0.2 % (far below the gaps between the wing's
/// frequencies, which are ≥ 5 % on the wings tested), each sign change bisected to round-off.
pub fn roots(cfg: &Config, count: usize) -> Vec<f64> {
    let w = &cfg.wing;
    let bending = 1.875104068711961f64.powi(2) / w.span.powi(2) * (w.ei / w.rho).sqrt();
    let torsion = std::f64::consts::FRAC_PI_2 / w.span * (w.gj / w.ip).sqrt();
    let mut lo = 0.01 * bending.min(torsion);
    let mut d_lo = char_det(cfg, lo);
    let mut found = Vec::new();
    while found.len() < count {
        let hi = lo * 1.002;
        let d_hi = char_det(cfg, hi);
        if d_hi.signum() != d_lo.signum() {
            let (mut a, mut b) = (lo, hi);
            for _ in 0..200 {
                let mid = 0.5 * (a + b);
                if char_det(cfg, mid).signum() == d_lo.signum() {
                    a = mid;
                } else {
                    b = mid;
                }
            }
            found.push(0.5 * (a + b));
        }
        (lo, d_lo) = (hi, d_hi);
    }
    found
}
