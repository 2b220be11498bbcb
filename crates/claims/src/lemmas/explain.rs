//! The lemmas row's evidence (labelled quantities), verdict and words.

use wingcheck_model::{Config, Quantity, Unit, ValueBasis};

use super::{compute, Computed};
use crate::display::{Flag, Table, Text};
use crate::explain::Explain;
use crate::settings::CheckSettings;
use crate::{Basis, ClaimId, ClaimRow, ClaimsError, Line, PlotData, Verdict};

/// One polynomial degree of the Lemma 2 search.
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct DegreeRecord {
    /// Largest degree K of ω = Σ c_k z^k.
    pub degree: Quantity,
    /// max ω(f)²/(f∫ω²) (printed (12)).
    pub printed: Quantity,
    /// max ω(f)²/(f∫ω'²) (corrected).
    pub corrected: Quantity,
}

/// The exact counterexample to the printed Lemma 2 on the configured span.
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct Lemma2Counterexample {
    /// The span f.
    pub f: Quantity,
    /// The function.
    pub omega: Text,
    /// ω(f)², exact.
    pub lhs_omega_f_sq: Text,
    /// f∫ω², exact.
    pub rhs_printed: Text,
    /// ω(f)² > f∫ω², decided exactly.
    pub printed_violated: Flag,
    /// f∫ω'², exact.
    pub rhs_corrected: Text,
    /// ω(f)² ≤ f∫ω'², decided exactly.
    pub corrected_holds: Flag,
}

/// The evidence of the `lemmas` row.
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct LemmasEvidence {
    /// max xy/(x²/c + c y²) found.
    pub lemma1_max_ratio: Quantity,
    /// Lemma 1 (11) holds (the maximum is ≤ 1).
    pub lemma1_holds: Flag,
    /// The sharp constant k of xy ≤ k(x²/c + c y²).
    pub lemma1_sharp_constant: Quantity,
    /// The Lemma 2 search per degree.
    pub lemma2_by_degree: Table<DegreeRecord>,
    /// The printed (12) survived the search.
    pub lemma2_printed_holds: Flag,
    /// Largest corrected ratio.
    pub lemma2_corrected_max_ratio: Quantity,
    /// The exact counterexample.
    pub lemma2_counterexample: Lemma2Counterexample,
    /// Equality cases of the comparison ODE.
    pub lemma3_cases: Quantity,
    /// max |RK4 − (14)|/(14) over them.
    pub lemma3_max_rel_err: Quantity,
    /// Inequality cases.
    pub lemma3_ineq_cases: Quantity,
    /// Inequality cases slower than (14).
    pub lemma3_violations: Quantity,
    /// Data of the Lemma 3 plot (context, not serialised).
    #[serde(skip)]
    pub lemma3_points: Vec<(f64, f64)>,
    /// p = a1/a2 and σ2(0)²/2 (context, not serialised).
    #[serde(skip)]
    pub p_and_q0: (f64, f64),
}

