//! The W-bounds row's evidence (labelled quantities), its verdict and its words.

use wingcheck_cert::exact::to_f64;
use wingcheck_model::{Config, ErrorSource, Quantity, Unit, ValueBasis};

use super::{certified_sign_unshown, compute_cancellable, sdp_wall_times, Computed};
use crate::certify::omega1::{EnclosureSummary, Position};
use crate::display::{Fact, Flag, Table, Text};
use crate::explain::Explain;
use crate::settings::CheckSettings;
use crate::{Basis, ClaimId, ClaimRow, ClaimsError, Verdict, WallTime};
use wingcheck_theory::sdp::PencilSdpRow;
use wingcheck_theory::{self as theory, Decision};

use super::records::{GalerkinRecord, SdpRecord};
use super::text::{fmt, refinement_plot, sdp_sentence};

/// What the W-bounds row found, reused by the mu-conditions and UUB rows.
#[derive(Debug, Clone)]
pub struct WBounds {
    /// The ledger row.
    pub row: ClaimRow,
    /// Its evidence.
    pub evidence: WBoundsEvidence,
    /// Wall times of the SDP cross-check.
    pub wall: Vec<WallTime>,
}

impl SdpRecord {
    fn of(r: &PencilSdpRow) -> SdpRecord {
        let side = |s: &wingcheck_theory::sdp::PencilSide, name: &str| {
            s.lambda_sdp.map(|l| Quantity::based(format!("{name} by SDP"), l, Unit::JouleSecond, ValueBasis::Solver))
        };
        let eig = |s: &wingcheck_theory::sdp::PencilSide, name: &str| {
            s.lambda_eig
                .map(|l| Quantity::based(format!("{name} by eigenvalues"), l, Unit::JouleSecond, ValueBasis::Solver))
        };
        let diff = [&r.lambda2, &r.lambda1].iter().filter_map(|s| s.difference).reduce(f64::max);
        let reasons: Vec<String> = [("λ2", &r.lambda2), ("λ1", &r.lambda1)]
            .iter()
            .filter_map(|(n, s)| s.reason.as_ref().map(|w| format!("{n}: {w}")))
            .collect();
        SdpRecord {
            elements: Quantity::count("elements N", r.elements),
            lambda2_sdp: side(&r.lambda2, "λ2(N)"),
            lambda2_eigenvalue: eig(&r.lambda2, "λ2(N)"),
            lambda1_sdp: side(&r.lambda1, "λ1(N)"),
            lambda1_eigenvalue: eig(&r.lambda1, "λ1(N)"),
            scale: Quantity::based("max |W/κ|", r.scale, Unit::JouleSecond, ValueBasis::Solver),
            difference: diff.filter(|_| r.scale > 0.0).map(|d| {
                Quantity::based("|SDP − eigenvalue| / max |W/κ|", d / r.scale, Unit::Dimensionless, ValueBasis::Solver)
            }),
            status: Text::text("clarabel status (λ2, λ1)", format!("{}, {}", r.lambda2.status, r.lambda1.status)),
            iterations: Quantity::count("iterations (λ2 + λ1)", (r.lambda2.iterations + r.lambda1.iterations) as usize),
            attempts: Quantity::count(
                "formulations tried (λ2 + λ1)",
                (r.lambda2.attempts + r.lambda1.attempts) as usize,
            ),
            accepted: Flag::new("accepted", r.accepted),
            reason: (!reasons.is_empty()).then(|| Text::text("why not accepted", reasons.join("; "))),
        }
    }
}

