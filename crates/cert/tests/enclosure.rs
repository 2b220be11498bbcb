//! Tests of the ω₁ enclosure's exact parts against independent truths: textbook element
//! matrices, an independent inertia count (signs of leading minors by pivoting Bareiss), the
//! closed form of the Green's-function trace and the analytic uncoupled spectrum, a Rayleigh
//! quotient integrated by hand, and the refusal of data that do not prove their bound.

use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use proptest::prelude::*;
use wingcheck_cert::banded::{inertia, SymBand};
use wingcheck_cert::enclosure::*;
use wingcheck_cert::exact::{frac, int, to_f64};
use wingcheck_cert::green::trace_g2;
use wingcheck_cert::psd::{check_positive_definite, determinant};
use wingcheck_cert::RationalMatrix;

fn unit_wing() -> WingConstants {
    WingConstants { span: int(1), rho: int(1), rho_xc: int(0), ei: int(1), gj: int(1), ip: int(1) }
}

/// The paper's wing (configs/paper.json): s = 2, ρ = 10, ρx_c = 7/2, EI = 1/5, GJ = 1/2, I_p = 3/2.
fn paper_wing() -> WingConstants {
    WingConstants { span: int(2), rho: int(10), rho_xc: frac(7, 2), ei: frac(1, 5), gj: frac(1, 2), ip: frac(3, 2) }
}

fn dense(b: &SymBand) -> RationalMatrix {
    RationalMatrix::from_fn(b.dim(), b.dim(), |i, j| b.get(i, j))
}

#[test]
fn one_element_pencil_is_the_textbook_beam_and_shaft() {
    // Unknowns of one element (s = 1): θ'(0), q(1), q'(1), θ(1), θ'(1). Textbook element
    // matrices (Przemieniecki 1968): bending EI/h³[12, 6h, −12, 6h; …; 4h²], geometric
    // (∫N'N') 1/(30h)[36, 3h, −36, 3h; 3h, 4h², −3h, −h²; …], mass h/420[156, 22h, 54, −13h; …; 4h²].
    let p = pencil(&unit_wing(), 1);
    let k = &p.stiffness;
    assert_eq!((k.get(1, 1), k.get(1, 2), k.get(2, 2)), (int(12), int(-6), int(4)));
    assert_eq!((k.get(3, 3), k.get(3, 4), k.get(4, 4)), (frac(36, 30), frac(-3, 30), frac(4, 30)));
    assert_eq!((k.get(0, 0), k.get(0, 3), k.get(0, 4)), (frac(4, 30), frac(-3, 30), frac(-1, 30)));
    assert!(k.get(1, 3).is_zero() && k.get(2, 4).is_zero(), "no elastic coupling");
    let m = &p.mass;
    assert_eq!((m.get(1, 1), m.get(1, 2), m.get(2, 2)), (frac(156, 420), frac(-22, 420), frac(4, 420)));
    assert_eq!((m.get(0, 0), m.get(0, 3), m.get(0, 4)), (frac(4, 420), frac(13, 420), frac(-3, 420)));
    // With ρx_c = 3/10 the cross mass is −ρx_c ∫N_a N_b: (q(1), θ(1)) gets −0.3·156/420.
    let p = pencil(&WingConstants { rho_xc: frac(3, 10), ..unit_wing() }, 1);
    assert_eq!(p.mass.get(1, 3), frac(-3, 10) * frac(156, 420));
    assert_eq!(p.mass.get(0, 1), frac(-3, 10) * frac(13, 420), "θ'(0) against q(1): ∫N2 N3 = 13h²/420");
}