fn evidence_of(c: &Computed) -> LemmasEvidence {
    let ratio = |label: &str, v: f64| Quantity::based(label, v, Unit::Dimensionless, ValueBasis::SearchMaximum);
    let cx = &c.counterexample;
    let corr_max = c.corrected.iter().cloned().fold(0.0, f64::max);
    let violated = cx.printed_violated;
    let (ineq, viol) = c.lemma3_inequality;
    LemmasEvidence {
        lemma1_max_ratio: ratio("Lemma 1: max xy/(x²/c + c y²)", c.lemma1_max_ratio),
        lemma1_holds: Flag::new("Lemma 1 (11) holds (max ≤ 1)", c.lemma1_max_ratio <= 1.0),
        lemma1_sharp_constant: Quantity::exact("sharp constant k of xy ≤ k(x²/c + c y²)", 0.5, Unit::Dimensionless),
        lemma2_by_degree: Table::new(
            "Lemma 2: best ratio over polynomials of degree ≤ K with ω(0) = 0",
            c.printed
                .iter()
                .zip(&c.corrected)
                .enumerate()
                .map(|(k, (p, q))| DegreeRecord {
                    degree: Quantity::count("degree K", k + 1),
                    printed: Quantity::based(
                        "ω(f)²/(f∫ω²), printed (12)",
                        *p,
                        Unit::Dimensionless,
                        ValueBasis::ClosedForm,
                    ),
                    corrected: Quantity::based(
                        "ω(f)²/(f∫ω'²), corrected",
                        *q,
                        Unit::Dimensionless,
                        ValueBasis::ClosedForm,
                    ),
                })
                .collect(),
        ),
        lemma2_printed_holds: Flag::new(
            "printed (12) survived the search",
            c.printed.iter().all(|&r| r <= 1.0) && !violated,
        ),
        lemma2_corrected_max_ratio: ratio("Lemma 2 corrected: max ω(f)²/(f∫ω'²)", corr_max),
        lemma2_counterexample: Lemma2Counterexample {
            f: Quantity::configured("span f", c.span, Unit::Metre),
            omega: Text::text("counterexample ω", cx.omega.clone()),
            lhs_omega_f_sq: Text::text("ω(f)², exact", cx.lhs.clone()),
            rhs_printed: Text::text("f∫ω², exact", cx.rhs_printed.clone()),
            printed_violated: Flag::new("ω(f)² > f∫ω² (printed (12) violated)", violated),
            rhs_corrected: Text::text("f∫ω'², exact", cx.rhs_corrected.clone()),
            corrected_holds: Flag::new("ω(f)² ≤ f∫ω'² (corrected form holds)", cx.corrected_holds),
        },
        lemma3_cases: Quantity::count("Lemma 3: equality cases", c.lemma3_points.len()),
        lemma3_max_rel_err: ratio("Lemma 3: max |RK4 − (14)|/(14)", c.lemma3_max_rel_err),
        lemma3_ineq_cases: Quantity::count("Lemma 3: inequality cases", ineq),
        lemma3_violations: Quantity::count("of which slower than (14)", viol),
        lemma3_points: c.lemma3_points.clone(),
        p_and_q0: (c.p, c.q0_config),
    }
}

impl LemmasEvidence {
    /// Lemma 3 reproduced: the RK4 times agree with (14) to 1e-6 and no inequality case is slower.
    fn lemma3_holds(&self) -> bool {
        self.lemma3_max_rel_err.value < 1e-6 && self.lemma3_violations.value == 0.0
    }

    fn corrected_ok(&self) -> bool {
        self.lemma2_corrected_max_ratio.value <= 1.0 + 1e-9
    }
}

impl Explain for LemmasEvidence {
    /// Lemma 1, Lemma 3 or the corrected Lemma 2 fails numerically → fails (computation);
    /// only the printed Lemma 2 fails → holds after correction, resting on the exact
    /// counterexample and the closed-form inequalities (AM–GM, Cauchy–Schwarz, the exact
    /// solution of the comparison ODE): analytic; nothing refuted → holds (the searches only).
    fn verdict(&self) -> (Verdict, Basis) {
        if !self.lemma1_holds.value || !self.lemma3_holds() || !self.corrected_ok() {
            (Verdict::Fails, Basis::Computation)
        } else if !self.lemma2_printed_holds.value {
            (Verdict::HoldsAfterCorrection, Basis::Analytic)
        } else {
            (Verdict::Holds, Basis::Computation)
        }
    }