/// The certified enclosure ω̲₁ ≤ ω₁ ≤ ω̄₁ of the continuous model (`omega1-enclosure.json`).
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct EnclosureEvidence {
    /// Whether the wing's ω₁ is certified.
    pub certified: Flag,
    /// ω̲₁ (nearest f64 of the exact bound).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lower: Option<Quantity>,
    /// ω̄₁ (nearest f64 of the exact bound).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub upper: Option<Quantity>,
    /// ω̲₁ and ω̄₁ as exact decimals.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub exact: Option<Text>,
    /// (ω̄₁ − ω̲₁)/ω̲₁.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub relative_width: Option<Quantity>,
    /// Modes k subtracted in the trace bound.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub modes: Option<Quantity>,
    /// Elements of the mesh on which the shifts are certified.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub inertia_elements: Option<Quantity>,
    /// Elements of the test vector's mesh.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rayleigh_elements: Option<Quantity>,
    /// Where the configured a/b lies against the enclosure (`below`, `inside`, `above`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub position: Option<Fact<Position>>,
    /// Why there is no enclosure.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<Text>,
}

impl EnclosureEvidence {
    fn of(e: &EnclosureSummary) -> EnclosureEvidence {
        match e {
            EnclosureSummary::Certified {
                lower,
                upper,
                lower_exact,
                upper_exact,
                relative_width,
                modes,
                inertia_elements,
                rayleigh_elements,
                position,
            } => EnclosureEvidence {
                certified: Flag::new("ω₁ enclosed by an exact certificate (continuous model)", true),
                lower: Some(Quantity::based(
                    "certified lower bound ω̲₁ of ω₁",
                    *lower,
                    Unit::PerSecond,
                    ValueBasis::LowerBound,
                )),
                upper: Some(Quantity::based(
                    "certified upper bound ω̄₁ of ω₁",
                    *upper,
                    Unit::PerSecond,
                    ValueBasis::UpperBound,
                )),
                exact: Some(Text::text("ω̲₁ ≤ ω₁ ≤ ω̄₁, exact (1/s)", format!("{lower_exact} ≤ ω₁ ≤ {upper_exact}"))),
                relative_width: Some(Quantity::based(
                    "relative width (ω̄₁ − ω̲₁)/ω̲₁",
                    *relative_width,
                    Unit::Dimensionless,
                    ValueBasis::Derived,
                )),
                modes: Some(Quantity::count("modes k subtracted in the trace bound", *modes)),
                inertia_elements: Some(Quantity::count("elements of the shifts' inertia mesh", *inertia_elements)),
                rayleigh_elements: Some(Quantity::count("elements of the test vector's mesh", *rayleigh_elements)),
                position: position.map(|p| Fact::new("configured a/b against the enclosure", p)),
                reason: None,
            },
            EnclosureSummary::NotCertified { reason } => EnclosureEvidence {
                certified: Flag::new("ω₁ enclosed by an exact certificate (continuous model)", false),
                lower: None,
                upper: None,
                exact: None,
                relative_width: None,
                modes: None,
                inertia_elements: None,
                rayleigh_elements: None,
                position: None,
                reason: Some(Text::text("why ω₁ is not certified", reason.clone())),
            },
        }
    }

    /// The configured a/b's position, when certified.
    pub fn position(&self) -> Option<Position> {
        self.position.as_ref().map(|p| p.value)
    }

    /// The enclosure in words.
    fn interval(&self) -> Option<String> {
        self.exact.as_ref().map(|x| {
            let w =
                self.relative_width.as_ref().map_or(String::new(), |w| format!(", relative width {}", w.value_text()));
            format!("{} 1/s (exact certificate{w})", x.value)
        })
    }
}

