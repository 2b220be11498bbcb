//! The convex layer of (29)–(32): closed forms against clarabel (re-verified), exactness,
//! scale invariance, and ε against an independent brute-force minimisation.

use wingcheck_model::Config;
use wingcheck_theory::convex::{check_epsilon, check_lambda3};
use wingcheck_theory::{best_point, DisturbanceBounds, MuData, WPencil};

fn paper() -> Config {
    Config::paper()
}

/// The points where the old formulation failed or accepted violated points (issue 10).
const ISSUE_POINTS: [(f64, f64); 12] = [
    (1.0, 2800.0),
    (1.0, 2900.0),
    (1.0, 3000.0),
    (1.0, 1e5),
    (2.0, 6000.0),
    (10.0, 3e4),
    (100.0, 1.0),
    (100.0, 3e5),
    (100.0, 1e7),
    (1.0 / 3000.0, 1.0),
    (1.0, 3500.0),
    (0.120861, 1.0),
];

#[test]
fn closed_form_lambda3_agrees_with_verified_clarabel_at_the_issue_points() {
    let cfg = paper();
    for (a, b) in ISSUE_POINTS {
        let d = MuData::new(&cfg, a, b);
        let c = check_lambda3(&d);
        assert!(c.accepted, "({a}, {b}): clarabel not accepted: {c:?}");
        // closed form (theory module docs) vs the solver's point, re-evaluated in the printed formulas
        assert!(c.relative_difference < 1e-6, "({a}, {b}): {c:?}");
    }
}

#[test]
fn epsilon_closed_form_agrees_with_verified_clarabel_where_feasible() {
    let cfg = paper();
    let bounds = DisturbanceBounds { g_hmax: 0.2, zeta3: 0.01, zeta4: 0.02 };
    let mut feasible = 0;
    for (a, b) in ISSUE_POINTS {
        let d = MuData::new(&cfg, a, b);
        let Some(p) = best_point(&d, 1.0, &bounds, 2.0, 1.0) else { continue };
        feasible += 1;
        assert!(p.verified_exact, "({a}, {b}): μ's not positive in exact arithmetic");
        let c = check_epsilon(&d, p.lambda3);
        assert!(c.accepted, "({a}, {b}): {c:?}");
        assert!(c.relative_difference < 1e-6, "({a}, {b}): {c:?}");
    }
    // a/b < r* = 3.5802e-4 (closed form of the paper's wing) at every point but (100, 1) and
    // (0.120861, 1)
    assert_eq!(feasible, 10);
}

/// Brute force over η5 (golden section on a fine bracket) with η1, η2, η6, η7 tight in the
/// printed μ3..μ6 and η3 = η4 = b/(2a): an independent route to min ε_η.
fn brute_force_eps_eta(d: &MuData, t: f64, g: f64) -> f64 {
    let c = d.c();
    let (r3, r4) = (d.a3() - t, d.a4() - t);
    let eps_at = |eta5: f64| {
        let eta1 = (r3 - c * eta5) / d.b;
        let eta2 = (r4 - c / eta5) / (d.b * d.x);
        let e3 = d.b / (2.0 * d.a);
        let eta6 = (d.a * d.ei - d.a * d.xi * d.ei / e3 - t) / (d.a * d.s.powi(4));
        let eta7 = (d.a * d.gj - d.a * d.xi * d.gj / e3 - t) / (d.a * d.s * d.s * d.x);
        (d.b / eta1 + d.b * d.x / eta2 + d.a / eta6 + d.a * d.x / eta7) * d.s * g * g
    };
    // bracket (c/R4, R3/c) in log space, then golden section
    let (mut lo, mut hi) = ((c / r4).ln(), (r3 / c).ln());
    let n = 2000;
    let mut best = (f64::INFINITY, lo);
    for i in 1..n {
        let x = lo + (hi - lo) * i as f64 / n as f64;
        let v = eps_at(x.exp());
        if v < best.0 {
            best = (v, x);
        }
    }
    let h = (hi - lo) / n as f64;
    lo = best.1 - h;
    hi = best.1 + h;
    let gr = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..200 {
        let (x1, x2) = (hi - gr * (hi - lo), lo + gr * (hi - lo));
        if eps_at(x1.exp()) <= eps_at(x2.exp()) {
            hi = x2;
        } else {
            lo = x1;
        }
    }
    eps_at((0.5 * (lo + hi)).exp())
}