    fn finding(&self) -> Vec<String> {
        let cx = &self.lemma2_counterexample;
        vec![
            if self.lemma1_holds.value {
                format!(
                    "Lemma 1 (11) holds but loosely: the largest xy/(x²/c + c y²) is {} (sharp constant ½).",
                    self.lemma1_max_ratio.value_text()
                )
            } else {
                format!("Lemma 1 (11) fails here: max xy/(x²/c + c y²) = {} > 1.", self.lemma1_max_ratio.value_text())
            },
            if cx.printed_violated.value {
                let rounded = [&cx.lhs_omega_f_sq, &cx.rhs_printed].iter().any(|t| t.value.starts_with('≈'));
                let eq = |t: &Text| match t.value.strip_prefix('≈') {
                    Some(v) => format!("≈ {v}"),
                    None => format!("= {}", t.value),
                };
                format!(
                    "Lemma 2 (12) is false as printed: on [0, {}] ω = {} has ω(f)² {} > f∫ω² {} ({}); the corrected ω(z)² ≤ z∫ω'² holds{}.",
                    cx.f.value_text(),
                    cx.omega.value,
                    eq(&cx.lhs_omega_f_sq),
                    eq(&cx.rhs_printed),
                    if rounded { "exact rationals, compared exactly, shown rounded" } else { "exact" },
                    if self.corrected_ok() { " with sharp constant 1" } else { " NOT in the search" }
                )
            } else {
                "Lemma 2 (12) was not refuted here.".to_string()
            },
            if self.lemma3_holds() {
                format!(
                    "Lemma 3's (14) is the exact reaching time of the comparison ODE (an independent RK4 agrees within {} over {} cases).",
                    self.lemma3_max_rel_err.value_text(),
                    self.lemma3_cases.value_text()
                )
            } else {
                format!(
                    "Lemma 3 is not reproduced: RK4 differs from (14) by up to {}, {} of {} inequality cases are slower.",
                    self.lemma3_max_rel_err.value_text(),
                    self.lemma3_violations.value_text(),
                    self.lemma3_ineq_cases.value_text()
                )
            },
        ]
    }

    fn decisive(&self) -> Vec<Quantity> {
        vec![self.lemma1_max_ratio.clone(), self.lemma2_corrected_max_ratio.clone(), self.lemma3_max_rel_err.clone()]
    }

    fn deciding(&self) -> String {
        let cx = &self.lemma2_counterexample;
        if !self.lemma1_holds.value {
            format!("Lemma 1: max xy/(x²/c + c y²) = {} > 1", self.lemma1_max_ratio.value_text())
        } else if !self.corrected_ok() {
            format!("corrected Lemma 2: max ω(f)²/(f∫ω'²) = {} > 1", self.lemma2_corrected_max_ratio.value_text())
        } else if !self.lemma3_holds() {
            format!("Lemma 3: RK4 differs from (14) by up to {}", self.lemma3_max_rel_err.value_text())
        } else if cx.printed_violated.value {
            format!("Lemma 2 as printed: ω = {} has ω(f)² > f∫ω² (exact)", cx.omega.value)
        } else {
            format!("all three reproduced; Lemma 3 to {}", self.lemma3_max_rel_err.value_text())
        }
    }

    fn details(&self) -> Vec<String> {
        let rows = &self.lemma2_by_degree.rows;
        let (first, last) = (rows.first(), rows.last());
        let mut d = Vec::new();
        if let (Some(a), Some(b)) = (first, last) {
            d.push(format!(
                "The best printed ratio ω(f)²/(f∫ω²) grows with the degree ({} at degree {}, {} at degree {}) and is unbounded as the degree grows.",
                a.printed.value_text(),
                a.degree.value_text(),
                b.printed.value_text(),
                b.degree.value_text()
            ));
        }
        d.push("Lemma 1 is written with x, y, c for the paper's a, b, p (not the weights of (15)); its sharp form is xy ≤ x²/(2c) + c y²/2 (AM–GM, equality at x = c y); Lemma 2's corrected form follows from Cauchy–Schwarz and is the one (36) uses.".into());
        d.push(format!(
            "Lemma 3's inequality cases: {} of {} are slower than (14).",
            self.lemma3_violations.value_text(),
            self.lemma3_ineq_cases.value_text()
        ));
        d
    }