/// The evidence of the `W-bounds` row.
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct WBoundsEvidence {
    /// a of (15).
    pub a: Quantity,
    /// b of (15).
    pub b: Quantity,
    /// a/b.
    pub a_over_b: Quantity,
    /// y1 of (26), exact.
    pub y1: Quantity,
    /// y2 of (27), exact.
    pub y2: Quantity,
    /// y3 of (28), exact.
    pub y3: Quantity,
    /// Printed λ1 = y1 + y3.
    pub lambda1_printed: Quantity,
    /// Printed λ2 = y2 − y3.
    pub lambda2_printed: Quantity,
    /// The printed condition b > 2y3/min{ρ, I_p, EI, GJ}, decided exactly.
    pub printed_condition: Flag,
    /// min{ρ, I_p, EI, GJ}.
    pub min_rho_ip_ei_gj: Quantity,
    /// 2ρx_c.
    pub two_rho_xc: Quantity,
    /// (a, b) grid points where the printed λ2 was evaluated.
    pub grid_points_checked: Quantity,
    /// Of those, points with printed λ2 < 0.
    pub grid_points_lambda2_printed_negative: Quantity,
    /// Of those, points where the printed condition holds.
    pub grid_points_condition_holds: Quantity,
    /// λ2* = inf W/κ (corrected cross term), extrapolated.
    pub lambda2_tight: Quantity,
    /// λ1* = sup W/κ, extrapolated.
    pub lambda1_tight: Quantity,
    /// λ2* with the printed cross term.
    pub lambda2_tight_printed_cross_term: Quantity,
    /// λ1* with the printed cross term.
    pub lambda1_tight_printed_cross_term: Quantity,
    /// Observed refinement order of λ2(N).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda2_refinement_order: Option<Quantity>,
    /// λ2(N), λ1(N) per N.
    pub lambda_by_elements: Table<GalerkinRecord>,
    /// ω₁, the largest a/b with W ≻ 0 (converged FE modes).
    pub a_over_b_max: Quantity,
    /// The same on the finest Galerkin space of the study (an upper bound).
    pub a_over_b_max_galerkin: Quantity,
    /// The same with the printed cross term, on that space.
    pub a_over_b_max_printed_cross_term: Quantity,
    /// The certified enclosure of ω₁ for the continuous model.
    pub omega1_enclosure: EnclosureEvidence,
    /// W ≻ 0 at the configured (a, b): by the enclosure when a/b lies outside it, else against
    /// the error of the converged ω₁.
    pub w_positive_definite: Fact<Decision>,
    /// The SDP cross-check (evidence only; the verdict never rests on it).
    pub sdp_cross_check: Table<SdpRecord>,
    /// W(x) of the exact witness state (when W is indefinite at the configured weights).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub witness_w: Option<Quantity>,
    /// κ(x) of the witness.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub witness_kappa: Option<Quantity>,
}

/// An exact value of W or of a W/κ constant (J s; per SI unit of κ for the constants).
fn w_exact(label: &str, v: f64) -> Quantity {
    Quantity::exact(label, v, Unit::JouleSecond)
}

fn tight(label: &str, e: theory::Estimate) -> Quantity {
    Quantity::estimate(
        label,
        e,
        Unit::JouleSecond,
        &[ErrorSource::Grid, ErrorSource::Extrapolation, ErrorSource::RoundOff],
    )
}

