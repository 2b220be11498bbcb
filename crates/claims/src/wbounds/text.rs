//! The W-bounds row's words that are not its verdict: the SDP cross-check's sentence and the
//! refinement figure.

use wingcheck_model::Quantity;

use super::records::{GalerkinRecord, SdpRecord};
use crate::{Line, PlotData};

/// A quantity's value as the row's sentences print it.
pub(super) fn fmt(q: &Quantity) -> String {
    q.value_text()
}

/// The SDP cross-check in one sentence: where it agrees with the eigenvalues and to what, and
/// every N not accepted with the reason.
pub fn sdp_sentence(rows: &[SdpRecord]) -> String {
    {
        let good: Vec<String> = rows.iter().filter(|r| r.accepted.value).map(|r| fmt(&r.elements)).collect();
        let worst = rows.iter().filter(|r| r.accepted.value).filter_map(|r| r.difference.as_ref()).map(|d| d.value);
        let worst = worst.fold(0.0f64, f64::max);
        let mut s = if good.is_empty() {
            "The SDP cross-check (clarabel) was not accepted at any N.".to_string()
        } else {
            format!(
                "An SDP (clarabel) agrees with the eigenvalues at N = {} to {} of max |W/κ|, each answer re-verified against W − λκ ⪰ 0 (float evidence, not proof).",
                good.join(", "),
                wingcheck_model::quantity::format_value(worst, None)
            )
        };
        for r in rows.iter().filter(|r| !r.accepted.value) {
            let why = r.reason.as_ref().map_or("no reason recorded", |t| t.value.as_str());
            s.push_str(&format!(" Not accepted at N = {}: {why}.", fmt(&r.elements)));
        }
        s
    }
}

/// λ2(N) and λ1(N) (`rows`) against the Galerkin elements N, with the weights `a`, `b` and the
/// extrapolated values `lambda2`, `lambda1` in the title.
pub(super) fn refinement_plot(
    rows: &[GalerkinRecord],
    a: &Quantity,
    b: &Quantity,
    lambda2: &Quantity,
    lambda1: &Quantity,
) -> PlotData {
    let x: Vec<f64> = rows.iter().map(|r| r.elements.value).collect();
    PlotData {
        name: "w-bounds-refinement".into(),
        title: format!(
            "Tight bounds of W/κ against the Galerkin elements N (a = {}, b = {}); extrapolated λ2* = {}, λ1* = {}",
            fmt(a),
            fmt(b),
            fmt(lambda2),
            fmt(lambda1)
        ),
        x_label: "elements N".into(),
        y_label: "W/κ extremes (J s)".into(),
        log_x: true,
        log_y: false,
        lines: vec![
            Line {
                label: "λ2(N) = min W/κ".into(),
                x: x.clone(),
                y: rows.iter().map(|r| r.lambda2.value).collect(),
                points: true,
            },
            Line {
                label: "λ1(N) = max W/κ".into(),
                x,
                y: rows.iter().map(|r| r.lambda1.value).collect(),
                points: true,
            },
        ],
    }
}
