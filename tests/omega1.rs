//! The certified enclosure ω̲₁ ≤ ω₁ ≤ ω̄₁ of the continuous wing against an independent
//! high-precision ω₁ (the characteristic determinant of the cantilever ODE, computed here), on
//! the paper's wing, an SI-scale wing and a short, strongly coupled wing; and the W-bounds
//! row's verdict resting on it at a/b = 0.9 ω₁, 1.1 ω₁ and inside the enclosure.

mod common;

use common::characteristic::omega1_reference;
use common::{paper_with, SI_WING};
use wingcheck_claims::certify::omega1::{self, Position};
use wingcheck_claims::{wbounds, Basis, CheckSettings, Verdict};

/// A short wing with heavy coupling (ρ I_p = 2 against (ρx_c)² = 1.44).
const COUPLED_WING: [&str; 6] =
    ["wing.span=0.5", "wing.rho=2", "wing.rho_xc=1.2", "wing.ei=3", "wing.gj=0.8", "wing.ip=1"];

#[test]
fn the_enclosure_contains_the_characteristic_determinant_root() {
    let mut si: Vec<&str> = SI_WING.to_vec();
    si.push("wing.rho_xc=3.5");
    for (name, sets, width) in
        [("paper", vec![], 1e-8), ("SI-scale", si, 1e-8), ("short coupled", COUPLED_WING.to_vec(), 2e-7)]
    {
        let cfg = paper_with(&sets);
        let reference = omega1_reference(&cfg);
        // A second, independent value: the simulator's ω₁ converged over FE meshes (its own
        // estimate ~1e-12; the two agree to ≤ 3e-15 on these wings).
        let fe = wingcheck_sim::modes::fundamental_frequency(&cfg).unwrap();
        println!("{name}: determinant root vs converged FE: {:.1e} relative", (reference / fe.value - 1.0).abs());
        assert!(
            (reference / fe.value - 1.0).abs() < 1e-13,
            "{name}: determinant root {reference:.15} vs converged FE {:.15}",
            fe.value
        );
        // The reference's uncertainty, taken as 1e-12 relative (≥ 300× the two methods'
        // disagreement), must lie entirely inside the certified enclosure.
        let c = omega1::compute(&cfg).unwrap();
        let e = &c.1;
        let (lo, hi) = (e.lower_f64(), e.upper_f64());
        println!(
            "{name}: {lo:.16} ≤ ω₁ = {reference:.16} ≤ {hi:.16}, relative width {:.2e} (below {:.2e}, above {:.2e})",
            e.relative_width(),
            1.0 - lo / reference,
            hi / reference - 1.0
        );
        assert!(lo <= reference * (1.0 - 1e-12) && reference * (1.0 + 1e-12) <= hi, "{name}: not contained");
        assert!(e.relative_width() <= width, "{name}: relative width {:.2e} > {width:.0e}", e.relative_width());
    }
}

/// The W-bounds row at a/b = a (b = 1): verdict, basis, its finding and details, the enclosure.
fn row_at(sets: &[&str], a: f64) -> (Verdict, Basis, String, wbounds::EnclosureEvidence) {
    let a_set = format!("control.a={a}");
    let mut sets = sets.to_vec();
    sets.extend(["control.b=1", a_set.as_str()]);
    let w = wbounds::check(&paper_with(&sets), &CheckSettings::default()).unwrap();
    let text = format!("{} {}", w.row.finding_text(), w.row.details.join(" "));
    (w.row.verdict, w.row.basis, text, w.evidence.omega1_enclosure.clone())
}

#[test]
fn the_w_bounds_verdict_rests_on_the_enclosure_outside_it_and_says_so_inside() {
    for sets in [vec![], SI_WING.to_vec()] {
        let cfg = paper_with(&sets);
        let (lo, hi) = {
            let c = omega1::compute(&cfg).unwrap();
            (c.1.lower_f64(), c.1.upper_f64())
        };
        let omega = 0.5 * (lo + hi);
        // a/b = 0.9 ω₁: W ≻ 0 proved; a/b = 1.1 ω₁: W proved not positive definite.
        let (v, b, s, e) = row_at(&sets, 0.9 * omega);
        assert_eq!(
            (v, b, e.position()),
            (Verdict::HoldsAfterCorrection, Basis::ExactCertificate, Some(Position::Below))
        );
        assert!(s.contains("proved: below the certified enclosure"), "{s}");
        let (v, b, s, e) = row_at(&sets, 1.1 * omega);
        assert_eq!((v, b, e.position()), (Verdict::Fails, Basis::ExactCertificate, Some(Position::Above)));
        assert!(s.contains("proved: above the certified enclosure"), "{s}");
        // Inside the enclosure the row says so, and its verdict is the float one (evidence).
        let (_, b, s, e) = row_at(&sets, omega);
        assert_eq!(e.position(), Some(Position::Inside), "{e:?}");
        assert_eq!(b, Basis::FloatSolver);
        assert!(s.contains("lies inside the certified enclosure"), "{s}");
    }
}