/// The evidence from the computed facts.
fn evidence_of(cfg: &Config, c: &Computed) -> WBoundsEvidence {
    let (a, b) = (cfg.control.a, cfg.control.b);
    let w = &cfg.wing;
    let p = &c.printed;
    let (total, neg, cond) = c.printed_grid;
    let per_n = |(n, l2, l1): &(usize, f64, f64)| GalerkinRecord {
        elements: Quantity::count("elements N", *n),
        lambda2: Quantity::based("λ2(N) = min W/κ (≥ λ2*)", *l2, Unit::JouleSecond, ValueBasis::UpperBound),
        lambda1: Quantity::based("λ1(N) = max W/κ (≤ λ1*)", *l1, Unit::JouleSecond, ValueBasis::LowerBound),
    };
    let upper = |label: &str, v: f64| Quantity::based(label, v, Unit::PerSecond, ValueBasis::UpperBound);
    let mut ev = WBoundsEvidence {
        a: Quantity::configured("weight a of (15)", a, Unit::Dimensionless),
        b: Quantity::configured("weight b of (15)", b, Unit::Second),
        a_over_b: Quantity::configured("a/b", if b > 0.0 { a / b } else { 0.0 }, Unit::PerSecond),
        y1: w_exact("printed y1", to_f64(&p.y1)),
        y2: w_exact("printed y2", to_f64(&p.y2)),
        y3: w_exact("printed y3", to_f64(&p.y3)),
        lambda1_printed: w_exact("printed λ1 = y1 + y3", to_f64(&(&p.y1 + &p.y3))),
        lambda2_printed: w_exact("printed λ2 = y2 − y3", to_f64(&(&p.y2 - &p.y3))),
        printed_condition: Flag::new("printed condition b > 2y3/min{ρ, I_p, EI, GJ} holds", p.condition_holds),
        min_rho_ip_ei_gj: Quantity::configured(
            "min{ρ, I_p, EI, GJ}",
            w.rho.min(w.ip).min(w.ei).min(w.gj),
            Unit::MixedSi,
        ),
        two_rho_xc: Quantity::configured("2ρx_c", 2.0 * w.rho_xc, Unit::MixedSi),
        grid_points_checked: Quantity::count("(a, b) grid points checked", total),
        grid_points_lambda2_printed_negative: Quantity::count("of which printed λ2 < 0", neg),
        grid_points_condition_holds: Quantity::count("of which the printed condition holds", cond),
        lambda2_tight: tight("tight λ2* = infimum of W/κ", c.corrected.lambda2),
        lambda1_tight: tight("tight λ1* = supremum of W/κ", c.corrected.lambda1),
        lambda2_tight_printed_cross_term: tight("λ2* with the printed cross term", c.printed_cross.lambda2),
        lambda1_tight_printed_cross_term: tight("λ1* with the printed cross term", c.printed_cross.lambda1),
        lambda2_refinement_order: c
            .corrected
            .order
            .map(|o| Quantity::based("observed order of λ2(N)", o, Unit::Dimensionless, ValueBasis::Derived)),
        lambda_by_elements: Table::new(
            "W/κ extremes per Galerkin space",
            c.corrected.by_elements.iter().map(per_n).collect(),
        ),
        a_over_b_max: Quantity::estimate(
            "largest a/b with W ≻ 0: ω₁",
            c.omega1,
            Unit::PerSecond,
            &[ErrorSource::Grid, ErrorSource::Extrapolation, ErrorSource::RoundOff],
        ),
        a_over_b_max_galerkin: upper(
            &format!("ω₁ on the {}-element Galerkin space", c.ratio_galerkin.0),
            c.ratio_galerkin.1,
        ),
        a_over_b_max_printed_cross_term: upper(
            &format!("largest a/b with W ≻ 0, printed cross term, {} elements", c.ratio_galerkin.0),
            c.ratio_printed_cross,
        ),
        omega1_enclosure: EnclosureEvidence::of(&c.enclosure),
        w_positive_definite: Fact::new(
            "W ≻ 0 at the configured a, b",
            super::decide(&c.enclosure, theory::w_positive_definite(a, b, c.omega1)),
        ),
        sdp_cross_check: Table::new("SDP cross-check of λ2(N), λ1(N)", c.sdp.iter().map(SdpRecord::of).collect()),
        witness_w: c.witness.map(|(wx, _)| w_exact("W(x) of the exact witness state", wx)),
        witness_kappa: c
            .witness
            .map(|(_, kx)| Quantity::exact("κ(x) of the witness state (SI values as numbers)", kx, Unit::MixedSi)),
    };
    if let Some(sign) = certified_sign_unshown(&ev.lambda2_tight, ev.omega1_enclosure.position()) {
        let label = format!(
            "{} (float value unresolved this close to a/b = ω₁: λ2* {sign} is proved by the certified enclosure of ω₁)",
            ev.lambda2_tight.label
        );
        ev.lambda2_tight = ev.lambda2_tight.relabel(label);
    }
    ev
}

