//! Tests for exact polynomials and FE matrices.

use num_rational::BigRational;
use wingcheck_cert::exact::{frac, int};
use wingcheck_cert::fe::*;
use wingcheck_cert::poly::Poly;
use wingcheck_cert::RationalMatrix;

fn m(rows: Vec<Vec<BigRational>>) -> RationalMatrix {
    RationalMatrix::from_rows(rows).unwrap()
}

#[test]
fn poly_arithmetic() {
    let p = Poly::new(vec![int(1), int(2), int(3)]); // 1 + 2x + 3x²
    let q = Poly::new(vec![int(-1), int(1)]); // x − 1
                                              // (1 + 2x + 3x²)(x − 1) = −1 − x − x² + 3x³ (expanded by hand).
    assert_eq!(&p * &q, Poly::new(vec![int(-1), int(-1), int(-1), int(3)]));
    assert_eq!(&p + &q, Poly::new(vec![int(0), int(3), int(3)]));
    assert_eq!(&p - &p, Poly::zero());
    assert_eq!(p.derivative(), Poly::new(vec![int(2), int(6)]));
    // ∫_0^1 (1 + 2x + 3x²) dx = 1 + 1 + 1 = 3; ∫_{1/2}^{1} x dx = 3/8.
    assert_eq!(p.integrate(&int(0), &int(1)), int(3));
    assert_eq!(Poly::x().integrate(&frac(1, 2), &int(1)), frac(3, 8));
    assert_eq!(p.eval(&int(2)), int(17));
    assert_eq!(Poly::new(vec![int(0), int(0)]).degree(), None);
}

/// Hermite consistent mass h/420·[...] — Przemieniecki, *Theory of Matrix
/// Structural Analysis* (1968), consistent mass matrix of a beam element; also
/// Cook et al., *Concepts and Applications of FEA*, beam consistent mass.
fn textbook_hermite_mass(h: &BigRational) -> RationalMatrix {
    let h2 = h * h;
    let r = |a: i64, p: u8| {
        let base = int(a) * h / int(420);
        match p {
            0 => base,
            1 => base * h,
            _ => base * &h2,
        }
    };
    m(vec![
        vec![r(156, 0), r(22, 1), r(54, 0), r(-13, 1)],
        vec![r(22, 1), r(4, 2), r(13, 1), r(-3, 2)],
        vec![r(54, 0), r(13, 1), r(156, 0), r(-22, 1)],
        vec![r(-13, 1), r(-3, 2), r(-22, 1), r(4, 2)],
    ])
}

/// Euler–Bernoulli beam stiffness 1/h³·[...] — Logan, *A First Course in the
/// Finite Element Method*, beam element stiffness (with EI = 1).
fn textbook_hermite_stiffness(h: &BigRational) -> RationalMatrix {
    let c = int(1) / (h * h * h);
    let h2 = h * h;
    let e = |a: i64, p: u8| match p {
        0 => int(a) * &c,
        1 => int(a) * h * &c,
        _ => int(a) * &h2 * &c,
    };
    m(vec![
        vec![e(12, 0), e(6, 1), e(-12, 0), e(6, 1)],
        vec![e(6, 1), e(4, 2), e(-6, 1), e(2, 2)],
        vec![e(-12, 0), e(-6, 1), e(12, 0), e(-6, 1)],
        vec![e(6, 1), e(2, 2), e(-6, 1), e(4, 2)],
    ])
}

#[test]
fn element_matrices_match_textbook() {
    for h in [int(1), frac(3, 7), frac(22, 5)] {
        assert_eq!(hermite_mass(&h), textbook_hermite_mass(&h));
        assert_eq!(hermite_stiffness(&h), textbook_hermite_stiffness(&h));
        // Bar consistent mass h/6·[[2,1],[1,2]] and stiffness 1/h·[[1,−1],[−1,1]]
        // (Logan, bar element; Cook et al., consistent mass of a bar).
        let s = &h / int(6);
        assert_eq!(linear_mass(&h), m(vec![vec![int(2) * &s, s.clone()], vec![s.clone(), int(2) * &s]]));
        let k = int(1) / &h;
        assert_eq!(linear_stiffness(&h), m(vec![vec![k.clone(), -&k], vec![-&k, k.clone()]]));
        // Shifted Legendre orthogonality: ∫_0^h P_k² = h/(2k+1) (Abramowitz & Stegun 22.2.10, rescaled).
        let dg = dg_cubic_mass(&h);
        for i in 0..4 {
            for j in 0..4 {
                let want = if i == j { &h / int(2 * i as i64 + 1) } else { int(0) };
                assert_eq!(dg.get(i, j), &want);
            }
        }
    }
}

