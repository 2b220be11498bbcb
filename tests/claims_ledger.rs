//! The ledger for any valid configuration: no NaN/inf/null anywhere, every evidence value a
//! labelled leaf, each verdict agrees with its own evidence, texts follow the facts of the run,
//! and the documented JSON shape (docs/ledger.md) is the one produced.

use proptest::prelude::*;
use serde_json::Value;
use wingcheck_claims::mu;
use wingcheck_claims::{check_all, CheckSettings, ClaimId, Evidence, Explain, Ledger, Study, Verdict};
use wingcheck_model::{apply_overrides, Config};
use wingcheck_theory::{Decision, MuData};

fn cfg_with(sets: &[String]) -> Config {
    apply_overrides(&Config::paper(), sets).expect("valid overrides")
}

fn short(extra: &[&str]) -> Config {
    let mut sets: Vec<String> = vec!["horizon.t_end=1".into()];
    sets.extend(extra.iter().map(|s| s.to_string()));
    cfg_with(&sets)
}

fn cases() -> u32 {
    std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(24)
}

fn no_non_finite(v: &Value) -> bool {
    match v {
        Value::Null => false,
        Value::Number(n) => n.as_f64().is_some_and(f64::is_finite),
        Value::Array(a) => a.iter().all(no_non_finite),
        Value::Object(m) => m.values().all(no_non_finite),
        _ => true,
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: cases() * 2, ..ProptestConfig::default() })]

    /// The mu-conditions evidence over random valid configurations (a log-uniform in
    /// [1e-6, 1e3], b/a in [1, 1e8], k1, k2 ∈ {0} ∪ [0.01, 10], ξ ∈ [0, 2], κ's in [0.1, 10]):
    /// finite, and the verdict follows the evidence.
    #[test]
    fn mu_evidence_is_finite_and_consistent(
        la in -6.0f64..3.0, lr in 0.0f64..8.0, k1 in prop_oneof![Just(0.0), 0.01f64..10.0],
        k2 in prop_oneof![Just(0.0), 0.01f64..10.0], xi in prop_oneof![Just(0.0), 0.0f64..2.0],
        kap in 0.1f64..10.0,
    ) {
        let a = 10f64.powf(la);
        let b = a * 10f64.powf(lr);
        let cfg = short(&[&format!("control.a={a}"), &format!("control.b={b}"), &format!("control.k1={k1}"),
            &format!("control.k2={k2}"), &format!("wing.xi={xi}"), &format!("observer.kappa1={kap}"),
            &format!("observer.kappa4={kap}")]);
        let m = mu::check(&cfg, &Study::new(), &CheckSettings::default()).unwrap();
        let v = m.row.evidence_json();
        prop_assert!(no_non_finite(&v), "{v}");
        let (verdict, _) = m.evidence.verdict();
        prop_assert_eq!(verdict == Verdict::Holds, m.evidence.satisfiable.value);
        let d = MuData::new(&cfg, a, b);
        // (32) holds iff a verified (exact) point exists, iff λ3* > 0 with k1, k2 > 0
        if m.evidence.satisfiable.value {
            let best = m.best().unwrap();
            prop_assert!(best.verified_exact);
            prop_assert!(best.lambda > 0.0 && best.epsilon.is_finite());
        }
        if k1 > 0.0 && k2 > 0.0 {
            prop_assert_eq!(m.evidence.satisfiable.value, d.lambda3_sup() > 0.0);
            // the closed-form boundary agrees (away from it by 1e-9 relative)
            let r = m.evidence.a_over_b_boundary.value;
            if (a / b - r).abs() > 1e-9 * r {
                prop_assert_eq!(m.evidence.satisfiable.value, a / b < r, "a/b = {} r* = {}", a / b, r);
            }
        }
        // an accepted solver answer agrees with the closed form
        if let Some(c) = &m.computed.lambda3_socp {
            if c.accepted {
                prop_assert!(c.relative_difference < 1e-6, "{c:?}");
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 5, ..ProptestConfig::default() })]

    /// The WHOLE check over random valid configurations (ranges as above; every κ drawn
    /// independently, so κ2 < ζ1 or κ5 < ζ2 occurs), horizon 2 s: it completes, the JSON holds
    /// no NaN/inf/null, every evidence value is a labelled leaf, and every row's verdict is the
    /// one its own evidence gives.
    #[test]
    fn whole_check_is_finite_and_consistent(
        la in -6.0f64..3.0, lr in 0.0f64..8.0, k1 in prop_oneof![Just(0.0), 0.01f64..10.0],
        k2 in prop_oneof![Just(0.0), 0.01f64..10.0], xi in prop_oneof![Just(0.0), 0.0f64..2.0],
        kap in proptest::array::uniform6(0.1f64..10.0),
    ) {
        let a = 10f64.powf(la);
        let b = a * 10f64.powf(lr);
        let mut sets: Vec<String> = vec!["horizon.t_end=2".into(), format!("control.a={a}"), format!("control.b={b}"),
            format!("control.k1={k1}"), format!("control.k2={k2}"), format!("wing.xi={xi}")];
        sets.extend(kap.iter().enumerate().map(|(i, k)| format!("observer.kappa{}={k}", i + 1)));
        let cfg = cfg_with(&sets);
        let l = check_all(&cfg).unwrap();
        prop_assert_eq!(l.rows.len(), ClaimId::ALL.len());
        prop_assert!(l.non_finite().is_empty(), "{:?}", l.non_finite());
        let v = serde_json::to_value(&l).unwrap();
        prop_assert!(no_non_finite(&v));
        for r in &l.rows {
            prop_assert!(!r.finding_text().contains("Internal error"), "{}: {}", r.id, r.finding_text());
        }
        verdict_matches_evidence(&l);
    }
}