    fn correction(&self) -> Option<String> {
        (!self.lemma2_printed_holds.value).then(|| {
            "Lemma 2 (12) must read ω̄(z)² ≤ z∫_0^z ω̄'(s)² ds ≤ f∫_0^f ω̄'(s)² ds (derivative inside the integral); \
             Lemma 1 may be sharpened to xy ≤ x²/(2c) + c y²/2 (the paper's a, b, p written x, y, c)"
                .to_string()
        })
    }
}

fn plots(e: &LemmasEvidence) -> Vec<PlotData> {
    let line = |label: &str, x: Vec<f64>, y: Vec<f64>, points: bool| Line { label: label.into(), x, y, points };
    let rows = &e.lemma2_by_degree.rows;
    let degrees: Vec<f64> = rows.iter().map(|r| r.degree.value).collect();
    let (xs, ys): (Vec<f64>, Vec<f64>) = e.lemma3_points.iter().copied().unzip();
    let lo = xs.iter().cloned().fold(f64::MAX, f64::min);
    let hi = xs.iter().cloned().fold(0.0, f64::max);
    let kmax = degrees.last().copied().unwrap_or(1.0);
    vec![
        PlotData {
            name: "lemmas-lemma2".into(),
            title: format!(
                "Lemma 2 on [0, {}]: best ratio over polynomials of degree ≤ K; printed (12) reaches {}, corrected form {}",
                e.lemma2_counterexample.f.value_text(),
                rows.last().map_or("—".into(), |r| r.printed.value_text()),
                e.lemma2_corrected_max_ratio.value_text()
            ),
            x_label: "degree K".into(),
            y_label: "max ω(f)² / (f ∫ …)".into(),
            log_x: false,
            log_y: true,
            lines: vec![
                line("printed: f ∫ ω²", degrees.clone(), rows.iter().map(|r| r.printed.value).collect(), true),
                line("corrected: f ∫ ω'²", degrees, rows.iter().map(|r| r.corrected.value).collect(), true),
                line("limit 1", vec![1.0, kmax], vec![1.0, 1.0], false),
            ],
        },
        PlotData {
            name: "lemmas-lemma3".into(),
            title: format!(
                "Lemma 3: numerical reaching time against (14), {} cases, max relative difference {}",
                e.lemma3_cases.value_text(),
                e.lemma3_max_rel_err.value_text()
            ),
            x_label: "t_f from (14) (s)".into(),
            y_label: "t_f by RK4 (s)".into(),
            log_x: true,
            log_y: true,
            lines: vec![line("cases", xs, ys, true), line("y = x", vec![lo, hi], vec![lo, hi], false)],
        },
    ]
}

/// Check Lemmas 1–3.
pub fn check(cfg: &Config, settings: &CheckSettings) -> Result<ClaimRow, ClaimsError> {
    let c = compute(cfg, settings)?;
    let e = evidence_of(&c);
    let fmt = |v: f64| wingcheck_model::quantity::format_value(v, None);
    let assumptions = vec![
        "Lemma 2 read with ω̄ = ω̄(z) at any z ∈ [0, f]; searched at z = f (the worst point for increasing ω)".into(),
        format!(
            "Lemma 2 search space: polynomials ω(z) = Σ_{{k=1}}^K c_k z^k (coefficients c_k), K ≤ {}, on the configured span f = {}",
            settings.lemma2_max_degree,
            e.lemma2_counterexample.f.value_text()
        ),
        format!(
            "Lemma 3 grid: φ1 ∈ {{0.1, 1.6, 10}}, φ2 ∈ {{0.1, 2^p·4, 50}}, φ3 ∈ {{0.1, p, 0.9}} with p = a1/a2 = {}, Q0 ∈ {{10⁻⁴, σ2(0)²/2 = {}, 1, 100}}; inequality cases ψ = c φ2 (1 + sin 5t), c ∈ {{0.1, 1}}",
            fmt(c.p),
            fmt(c.q0_config)
        ),
    ];
    let plots = plots(&e);
    Ok(ClaimRow::decided(ClaimId::Lemmas, e, assumptions, plots))
}