/// Compute the evidence (and the SDP wall times).
pub fn evidence(cfg: &Config, settings: &CheckSettings) -> Result<(WBoundsEvidence, Vec<WallTime>), ClaimsError> {
    evidence_cancellable(cfg, settings, &wingcheck_model::Cancel::new())
}

/// [`evidence`] whose SDP cross-check stops once `cancel` is set (its rows then say so; the
/// caller discards the ledger, [`crate::check_all_cancellable`]).
pub fn evidence_cancellable(
    cfg: &Config,
    settings: &CheckSettings,
    cancel: &wingcheck_model::Cancel,
) -> Result<(WBoundsEvidence, Vec<WallTime>), ClaimsError> {
    let c = compute_cancellable(cfg, settings, cancel)?;
    Ok((evidence_of(cfg, &c), sdp_wall_times(&c)))
}

impl WBoundsEvidence {
    fn structural(&self) -> bool {
        self.min_rho_ip_ei_gj.value <= self.two_rho_xc.value
    }

    fn sdp_sentence(&self) -> String {
        sdp_sentence(&self.sdp_cross_check.rows)
    }
}

impl SdpRecord {
    /// The display record of one N's cross-check.
    pub fn from_row(r: &PencilSdpRow) -> SdpRecord {
        SdpRecord::of(r)
    }
}

impl Explain for WBoundsEvidence {
    /// W ≻ 0 decided → holds after correction; indefinite → fails; within the error of ω₁ →
    /// inconclusive. The basis is the exact certificate when the enclosure decides W ≻ 0 (or an
    /// exact witness shows W indefinite), else the float solver.
    fn verdict(&self) -> (Verdict, Basis) {
        let certified = self.omega1_enclosure.position();
        match self.w_positive_definite.value {
            Decision::Yes if certified == Some(Position::Below) => {
                (Verdict::HoldsAfterCorrection, Basis::ExactCertificate)
            }
            Decision::Yes => (Verdict::HoldsAfterCorrection, Basis::FloatSolver),
            Decision::No if certified == Some(Position::Above) || self.witness_w.is_some() => {
                (Verdict::Fails, Basis::ExactCertificate)
            }
            Decision::No => (Verdict::Fails, Basis::FloatSolver),
            Decision::Undecided => (Verdict::Inconclusive, Basis::FloatSolver),
        }
    }

    fn finding(&self) -> Vec<String> {
        let l2 = &self.lambda2_printed;
        let printed = if l2.value < 0.0 && self.structural() {
            format!(
                "As printed, λ2 = y2 − y3 = {} < 0 for every a, b > 0 here, because min{{ρ, I_p, EI, GJ}} = {} ≤ 2ρx_c = {} (SI values compared as numbers, as the paper does).",
                fmt(l2),
                fmt(&self.min_rho_ip_ei_gj),
                fmt(&self.two_rho_xc)
            )
        } else if l2.value < 0.0 {
            format!("As printed, λ2 = y2 − y3 = {} < 0 at the configured a, b, so 0 ≤ λ2κ fails.", fmt(l2))
        } else {
            format!("As printed, λ2 = y2 − y3 = {} ≥ 0 at the configured a, b.", fmt(l2))
        };
        let certified = self.omega1_enclosure.position();
        let here = match (self.w_positive_definite.value, certified) {
            (Decision::Yes, Some(Position::Below)) => {
                "W is positive definite there (proved: below the certified enclosure)"
            }
            (Decision::Yes, _) => "W is positive definite there",
            (Decision::No, Some(Position::Above)) => "W is indefinite there (proved: above the certified enclosure)",
            (Decision::No, _) if self.witness_w.is_some() => {
                "W is indefinite there (an exact rational state has W < 0)"
            }
            (Decision::No, _) => "W is indefinite there",
            (Decision::Undecided, _) => "that is within the error of the threshold, so W ≻ 0 is not decided",
        };
        vec![
            printed,
            format!(
                "W ≻ 0 exactly when a/b < ω₁ = {}; at the configured a/b = {} {here}.",
                self.a_over_b_max.pm_text(),
                fmt(&self.a_over_b)
            ),
            match certified_sign_unshown(&self.lambda2_tight, certified) {
                Some(sign) => format!(
                    "The tightest constants are λ2* {sign} (proved by the certified enclosure; the float extrapolation, {}, does not resolve it this close to a/b = ω₁) and λ1* = {}.",
                    self.lambda2_tight.pm_text(),
                    self.lambda1_tight.pm_text()
                ),
                None => format!(
                    "The tightest constants are λ2* = {} and λ1* = {}.",
                    self.lambda2_tight.pm_text(),
                    self.lambda1_tight.pm_text()
                ),
            },
        ]
    }

