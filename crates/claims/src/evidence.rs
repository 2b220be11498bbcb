//! The typed evidence of a row: one variant per claim, holding that claim's evidence struct,
//! each of which turns itself into a verdict and words through [`Explain`] ([`crate::explain`]).

use serde::Serialize;

use crate::comparison::ComparisonEvidence;
use crate::explain::Explain;
use crate::finite_time::FiniteTimeEvidence;
use crate::lemmas::LemmasEvidence;
use crate::mu::MuEvidence;
use crate::uub::UubEvidence;
use crate::wbounds::WBoundsEvidence;

/// A row's evidence, one variant per claim (serialised as the claim's own struct).
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
#[serde(untagged)]
pub enum Evidence {
    /// W-bounds.
    WBounds(Box<WBoundsEvidence>),
    /// mu-conditions.
    Mu(Box<MuEvidence>),
    /// UUB.
    Uub(Box<UubEvidence>),
    /// finite-time-1 / finite-time-2.
    FiniteTime(Box<FiniteTimeEvidence>),
    /// lemmas.
    Lemmas(Box<LemmasEvidence>),
    /// ftdo-vs-dobc.
    Comparison(Box<ComparisonEvidence>),
    /// Nothing was computed (an inconclusive row); serialised as `{}`.
    #[serde(serialize_with = "serialize_empty")]
    None,
}

impl Evidence {
    /// The evidence's own verdict (None for [`Evidence::None`]).
    pub fn explain(&self) -> Option<&dyn Explain> {
        Some(match self {
            Evidence::WBounds(e) => e.as_ref(),
            Evidence::Mu(e) => e.as_ref(),
            Evidence::Uub(e) => e.as_ref(),
            Evidence::FiniteTime(e) => e.as_ref(),
            Evidence::Lemmas(e) => e.as_ref(),
            Evidence::Comparison(e) => e.as_ref(),
            Evidence::None => return None,
        })
    }

    /// The display nodes of the evidence ([`crate::display::nodes`]).
    pub fn nodes(&self) -> Result<Vec<crate::display::Node>, crate::display::ShapeError> {
        match self {
            Evidence::None => Ok(Vec::new()),
            e => crate::display::nodes(e),
        }
    }
}

macro_rules! evidence_from {
    ($($t:ty => $v:ident),* $(,)?) => {
        $(impl From<$t> for Evidence {
            fn from(e: $t) -> Evidence {
                Evidence::$v(Box::new(e))
            }
        })*
    };
}

evidence_from!(
    WBoundsEvidence => WBounds,
    MuEvidence => Mu,
    UubEvidence => Uub,
    FiniteTimeEvidence => FiniteTime,
    LemmasEvidence => Lemmas,
    ComparisonEvidence => Comparison,
);

/// `{}`: the evidence of a row that computed nothing (an untagged unit variant would be null).
fn serialize_empty<S: serde::Serializer>(s: S) -> Result<S::Ok, S::Error> {
    use serde::ser::SerializeMap;
    s.serialize_map(Some(0))?.end()
}