#[test]
fn pencil_forms_agree_with_the_rayleigh_assembly_and_are_definite() {
    // Two assembly paths (banded pencil in scaled unknowns; element-wise quadratic forms of
    // the nodal vector) must give the same a(v, v) and m(v, v).
    let w = paper_wing();
    let n = 5;
    let p = pencil(&w, n);
    assert!(check_positive_definite(&dense(&p.stiffness)).is_ok());
    assert!(check_positive_definite(&dense(&p.mass)).is_ok());
    let h = &w.span / int(n as i64);
    let nodal: Vec<BigRational> =
        (0..4 * (n + 1)).map(|i| if i < 3 { int(0) } else { frac((i as i64 * 7919) % 23 - 11, 7) }).collect();
    let x: Vec<BigRational> = (0..unknowns(n))
        .map(|u| {
            let (node, field) = (0..=n)
                .flat_map(|j| (0..4).map(move |f| (j, f)))
                .find(|&(j, f)| unknown_index(j, f) == Some(u))
                .unwrap();
            let v = &nodal[4 * node + field];
            if field % 2 == 1 {
                v * &h
            } else {
                v.clone()
            }
        })
        .collect();
    let form = |b: &SymBand| {
        let d = dense(b);
        let y = d.mul_vec(&x).unwrap();
        x.iter().zip(&y).fold(BigRational::zero(), |acc, (a, b)| acc + a * b)
    };
    let (a, m, r) = rayleigh_quotient(&w, n, &nodal).unwrap();
    assert_eq!(a, form(&p.stiffness));
    assert_eq!(m, form(&p.mass));
    assert_eq!(r, &a / &m);
}

#[test]
fn rayleigh_quotient_of_a_cubic_state_is_the_hand_integral() {
    // q = z², θ = z are reproduced exactly by C¹ cubics, so R(v) on any mesh is the continuous
    // quotient: a = ∫ 4EI + GJ = (4EI + GJ)s, m = ∫ ρz⁴ − 2ρx_c z³ + I_p z² = ρs⁵/5 − ρx_c s⁴/2 + I_p s³/3.
    let w = paper_wing();
    let s = &w.span;
    for n in [1, 3, 8] {
        let h = s / int(n);
        let nodal: Vec<BigRational> = (0..=n)
            .flat_map(|j| {
                let z = &h * int(j);
                [&z * &z, int(2) * &z, z.clone(), int(1)]
            })
            .enumerate()
            .map(|(i, v)| if i == 3 { int(1) } else { v })
            .collect();
        let (a, m, _) = rayleigh_quotient(&w, n as usize, &nodal).unwrap();
        let s2 = s * s;
        assert_eq!(a, (int(4) * &w.ei + &w.gj) * s);
        assert_eq!(m, &w.rho * &s2 * &s2 * s / int(5) - &w.rho_xc * &s2 * &s2 / int(2) + &w.ip * &s2 * s / int(3));
    }
    // A state with q(0) ≠ 0 is not admissible: refused.
    let mut bad = vec![int(0); 4 * 3];
    bad[0] = frac(1, 1000);
    bad[5] = int(1);
    let e = rayleigh_quotient(&w, 2, &bad).unwrap_err();
    assert!(e.to_string().contains("violates the clamp: q(0)"), "{e}");
}

#[test]
fn trace_matches_its_closed_form_and_the_uncoupled_spectrum() {
    // Closed form by hand: ∫∫g_b² = 11s⁸/(1680EI²), ∫∫g_b g_t = 11s⁶/(360 EI GJ), ∫∫g_t² = s⁴/(6GJ²).
    let w = paper_wing();
    let (s, ei, gj) = (&w.span, &w.ei, &w.gj);
    let p = |k: u32| (0..k).fold(BigRational::one(), |acc, _| acc * s);
    let closed = int(11) * &w.rho * &w.rho * p(8) / (int(1680) * ei * ei)
        + int(11) * &w.rho_xc * &w.rho_xc * p(6) / (int(180) * ei * gj)
        + &w.ip * &w.ip * p(4) / (int(6) * gj * gj);
    assert_eq!(trace_g2(s, &w.rho, &w.rho_xc, ei, gj, &w.ip), closed);
    assert_eq!(trace_g2(s, &w.rho, &-&w.rho_xc, ei, gj, &w.ip), closed, "the sign of the coupling does not enter");
    // Uncoupled: Σ ω⁻⁴ over the analytic spectrum, bending ω = (βs)²/s²·√(EI/ρ) with
    // 1 + cos βs cosh βs = 0 (roots by bisection), torsion ω = (2j−1)π/(2s)·√(GJ/I_p).
    let u = WingConstants { rho_xc: int(0), ..paper_wing() };
    let (sf, rho, eif, gjf, ip): (f64, f64, f64, f64, f64) = (2.0, 10.0, 0.2, 0.5, 1.5);
    let root = |n: usize| {
        let (mut lo, mut hi) = ((n as f64 - 1.0) * std::f64::consts::PI, n as f64 * std::f64::consts::PI);
        let f = |x: f64| 1.0 + x.cos() * x.cosh();
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if f(lo).signum() == f(mid).signum() {
                lo = mid
            } else {
                hi = mid
            }
        }
        0.5 * (lo + hi)
    };
    let bending: f64 = (1..=60).map(|n| (root(n).powi(2) / (sf * sf) * (eif / rho).sqrt()).powi(-4)).sum();
    let torsion: f64 = (1..=200_000)
        .map(|j| ((2 * j - 1) as f64 * std::f64::consts::PI / (2.0 * sf) * (gjf / ip).sqrt()).powi(-4))
        .sum();
    let exact = to_f64(&u.trace_g2());
    assert!(((bending + torsion) / exact - 1.0).abs() < 1e-12, "{} vs {exact}", bending + torsion);
}

