//! The rows of the W-bounds evidence's tables: one element count of the W/κ refinement study
//! ([`GalerkinRecord`]) and one of the SDP cross-check ([`SdpRecord`]).

use wingcheck_model::Quantity;

use crate::display::{Flag, Text};

/// One element count of the W/κ refinement study.
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct GalerkinRecord {
    /// N.
    pub elements: Quantity,
    /// λ2(N) = min W/κ on the N-element space (≥ λ2*).
    pub lambda2: Quantity,
    /// λ1(N) = max W/κ on it (≤ λ1*).
    pub lambda1: Quantity,
}

/// One element count of the SDP cross-check.
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct SdpRecord {
    /// N.
    pub elements: Quantity,
    /// λ2 from clarabel (absent when it returned no point).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda2_sdp: Option<Quantity>,
    /// λ2(N) from the generalised eigenvalues at the same N.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda2_eigenvalue: Option<Quantity>,
    /// λ1 from clarabel.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda1_sdp: Option<Quantity>,
    /// λ1(N) from the generalised eigenvalues.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda1_eigenvalue: Option<Quantity>,
    /// max |W/κ| at this N (the scale of the re-verification tolerance).
    pub scale: Quantity,
    /// Largest |SDP − eigenvalue| over both sides, relative to max |W/κ|.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub difference: Option<Quantity>,
    /// clarabel's status, both sides.
    pub status: Text,
    /// Interior-point iterations, both sides.
    pub iterations: Quantity,
    /// Formulations tried, both sides (2 when the first point was rescaled and solved again).
    pub attempts: Quantity,
    /// Both sides solved, re-verified and agreeing with the eigenvalues.
    pub accepted: Flag,
    /// Why not, when not.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<Text>,
}