#[test]
fn cross_masses() {
    let h = frac(5, 3);
    let c = hermite_linear_cross_mass(&h);
    // ∫_0^1 (1−3x²+2x³)(1−x) dx = 1 − 1/2 − 1 + 5/4 − 2/5 = 7/20 (by hand), times h.
    assert_eq!(c.get(0, 0), &(frac(7, 20) * &h));
    // Rows summed over the linear basis (L1 + L2 = 1) give ∫N_i = [h/2, h²/12, h/2, −h²/12],
    // the consistent load vector of a uniform load (Logan, beam equivalent nodal forces).
    let load = [&h / int(2), &h * &h / int(12), &h / int(2), -(&h * &h) / int(12)];
    for (i, want) in load.iter().enumerate() {
        assert_eq!(&(c.get(i, 0) + c.get(i, 1)), want);
    }
    // P0 = 1, so column 0 of the Hermite×DG cross mass is the same load vector.
    let hd = hermite_dg_cross_mass(&h);
    for (i, want) in load.iter().enumerate() {
        assert_eq!(hd.get(i, 0), want);
    }
    // ∫_0^1 (1−x)(2x−1) dx = −1/6 and ∫_0^1 x(2x−1) dx = 1/6 (by hand), times h.
    let ld = linear_dg_cross_mass(&h);
    assert_eq!(ld.get(0, 0), &(&h / int(2)));
    assert_eq!(ld.get(0, 1), &(-&h / int(6)));
    assert_eq!(ld.get(1, 1), &(&h / int(6)));
    // Legendre P3 is orthogonal to every polynomial of degree ≤ 2, so to L1 (A&S 22.2.10).
    assert_eq!(ld.get(0, 3), &int(0));
}

/// Global nodal vectors of w = x² (Hermite), θ = x (linear) and x (DG).
fn interpolants(mesh: &ClampedMesh) -> (Vec<BigRational>, Vec<BigRational>, Vec<BigRational>) {
    let h = mesh.h();
    let n = mesh.elements();
    let mut wh = Vec::new();
    let mut th = Vec::new();
    let mut dg = Vec::new();
    for i in 1..=n {
        let x = &h * int(i as i64);
        wh.push(&x * &x);
        wh.push(int(2) * &x);
        th.push(x);
    }
    for e in 0..n {
        // x = a + h/2 + (h/2)·P1 on element [a, a + h].
        let a = &h * int(e as i64);
        dg.extend([a + &h / int(2), &h / int(2), int(0), int(0)]);
    }
    (wh, th, dg)
}

fn quad(a: &[BigRational], m: &RationalMatrix, b: &[BigRational]) -> BigRational {
    let mb = m.mul_vec(b).unwrap();
    a.iter().zip(&mb).map(|(x, y)| x * y).sum()
}

#[test]
fn global_assembly_integrates_exactly() {
    let s = frac(3, 2);
    let mesh = ClampedMesh::new(s.clone(), 5);
    let (wh, th, dg) = interpolants(&mesh);
    let pow = |k: i32| (0..k).fold(int(1), |acc, _| acc * &s);
    // ∫_0^s x⁴ = s⁵/5, ∫ (x²)''² = 4s, ∫ x² = s³/3, ∫ (x')² = s, ∫ x²·x = s⁴/4 (calculus).
    assert_eq!(quad(&wh, &mesh.mass(Space::Hermite, Space::Hermite), &wh), pow(5) / int(5));
    assert_eq!(quad(&wh, &mesh.hermite_stiffness(), &wh), int(4) * &s);
    assert_eq!(quad(&th, &mesh.mass(Space::Linear, Space::Linear), &th), pow(3) / int(3));
    assert_eq!(quad(&th, &mesh.linear_stiffness(), &th), s.clone());
    assert_eq!(quad(&wh, &mesh.mass(Space::Hermite, Space::Linear), &th), pow(4) / int(4));
    assert_eq!(quad(&wh, &mesh.mass(Space::Hermite, Space::DgCubic), &dg), pow(4) / int(4));
    assert_eq!(quad(&th, &mesh.mass(Space::Linear, Space::DgCubic), &dg), pow(3) / int(3));
    assert_eq!(quad(&dg, &mesh.mass(Space::DgCubic, Space::DgCubic), &dg), pow(3) / int(3));
    let k = mesh.hermite_stiffness();
    assert_eq!((k.rows(), k.cols()), (10, 10));
    assert!(k.is_symmetric());
    assert_eq!(mesh.mass(Space::Hermite, Space::Linear).cols(), 5);
}