/// Each row's verdict and basis are those its own evidence gives, and the row agrees with the
/// facts the evidence records.
fn verdict_matches_evidence(l: &Ledger) {
    for r in &l.rows {
        if let Some(e) = r.evidence.explain() {
            assert_eq!((r.verdict, r.basis), e.verdict(), "{}: verdict vs its own evidence", r.id);
            assert_eq!(r.finding, e.finding(), "{}", r.id);
            assert!(r.finding.len() <= 3, "{}: {:?}", r.id, r.finding);
        }
        assert!(r.evidence.nodes().is_ok(), "{}: {:?}", r.id, r.evidence.nodes());
        match &r.evidence {
            Evidence::WBounds(e) => {
                let d = e.w_positive_definite.value;
                let expect = match d {
                    Decision::Yes => Verdict::HoldsAfterCorrection,
                    Decision::No => Verdict::Fails,
                    Decision::Undecided => Verdict::Inconclusive,
                };
                assert_eq!(r.verdict, expect, "W-bounds");
                assert_eq!(
                    r.finding_text().contains("W is positive definite there"),
                    d == Decision::Yes,
                    "{}",
                    r.finding_text()
                );
            }
            Evidence::Mu(e) => assert_eq!(r.verdict == Verdict::Holds, e.satisfiable.value),
            Evidence::Uub(e) => {
                if e.bound_violated.value {
                    assert_eq!(r.verdict, Verdict::Fails);
                } else if e.w0_diverges.value {
                    assert_eq!(r.verdict, Verdict::Vacuous);
                }
            }
            Evidence::FiniteTime(e) => {
                if !e.hypothesis_holds.value {
                    assert_eq!(r.verdict, Verdict::Inconclusive);
                } else if e.sigma0.value == 0.0 && r.verdict != Verdict::Fails {
                    assert_eq!(r.verdict, Verdict::TriviallyTrue);
                }
            }
            _ => {}
        }
    }
}

#[test]
fn full_ledgers_off_the_paper_point_are_finite_and_consistent() {
    // the paper's wing off its gains, and an SI-scale wing (span 6 m, EI 1e7, GJ 1e6, ρ 100, I_p 10)
    let configs = [
        short(&["control.a=0.05"]),
        short(&["control.a=1", "control.b=2800", "control.k2=0"]),
        short(&[
            "wing.span=6",
            "wing.ei=1e7",
            "wing.gj=1e6",
            "wing.rho=100",
            "wing.ip=10",
            "wing.rho_xc=5",
            "initial.shape=cantilever",
        ]),
    ];
    for cfg in &configs {
        let l = check_all(cfg).unwrap();
        assert!(l.non_finite().is_empty(), "{:?}", l.non_finite());
        let json = serde_json::to_string(&l).unwrap();
        assert!(!json.contains("null") && !json.contains("NaN"));
        for r in &l.rows {
            assert!(!r.finding_text().contains("Internal error"), "{}: {}", r.id, r.finding_text());
        }
        verdict_matches_evidence(&l);
    }
}

