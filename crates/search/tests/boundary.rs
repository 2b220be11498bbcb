//! The boundaries found by a search agree with the claim checker's independent answers:
//! W ≻ 0 ⟺ a/b < ω₁ (the converged fundamental frequency of the simulator's FE modes, the
//! threshold of the ledger's W-bounds row), (32) feasible ⟺ a/b < `closed_form_ratio`.

use wingcheck_claims::mu::best_point;
use wingcheck_model::{apply_overrides, Config};
use wingcheck_search::{run, RunControl, Search, SearchOptions, TheoryCache};
use wingcheck_theory::lyapunov::a_over_b_max;
use wingcheck_theory::lyapunov::{assemble, tight_constants, Coupling, LyapunovParams};
use wingcheck_theory::MuData;

/// Paper config with a short horizon (the theory does not depend on it; the simulation only
/// has to run).
fn short() -> Config {
    apply_overrides(&Config::paper(), &["horizon.t_end=0.2".into()]).expect("valid")
}

fn boundary_estimates(dir: &std::path::Path, kind: &str) -> Vec<(f64, f64, f64)> {
    let text = std::fs::read_to_string(dir.join("boundary.csv")).expect("boundary.csv");
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().expect("header").split(',').collect();
    let col = |name: &str| head.iter().position(|h| *h == name).expect("column");
    let (lo, hi, est) = (col("lo"), col("hi"), col("estimate"));
    lines
        .filter(|l| l.starts_with(kind))
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (f[lo].parse().unwrap(), f[hi].parse().unwrap(), f[est].parse().unwrap())
        })
        .collect()
}

/// The short paper config, the refinement tolerance 1e-6, and a complete refined search along
/// a ∈ [1e-5, 1] (11 log points) written to a temporary directory.
fn refined_search_along_a() -> (Config, f64, tempfile::TempDir) {
    let base = short();
    let tol = 1e-6;
    let search = Search::new(
        base.clone(),
        &["control.a=1e-5..1:log:11".into()],
        SearchOptions { refine: Some(tol), chunk_size: 4, ..Default::default() },
    )
    .expect("valid search");
    let dir = tempfile::tempdir().unwrap();
    let summary = run(&search, dir.path(), RunControl::default()).expect("runs");
    assert!(summary.complete);
    (base, tol, dir)
}

#[test]
fn boundaries_along_a_match_the_claim_checker() {
    let (base, tol, dir) = refined_search_along_a();

    // Reference 1: largest a/b with W ≻ 0 = ω₁, here the simulator's converged FE ω₁
    // (wingcheck_sim::modes::fundamental_frequency, Romberg over uniform meshes, error ~1e-12
    // relative); cross-checked against the pencil (W(1,0), W(0,1)) on V_8
    // (wingcheck_theory::lyapunov::a_over_b_max), an upper bound by Rayleigh–Ritz within 1e-3.
    // b = 1, so a* = (a/b)*.
    let w_ref = wingcheck_sim::modes::fundamental_frequency(&base).expect("ω₁").value;
    let pencil = a_over_b_max(&base, Coupling::Corrected, 8).expect("pencil");
    assert!(pencil >= w_ref && pencil - w_ref < 1e-3 * w_ref, "pencil {pencil} vs ω₁ {w_ref}");
    assert!((w_ref - 0.1209).abs() < 1e-3, "reference ω₁ ≈ 0.1209, got {w_ref}");
    let w = boundary_estimates(dir.path(), "w_positive_definite");
    assert_eq!(w.len(), 1, "one W ≻ 0 boundary crossing along a: {w:?}");
    let (lo, hi, est) = w[0];
    assert!(hi / lo - 1.0 <= tol, "bracket refined to the tolerance: [{lo}, {hi}]");
    // The bracket must contain the reference up to ω₁'s error estimate (≤ 1e-9 relative).
    assert!(lo <= w_ref * (1.0 + 1e-9) && w_ref <= hi * (1.0 + 1e-9), "[{lo}, {hi}] ∌ {w_ref}");
    assert!((est / w_ref - 1.0).abs() <= tol, "estimate {est} vs {w_ref}");
    // With a tolerance the W ≻ 0 boundary along a is the certified enclosure of ω₁ (b = 1),
    // not a bisection: its bounds, rounded outwards, and a note saying so.
    let e = wingcheck_claims::certify::omega1::compute(&base).expect("enclosure");
    assert!(lo <= e.1.lower_f64() && e.1.upper_f64() <= hi && hi / lo - 1.0 < 1e-8, "[{lo}, {hi}]");
    let csv = std::fs::read_to_string(dir.path().join("boundary.csv")).unwrap();
    let row = csv.lines().find(|l| l.starts_with("w_positive_definite")).unwrap();
    assert!(row.contains(",0,certified enclosure "), "{row}");

    // Reference 2: the closed-form boundary r* of the μ-conditions (crates/claims/src/mu.rs,
    // module docs): ≈ 3.58e-4 for the paper data (α = 0.00375, β = 0.0375, c = 7).
    let mu_ref = MuData::closed_form_ratio(&base);
    assert!((mu_ref - 3.58e-4).abs() < 0.01e-4, "reference r* ≈ 3.58e-4, got {mu_ref}");
    let m = boundary_estimates(dir.path(), "feasible_32");
    assert_eq!(m.len(), 1, "one (32) boundary crossing along a: {m:?}");
    let (lo, hi, est) = m[0];
    assert!(hi / lo - 1.0 <= tol);
    // The SOCP decides the sign of λ3* to clarabel's tolerance (~1e-8 absolute on λ3,
    // |dλ3/da| = O(ρ) = O(10)), so the boundary is located to ~1e-5 relative at worst.
    assert!((est / mu_ref - 1.0).abs() < 1e-4, "estimate {est} vs closed form {mu_ref}");
}