    /// The printed and the tight λ2, ω₁, the certified bound that decides (the upper one when
    /// a/b lies above the enclosure, the lower one below it, both inside it) and a/b.
    fn decisive(&self) -> Vec<Quantity> {
        let mut out = vec![self.lambda2_printed.clone(), self.lambda2_tight.clone(), self.a_over_b_max.clone()];
        let e = &self.omega1_enclosure;
        match e.position() {
            Some(Position::Above) => out.extend(e.upper.iter().cloned()),
            Some(Position::Below) => out.extend(e.lower.iter().cloned()),
            _ => out.extend(e.lower.iter().chain(&e.upper).cloned()),
        }
        out.push(self.a_over_b.clone());
        out
    }

    fn deciding(&self) -> String {
        // a/b to 4 digits when it is not a short decimal (1/3000), so the line stays one line
        let ratio = self.a_over_b.equals_text();
        let e = &self.omega1_enclosure;
        let omega = self.a_over_b_max.pm_text();
        let printed = if self.lambda2_printed.value < 0.0 { ", but the printed λ2 < 0" } else { "" };
        match (self.w_positive_definite.value, e.position(), &e.lower, &e.upper) {
            (Decision::No, Some(Position::Above), _, Some(u)) => {
                format!("a/b {ratio} > ω̄₁ = {}: W is indefinite (proved)", u.value_text())
            }
            (Decision::Yes, Some(Position::Below), Some(l), _) => {
                format!("a/b {ratio} < ω̲₁ = {}: W ≻ 0 (proved){printed}", l.value_text())
            }
            (Decision::No, _, _, _) if self.witness_w.is_some() => format!(
                "W(x) = {} < 0 for an exact state x: W is indefinite",
                self.witness_w.as_ref().map_or_else(String::new, Quantity::value_text)
            ),
            (Decision::No, _, _, _) => format!("a/b {ratio} > ω₁ = {omega}: W is indefinite"),
            (Decision::Yes, _, _, _) => format!("a/b {ratio} < ω₁ = {omega}: W ≻ 0{printed}"),
            (Decision::Undecided, _, _, _) => format!("a/b {ratio} is within the error of ω₁ = {omega}"),
        }
    }

    fn details(&self) -> Vec<String> {
        let mut d = vec![format!(
            "The printed λ2 is negative at {} of {} (a, b) grid points; the printed condition on b holds at {}.",
            fmt(&self.grid_points_lambda2_printed_negative),
            fmt(&self.grid_points_checked),
            fmt(&self.grid_points_condition_holds)
        )];
        d.push(format!(
            "With the cross term as printed (b x_c instead of bρx_c) the tight constants are λ2* = {}, λ1* = {} and W ≻ 0 needs a/b < {} on the Galerkin space.",
            fmt(&self.lambda2_tight_printed_cross_term),
            fmt(&self.lambda1_tight_printed_cross_term),
            fmt(&self.a_over_b_max_printed_cross_term)
        ));
        d.push(format!(
            "{} is {} (a Rayleigh–Ritz upper bound of ω₁).",
            self.a_over_b_max_galerkin.label,
            fmt(&self.a_over_b_max_galerkin)
        ));
        d.push(match (self.omega1_enclosure.interval(), self.omega1_enclosure.position()) {
            (Some(i), Some(Position::Inside)) => format!(
                "The configured a/b lies inside the certified enclosure {i}, so the certificate does not decide W ≻ 0 here; the converged float ω₁ does (evidence)."
            ),
            (Some(i), Some(_)) => format!("The certified enclosure {i} decides W ≻ 0 at the configured a/b for the continuous model."),
            (Some(i), None) => format!("The certified enclosure is {i}; b = 0, so a/b is undefined."),
            (None, _) => format!(
                "ω₁ is not certified ({}), so the decision rests on the converged float ω₁.",
                self.omega1_enclosure.reason.as_ref().map_or("no reason recorded", |r| r.value.as_str())
            ),
        });
        d.push(self.sdp_sentence());
        d
    }