#[test]
fn texts_follow_the_facts_of_the_run() {
    let study = Study::new();
    let settings = CheckSettings::default();
    // W-bounds: a/b = 0.05 < ω₁ ≈ 0.121 (positive definite) vs a/b = 1 (indefinite)
    let (lo, hi) = (short(&["control.a=0.05"]), short(&[]));
    let w = |c: &Config| wingcheck_claims::wbounds::check(c, &settings).unwrap().row.finding_text();
    let (wl, wh) = (w(&lo), w(&hi));
    assert!(wl.contains("W is positive definite") && !wh.contains("W is positive definite"));
    assert!(wh.contains("indefinite") && !wl.contains("indefinite"));
    // mu: a/b = 1e-4 < r* (satisfiable) vs 1 (μ3 < 0)
    let ml = mu::check(&short(&["control.a=1e-4"]), &study, &settings).unwrap().row.finding_text();
    let mh = mu::check(&hi, &study, &settings).unwrap().row.finding_text();
    assert!(ml.contains("can be met") && mh.contains("cannot hold") && mh.contains("μ3"), "{ml} / {mh}");
    // UUB: linear initial shape (W(0) = ∞) vs the clamp-compatible cantilever shape
    let uub = |cfg: &Config| {
        let st = Study::new();
        let w = wingcheck_claims::wbounds::check(cfg, &settings).unwrap();
        let m = mu::check(cfg, &st, &settings).unwrap();
        wingcheck_claims::uub::check(cfg, &w, &m, &st, &settings).unwrap().finding_text()
    };
    assert!(uub(&hi).contains("grows without bound"));
    assert!(!uub(&short(&["initial.shape=cantilever"])).contains("grows without bound"));
    // finite-time-1: σ1(0) = 0 at the paper's state (trivially true) vs ν1(0) = 0.5
    use wingcheck_claims::finite_time::{check as ft, Channel};
    let ftt = |c: &Config, ch| ft(c, ch, &settings).unwrap().finding_text();
    assert!(ftt(&hi, Channel::Bending).contains("nothing is tested"));
    assert!(!ftt(&short(&["observer.nu1_0=0.5"]), Channel::Bending).contains("nothing is tested"));
    // finite-time-2: hypothesis κ5 ≥ ζ2 = 0.06 holds at the paper's κ5 = 1, fails at 0.01
    assert!(ftt(&short(&["observer.kappa5=0.01"]), Channel::Torsion).contains("hypothesis fails"));
    assert!(!ftt(&hi, Channel::Torsion).contains("hypothesis fails"));
    // ftdo-vs-dobc: the tip-disturbance bounds quoted are this run's (0.08 N vs 0.5 N)
    use wingcheck_claims::comparison::check as cmp;
    assert!(cmp(&hi, &study, &settings).unwrap().details.join(" ").contains("ζ1 = 0.08000 N"));
    let amp = short(&["disturbance.tip_bending.amp=0.48"]);
    assert!(cmp(&amp, &study, &settings).unwrap().details.join(" ").contains("ζ1 = 0.5000 N"));
}

#[test]
fn lemma_texts_follow_the_span_and_the_exponent() {
    use wingcheck_claims::lemmas;
    let settings = CheckSettings::default();
    // Span f = 2 (the paper's): the counterexample is ω = z^k with the least k such that
    // 2k + 1 > f² = 4, i.e. k = 2: ω(2)² = 2⁴ = 16 > 2∫_0^2 z⁴ dz = 2·32/5 = 64/5 (by hand);
    // the degree-1 ratio is 3/f² = 0.75 (∫_0^1 x² = 1/3).
    let two = lemmas::check(&short(&[]), &settings).unwrap();
    let t2 = two.finding_text();
    assert!(t2.contains("on [0, 2 m]") && t2.contains("ω = z² "), "{t2}");
    assert!(t2.contains("ω(f)² = 16 > f∫ω² = 64/5"), "{t2}");
    assert!(two.details.join(" ").contains("(0.7500 at degree 1,"), "{:?}", two.details);
    assert!(two.assumptions.join(" ").contains("p = a1/a2 = 0.5385"), "{:?}", two.assumptions); // 7/13
                                                                                                // Span f = 6 with a1/a2 = 3/5: least k with 2k + 1 > 36 is k = 18; degree-1 ratio 3/36.
    let six = lemmas::check(&short(&["wing.span=6", "observer.a1=3", "observer.a2=5"]), &settings).unwrap();
    let t6 = six.finding_text();
    assert!(t6.contains("on [0, 6 m]") && t6.contains("ω = z¹⁸ "), "{t6}");
    assert!(six.details.join(" ").contains("(0.08333 at degree 1,"), "{:?}", six.details);
    assert!(six.assumptions.join(" ").contains("p = a1/a2 = 0.6000"), "{:?}", six.assumptions);
    assert!(!t6.contains("64/5") && !t6.contains("on [0, 2 m]"));
    // the evidence carries the same facts, exactly
    let Evidence::Lemmas(e) = &six.evidence else { panic!("lemmas evidence") };
    assert_eq!(e.lemma2_counterexample.omega.value, "z¹⁸");
    assert_eq!(e.lemma2_counterexample.f.value, 6.0);
    assert!(e.lemma2_counterexample.printed_violated.value);
}