/// Negative eigenvalues by an independent route: sign changes of the leading principal minors
/// Δ_0 = 1, Δ_1, …, Δ_n (computed by pivoting Bareiss, `psd::determinant`), valid when none vanishes.
fn sign_changes(a: &RationalMatrix) -> Option<usize> {
    let n = a.rows();
    let mut prev = BigRational::one();
    let mut changes = 0;
    for k in 1..=n {
        let d = determinant(&RationalMatrix::from_fn(k, k, |i, j| a.get(i, j).clone())).unwrap();
        if d.is_zero() {
            return None;
        }
        changes += usize::from(d.is_negative() != prev.is_negative());
        prev = d;
    }
    Some(changes)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn banded_inertia_matches_leading_minor_signs(n in 1usize..9, bw in 0usize..4, seed in proptest::collection::vec(-9i64..10, 64)) {
        let mut b = SymBand::zeros(n, bw);
        let mut t = 0;
        for i in 0..n {
            for j in i..(i + bw + 1).min(n) {
                b.add_to(i, j, &frac(seed[t % seed.len()], 1 + (t as i64 % 3)));
                t += 1;
            }
        }
        let d = dense(&b);
        match (inertia(&b), sign_changes(&d)) {
            (Ok(i), Some(c)) => {
                prop_assert_eq!(i.negative, c);
                prop_assert_eq!(i.positive, n - c);
            }
            (Err(z), None) => prop_assert!(z.order >= 1 && z.order <= n),
            (r, c) => prop_assert!(false, "inertia {:?} but leading-minor count {:?}", r, c),
        }
    }
}

/// ω₁² of the uncoupled unit wing: min of bending (1.875104068711961…)⁴ (cantilever root, by
/// bisection below) and torsion (π/2)².
fn uncoupled_unit_eigenvalues() -> Vec<f64> {
    let mut v: Vec<f64> = (1..=6)
        .map(|n| {
            let (mut lo, mut hi) = ((n as f64 - 1.0) * std::f64::consts::PI, n as f64 * std::f64::consts::PI);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if (1.0 + lo.cos() * lo.cosh()).signum() == (1.0 + mid.cos() * mid.cosh()).signum() {
                    lo = mid
                } else {
                    hi = mid
                }
            }
            (0.5 * (lo + hi)).powi(4)
        })
        .chain((1..=6).map(|j| ((2 * j - 1) as f64 * std::f64::consts::PI / 2.0).powi(2)))
        .collect();
    v.sort_by(f64::total_cmp);
    v
}

#[test]
fn galerkin_counts_never_exceed_the_continuous_ones() {
    // Conformity: #{Galerkin eigenvalues < Λ} ≤ #{continuous eigenvalues < Λ} for every Λ
    // (min–max). Checked just above and below each of the lowest analytic eigenvalues.
    let ev = uncoupled_unit_eigenvalues();
    let p = pencil(&unit_wing(), 8);
    for (i, &l) in ev.iter().take(6).enumerate() {
        for (lam, continuous) in [(l * (1.0 - 1e-7), i), (l * (1.0 + 1e-3), i + 1)] {
            let lam = wingcheck_cert::exact::from_f64_exact(lam).unwrap();
            let c = shift_inertia(&p, &lam).unwrap().negative;
            assert!(c <= continuous, "Λ = {}: {c} Galerkin eigenvalues below, {continuous} continuous", to_f64(&lam));
            // …and the mesh resolves these low modes: just above ωᵢ² the counts agree.
            if continuous == i + 1 && i < 4 {
                assert_eq!(c, continuous, "mode {} not resolved at 8 elements", i + 1);
            }
        }
    }
}