    fn correction(&self) -> Option<String> {
        match self.w_positive_definite.value {
            Decision::Yes => Some(format!(
                "replace λ2 = y2 − y3 by the tight λ2* = infimum of W/κ = {} and λ1 by λ1* = {}; they are positive iff a/b < ω₁ (cross term −bρx_c∫q̇θ̇)",
                fmt(&self.lambda2_tight),
                fmt(&self.lambda1_tight)
            )),
            Decision::No => Some(match &self.omega1_enclosure.lower {
                Some(lower) => format!(
                    "choose a/b < ω̲₁ = {} (certified: W ≻ 0 is then proved) and use the tight λ2* (positive there) instead of y2 − y3",
                    lower.value_text()
                ),
                None => format!(
                    "choose a/b < ω₁ = {} and use the tight λ2* (positive there) instead of y2 − y3",
                    fmt(&self.a_over_b_max)
                ),
            }),
            Decision::Undecided => None,
        }
    }
}

/// Check Theorem 1.
pub fn check(cfg: &Config, settings: &CheckSettings) -> Result<WBounds, ClaimsError> {
    check_cancellable(cfg, settings, &wingcheck_model::Cancel::new())
}

/// [`check`] whose SDP cross-check stops once `cancel` is set.
pub fn check_cancellable(
    cfg: &Config,
    settings: &CheckSettings,
    cancel: &wingcheck_model::Cancel,
) -> Result<WBounds, ClaimsError> {
    let (e, wall) = evidence_cancellable(cfg, settings, cancel)?;
    let assumptions = vec![
        format!("a = {}, b = {} (the paper does not give them)", fmt(&e.a), fmt(&e.b)),
        "W_o's last term read as −bρx_c∫q̇θ̇ (the paper prints b x_c; the bound (27) uses bρx_c); the printed variant is reported too".into(),
        format!(
            "state space discretised by cubic Hermite q, linear θ, discontinuous cubic velocities on N ∈ {:?} uniform elements (the SDP cross-check on N ∈ {:?}); the infimum over the velocities is exact",
            settings.w_grids, settings.sdp_grids
        ),
        "the threshold ω₁: W ≻ 0 iff a/b < ω₁ for the continuous model (the per-mode argument in model.md); decided by the certified enclosure ω̲₁ ≤ ω₁ ≤ ω̄₁ (omega1-enclosure.json: a Rayleigh quotient above, the trace of the compliance operator with exact inertia counts below) when a/b lies outside it, else by the converged fundamental frequency (Romberg over uniform FE meshes 16, 32, …, with its error estimate); the Galerkin value on the finest space, an upper bound (Rayleigh–Ritz), is a cross-check".into(),
    ];
    let plots = vec![refinement_plot(&e.lambda_by_elements.rows, &e.a, &e.b, &e.lambda2_tight, &e.lambda1_tight)];
    let row = ClaimRow::decided(ClaimId::WBounds, e.clone(), assumptions, plots);
    Ok(WBounds { row, evidence: e, wall })
}