#[test]
fn the_w_boundary_along_b_is_the_certified_enclosure() {
    // a = 1, b ∈ [1, 100]: W ≻ 0 iff b > a/ω₁ ≈ 8.27; the enclosure gives b ∈ [a/ω̄₁, a/ω̲₁].
    let base = short();
    let search = Search::new(
        base.clone(),
        &["control.b=1..100:log:5".into()],
        SearchOptions { refine: Some(1e-6), ..Default::default() },
    )
    .unwrap();
    let dir = tempfile::tempdir().unwrap();
    assert!(run(&search, dir.path(), RunControl::default()).unwrap().complete);
    let w = boundary_estimates(dir.path(), "w_positive_definite");
    assert_eq!(w.len(), 1, "{w:?}");
    let (lo, hi, _) = w[0];
    // Reference: 1/ω₁ with the converged FE ω₁ (± ~1e-12 relative).
    let b_ref = 1.0 / wingcheck_sim::modes::fundamental_frequency(&base).unwrap().value;
    assert!(lo < b_ref && b_ref < hi && hi / lo - 1.0 < 1e-8, "[{lo}, {hi}] vs {b_ref}");
}

#[test]
fn coarse_verdicts_follow_the_ratio() {
    // Log grid over a (b = 1) without refinement: each point's verdicts agree with the
    // references away from the boundaries.
    let base = short();
    let search = Search::new(base.clone(), &["control.a=1e-5..1:log:6".into()], SearchOptions::default()).unwrap();
    let cache = TheoryCache::new(8);
    let runs = wingcheck_search::modal::RunCache::new();
    // converged ω₁ (wingcheck_sim::modes::fundamental_frequency), the threshold the search uses
    let w_ref = wingcheck_sim::modes::fundamental_frequency(&base).unwrap().value;
    let mu_ref = MuData::closed_form_ratio(&base);
    for p in 0..search.points() {
        let r = search.evaluate(p, &cache, &runs);
        let a: f64 = r.values[0].parse().unwrap();
        assert_eq!(r.w_positive_definite, Some(a < w_ref), "a = {a}");
        assert_eq!(r.feasible_32, Some(a < mu_ref), "a = {a}");
        assert_eq!(r.theorem_feasible(), Some(a < mu_ref.min(w_ref)));
    }
}