/// The ledger decides with the coarsest enclosure of the ladder that decides, and certify writes
/// the tightest: wherever the coarse one decides, the tightest (the certificate a referee
/// re-checks) decides the same, and its bounds are within the coarse ones.
#[test]
fn the_ledgers_coarse_enclosure_agrees_with_the_certificate_it_cites() {
    use wingcheck_claims::certify::omega1::EnclosureSummary;
    for sets in [vec![], SI_WING.to_vec()] {
        let omega = {
            let c = omega1::compute(&paper_with(&sets)).unwrap();
            0.5 * (c.1.lower_f64() + c.1.upper_f64())
        };
        for factor in [0.5, 0.9, 0.999, 1.001, 1.1, 8.0] {
            let a_set = format!("control.a={}", factor * omega);
            let mut s = sets.clone();
            s.extend(["control.b=1", a_set.as_str()]);
            let cfg = paper_with(&s);
            let (coarse, tight) = (EnclosureSummary::deciding(&cfg), EnclosureSummary::of(&cfg));
            assert_eq!(coarse.position(), tight.position(), "{factor}: {coarse:?} vs {tight:?}");
            let ((cl, cu), (tl, tu)) = (coarse.bounds().unwrap(), tight.bounds().unwrap());
            assert!(cl <= tl && tu <= cu, "{factor}: [{cl}, {cu}] does not contain [{tl}, {tu}]");
        }
    }
}

/// Just outside the certified enclosure the certificate decides the sign of λ2* (> 0 below,
/// < 0 above), while the float extrapolation of λ2* (→ 0 at ω₁) straddles 0 within its error:
/// the row then prints the proved sign and calls the float value unresolved, in the finding and
/// in the quantity's label. Well away from ω₁ the float value shows the sign and prints as is.
#[test]
fn near_omega1_the_row_prints_the_proved_sign_of_lambda2_not_an_unresolved_float() {
    let cfg = paper_with(&[]);
    let (lo, hi) = {
        let c = omega1::compute(&cfg).unwrap();
        (c.1.lower_f64(), c.1.upper_f64())
    };
    let tight = |a: f64| {
        let a_set = format!("control.a={a}");
        let w = wbounds::check(&paper_with(&["control.b=1", a_set.as_str()]), &CheckSettings::default()).unwrap();
        (w.evidence.lambda2_tight.clone(), w.row.finding_text(), w.evidence.omega1_enclosure.position())
    };
    // a/b 1e-6 below the lower bound and above the upper one (relative): outside the enclosure
    for (a, position, sign) in
        [(lo * (1.0 - 1e-6), Position::Below, "> 0"), (hi * (1.0 + 1e-6), Position::Above, "< 0")]
    {
        let (l2, finding, at) = tight(a);
        assert_eq!(at, Some(position));
        let error = l2.error().unwrap();
        assert!(l2.value - error <= 0.0 && 0.0 <= l2.value + error, "the float λ2* decides here: {l2:?}");
        assert!(l2.label.contains(&format!("λ2* {sign} is proved")), "{}", l2.label);
        assert!(finding.contains(&format!("λ2* {sign} (proved by the certified enclosure")), "{finding}");
    }
    // a/b = 0.5 ω₁: the float value is positive beyond its error and prints as it is
    let (l2, finding, _) = tight(0.25 * (lo + hi));
    assert!(l2.value - l2.error().unwrap() > 0.0 && !l2.label.contains("unresolved"), "{l2:?}");
    assert!(finding.contains(&format!("λ2* = {}", l2.pm_text())), "{finding}");
}