/// `cfg` with the FTDO controller (the study's [`Study::ftdo`] run).
fn study_ftdo(cfg: &wingcheck_model::Config) -> wingcheck_model::Config {
    let mut c = cfg.clone();
    c.control.kind = wingcheck_model::ControllerKind::Ftdo;
    c
}

#[test]
fn each_distinct_simulation_runs_once() {
    let study = Study::new();
    let cfg = short(&[]);
    let a = study.ftdo(&cfg).unwrap();
    let b = study.ftdo(&cfg).unwrap();
    assert!(std::sync::Arc::ptr_eq(&a, &b));
    assert_eq!(study.simulations_run(), 1);
    // the mu row's FTDO run at the paper's gains is the configured run (kind = ftdo); the row
    // adds only its two refinements (ζ3, ζ4's ±), which the comparison's FTDO shares
    mu::check(&cfg, &study, &CheckSettings::default()).unwrap();
    assert_eq!(study.simulations_run(), 3);
    let plan = wingcheck_claims::comparison::Runs::of(&cfg, &CheckSettings::default());
    let shared = wingcheck_claims::study::refine::refinements(&study_ftdo(&cfg));
    assert!(shared.iter().all(|c| plan.refined().contains(c)), "the comparison refines the same FTDO run");
    // two threads asking for the same run at once: it runs once, both get it
    let other = short(&["control.a=0.7"]);
    let (x, y) = std::thread::scope(|s| {
        let x = s.spawn(|| study.ftdo(&other).unwrap());
        let y = s.spawn(|| study.ftdo(&other).unwrap());
        (x.join().unwrap(), y.join().unwrap())
    });
    assert!(std::sync::Arc::ptr_eq(&x, &y));
    assert_eq!(study.simulations_run(), 4);
}

/// docs/ledger.md documents the JSON shape with an example: its top-level keys, row keys and
/// mu-conditions evidence keys must be exactly those `check --json` produces.
#[test]
fn documented_ledger_shape_is_the_produced_one() {
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/ledger.md")).unwrap();
    let section = &doc[doc.find("## Example").expect("the example section")..];
    let start = section.find("```json").expect("a json example") + 7;
    let end = start + section[start..].find("```").unwrap();
    let example: Value = serde_json::from_str(&section[start..end]).expect("the example parses");
    let produced = serde_json::to_value(check_all(&short(&["control.a=1e-4"])).unwrap()).unwrap();
    let keys = |v: &Value| v.as_object().unwrap().keys().cloned().collect::<Vec<_>>();
    assert_eq!(keys(&example), keys(&produced));
    let ex_row = &example["rows"][0];
    let row = produced["rows"].as_array().unwrap().iter().find(|r| r["id"] == ex_row["id"]).unwrap();
    assert_eq!(keys(ex_row), keys(row));
    assert_eq!(keys(&ex_row["evidence"]), keys(&row["evidence"]));
    assert_eq!(keys(&ex_row["evidence"]["best"]), keys(&row["evidence"]["best"]));
    assert_eq!(keys(&example["settings"]), keys(&produced["settings"]));
    // every verdict and basis exists in the doc's vocabulary tables
    for v in Verdict::ALL {
        assert!(doc.contains(&format!("`{}`", v.name())), "verdict {} undocumented", v.name());
    }
    for b in wingcheck_claims::Basis::ALL {
        assert!(doc.contains(&format!("`{}`", b.name())), "basis {} undocumented", b.name());
    }
}

/// The work estimate's run plan is the runs `check` makes: at the paper's point, with the
/// explicit rule and at a point where (32) holds, the study simulates exactly the planned
/// configurations (each once).
#[test]
fn the_run_plan_is_what_check_simulates() {
    use wingcheck_claims::plan::check_runs;
    for extra in [vec![], vec!["observer.rule=explicit"], vec!["control.a=1e-4"]] {
        let cfg = short(&extra);
        let settings = CheckSettings::default();
        let study = Study::new();
        wingcheck_claims::check_all_with(&cfg, &study, &settings).unwrap();
        let mut simulated = study.keys();
        simulated.sort();
        let mut planned: Vec<String> =
            check_runs(&cfg, &settings).iter().map(wingcheck_claims::config_sha256).collect();
        planned.sort();
        assert_eq!(simulated, planned, "{extra:?}");
        assert_eq!(study.simulations_run(), planned.len());
    }
}