fn data_for(
    w: &WingConstants,
    n: usize,
    shifts: Vec<BigRational>,
    nr: usize,
    vector: Vec<BigRational>,
) -> EnclosureData {
    EnclosureData { wing: w.clone(), inertia_elements: n, shifts, rayleigh_elements: nr, vector }
}

const LIMITS: Limits = Limits { max_modes: 8, max_inertia_elements: 8, max_rayleigh_elements: 8 };

#[test]
fn the_uncoupled_enclosure_contains_the_analytic_frequency_and_forgeries_are_refuted() {
    let w = unit_wing();
    let ev = uncoupled_unit_eigenvalues();
    let omega1 = ev[0].sqrt(); // 1.875104068711961² = 3.5160152…
                               // Shifts 1 % above ω₂² … ω₅² (8 elements resolve them to < 1e-3, as the test above
                               // shows); test vector: the cubic q = z²(3 − z), θ = 0.
    let shifts: Vec<BigRational> =
        ev[1..5].iter().map(|l| wingcheck_cert::exact::from_f64_exact(l * (1.0 + 1e-2)).unwrap()).collect();
    let nr = 4;
    let vector: Vec<BigRational> = (0..=nr)
        .flat_map(|j| {
            let z = frac(j as i64, nr as i64);
            [&z * &z * (int(3) - &z), &z * (int(6) - int(3) * &z), int(0), int(0)]
        })
        .collect();
    let c = check(&data_for(&w, 8, shifts.clone(), nr, vector.clone()), &LIMITS).unwrap();
    let (lo, hi) = (to_f64(&c.lower), to_f64(&c.upper));
    assert!(lo <= omega1 && omega1 <= hi, "{lo} ≤ {omega1} ≤ {hi}");
    assert_eq!(c.counts.len(), 4);
    assert!(c.counts.iter().enumerate().all(|(j, &n)| n >= j + 2));
    // The exact inequalities behind the rational bounds.
    assert!(&c.lower * &c.lower * &c.lower * &c.lower * &c.inverse_fourth_bound <= BigRational::one());
    assert!(&c.upper * &c.upper >= c.rayleigh);
    // Forgery: Λ₃ below the third Galerkin eigenvalue.
    let mut low = shifts.clone();
    low[1] = wingcheck_cert::exact::from_f64_exact(ev[2] * 0.99).unwrap();
    let e = check(&data_for(&w, 8, low, nr, vector.clone()), &LIMITS).unwrap_err();
    assert!(matches!(e, EnclosureError::ShiftTooLow { mode: 3, negative: 2, .. }), "{e}");
    // Forgery: the test vector moved off the clamp.
    let mut off = vector.clone();
    off[1] = frac(1, 10);
    let e = check(&data_for(&w, 8, shifts.clone(), nr, off), &LIMITS).unwrap_err();
    assert!(e.to_string().contains("violates the clamp: q'(0)"), "{e}");
    // Sizes beyond the limits are refused before any arithmetic.
    let e = check(&data_for(&w, 9, shifts.clone(), nr, vector.clone()), &LIMITS).unwrap_err();
    assert!(e.to_string().contains("inertia_elements: 9 outside [1, 8]"), "{e}");
    let e = check(&data_for(&w, 8, vec![int(1); 8], nr, vector.clone()), &LIMITS).unwrap_err();
    assert!(e.to_string().contains("k = 9 modes, at most 8"), "{e}");
    let e = check(&data_for(&w, 8, shifts.clone(), nr, vector[..8].to_vec()), &LIMITS).unwrap_err();
    assert!(e.to_string().contains("8 entries, 20 required"), "{e}");
    // A mass matrix that is not positive definite.
    let bad = WingConstants { rho_xc: int(2), ..w.clone() };
    let e = check(&data_for(&bad, 8, shifts, nr, vector), &LIMITS).unwrap_err();
    assert!(e.to_string().contains("ρ I_p > (ρx_c)²"), "{e}");
}