#[test]
fn epsilon_equals_a_brute_force_minimisation_over_eta5() {
    let cfg = paper();
    for (a, b, frac) in [(1.0, 3000.0, 0.5), (1e-4, 1.0, 0.3), (3e-3, 30.0, 0.9), (2.0, 6000.0, 0.1)] {
        let d = MuData::new(&cfg, a, b);
        let t = frac * d.lambda3_sup();
        let closed = d.epsilon_eta_min(t, 0.2);
        let brute = brute_force_eps_eta(&d, t, 0.2);
        assert!((closed - brute).abs() <= 1e-6 * brute, "({a}, {b}): closed {closed} vs brute force {brute}");
    }
}

#[test]
fn forty_by_forty_grid_has_no_failures_and_is_scale_invariant() {
    let cfg = paper();
    let pencil = WPencil::new(&cfg, 4).unwrap();
    // ζ3 = ζ4 = 0: the observer terms ζ²/k of ε are not homogeneous in (a, b) (theory docs)
    let bounds = DisturbanceBounds { g_hmax: 0.2, zeta3: 0.0, zeta4: 0.0 };
    let scale = 1e3;
    let mut feasible = 0;
    let rel = |x: f64, y: f64| (x - y).abs() / y.abs().max(f64::MIN_POSITIVE);
    for i in 0..40 {
        for j in 0..40 {
            let a = 10f64.powf(-4.0 + 6.0 * i as f64 / 39.0);
            let b = a * 10f64.powf(1.0 + 5.0 * j as f64 / 39.0);
            let d = MuData::new(&cfg, a, b);
            let ds = MuData::new(&cfg, scale * a, scale * b);
            let l3 = d.lambda3_sup();
            assert!(l3.is_finite());
            assert!(rel(ds.lambda3_sup() / (scale * a), l3 / a) < 1e-6, "λ3*/a at ({a}, {b})");
            let decided = d.obstruction_exact(2.0, 1.0).is_none();
            assert_eq!(decided, l3 > 0.0, "exact criterion vs closed form at ({a}, {b})");
            if !decided {
                continue;
            }
            feasible += 1;
            let (l2, l1) = pencil.constants(a, b).unwrap();
            let (l2s, l1s) = pencil.constants(scale * a, scale * b).unwrap();
            let p = best_point(&d, l1, &bounds, 2.0, 1.0).expect("feasible");
            let ps = best_point(&ds, l1s, &bounds, 2.0, 1.0).expect("feasible");
            assert!(p.verified_exact && ps.verified_exact, "exact re-check at ({a}, {b})");
            assert!(rel(ps.epsilon / (scale * a), p.epsilon / a) < 1e-6, "ε/a at ({a}, {b})");
            assert!(rel(ps.lambda, p.lambda) < 1e-6, "λ at ({a}, {b})");
            if l2 > 0.0 {
                let ub = (cfg.wing.span.powi(3) / l2 * p.epsilon / p.lambda).sqrt();
                let ubs = (cfg.wing.span.powi(3) / l2s * ps.epsilon / ps.lambda).sqrt();
                assert!(rel(ubs, ub) < 1e-6, "UUB bound at ({a}, {b}): {ub} vs {ubs}");
            }
            let c = check_epsilon(&d, p.lambda3);
            assert!(c.accepted && c.relative_difference < 1e-6, "ε cross-check at ({a}, {b}): {c:?}");
        }
    }
    assert!(feasible > 100, "the grid crosses the boundary a/b = r*: {feasible} feasible points");
}