#[test]
fn fast_theory_matches_the_claims_functions() {
    // The search computes λ2, λ1 from the cached pencil; the claims crate assembles W(a, b)
    // and solves the generalised eigenproblem (lyapunov::tight_constants). Same N = 8.
    let base = short();
    let cache = TheoryCache::new(8);
    for (a, b) in [(1e-4, 1.0), (0.05, 2.0), (1.0, 1.0), (3e-3, 30.0)] {
        let cfg = apply_overrides(&base, &[format!("control.a={a}"), format!("control.b={b}")]).unwrap();
        let v = cache.verdicts(&cfg).unwrap();
        let t =
            tight_constants(&assemble(&LyapunovParams::from_config(&cfg, Coupling::Corrected, 8)).unwrap()).unwrap();
        let scale = t.lambda1.abs();
        assert!((v.lambda2 - t.lambda2).abs() <= 1e-10 * scale, "λ2 {} vs {}", v.lambda2, t.lambda2);
        assert!((v.lambda1 - t.lambda1).abs() <= 1e-10 * scale, "λ1 {} vs {}", v.lambda1, t.lambda1);
    }
    // λ and ε: the same fractions of λ3* as mu::best_point, with the λ1 from the cache.
    let cfg = apply_overrides(&base, &["control.a=1e-4".into()]).unwrap();
    let bounds = (0.2, 0.01, 0.02); // arbitrary positive (g_hmax, ζ3, ζ4); the same for both
    let t = cache.evaluate(&cfg, Some(bounds)).unwrap();
    let bp = best_point(&cfg, 1e-4, 1.0, bounds, 8).unwrap().expect("a/b = 1e-4 < r* is feasible");
    let rel = |x: f64, y: f64| (x - y).abs() / y.abs();
    assert!(rel(t.lambda.unwrap(), bp.lambda) < 1e-9, "λ {:?} vs {}", t.lambda, bp.lambda);
    assert!(rel(t.epsilon.unwrap(), bp.epsilon) < 1e-9, "ε {:?} vs {}", t.epsilon, bp.epsilon);
    let ub = (cfg.wing.span.powi(3) / t.lambda2.unwrap() * bp.epsilon / bp.lambda).sqrt();
    assert!(rel(t.uub_bound_q.unwrap(), ub) < 1e-9);
}

#[test]
fn refined_boundaries_meet_the_closed_forms_to_1e_6() {
    // grid step along a: a factor √10 (1e-5..1, 11 log points), so every bisected crossing
    // starts in a bracket of log-width ln √10 and bisection (geometric midpoints) needs
    // ⌈log2(ln √10 / ln(1 + tol))⌉ = 21 theory evaluations to reach hi/lo − 1 ≤ tol.
    let (base, tol, dir) = refined_search_along_a();
    let evaluations = (0.5 * 10f64.ln() / tol.ln_1p()).log2().ceil() as usize;
    assert_eq!(evaluations, 21);
    let rows = |kind: &str| -> Vec<(f64, f64, f64, usize)> {
        let text = std::fs::read_to_string(dir.path().join("boundary.csv")).unwrap();
        text.lines()
            .filter(|l| l.starts_with(kind))
            .map(|l| {
                let f: Vec<&str> = l.split(',').collect();
                (f[3].parse().unwrap(), f[4].parse().unwrap(), f[5].parse().unwrap(), f[7].parse().unwrap())
            })
            .collect()
    };
    // Closed form 1 (crates/claims wbounds, item 3): W ≻ 0 iff a/b < ω₁, the fundamental
    // frequency of the undamped wing — the simulator's converged FE ω₁
    // (wingcheck_sim::modes::fundamental_frequency, Romberg over uniform meshes 16, 32, …),
    // the threshold of the ledger's W-bounds row and of the search.
    let omega1 = wingcheck_sim::modes::fundamental_frequency(&base).unwrap().value;
    // Closed form 2 (crates/claims mu, module docs): (32) feasible iff a/b < r*.
    let r_star = MuData::closed_form_ratio(&base);
    for (kind, reference) in [("w_positive_definite", omega1), ("feasible_32", r_star)] {
        let r = rows(kind);
        assert_eq!(r.len(), 1, "{kind}: one crossing along a: {r:?}");
        let (lo, hi, est, n) = r[0];
        assert!(hi / lo - 1.0 <= tol, "{kind}: bracket [{lo}, {hi}] refined to {tol}");
        // (32) is bisected; W ≻ 0 along a needs no evaluation: its bracket is the certified
        // enclosure of ω₁ (b = 1).
        let expected = if kind == "feasible_32" { evaluations } else { 0 };
        assert_eq!(n, expected, "{kind}: the stated number of theory evaluations");
        assert!((est / reference - 1.0).abs() <= tol, "{kind}: estimate {est} vs closed form {reference}");
    }
}
