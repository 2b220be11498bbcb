//! The one trait that turns a row's evidence into a verdict and words.
//!
//! Each claim module computes its evidence struct (labelled [`wingcheck_model::Quantity`]s,
//! [`crate::display::Flag`]s, [`crate::display::Text`]s, [`crate::display::Table`]s) and
//! implements [`Explain`] on it: the verdict and its basis, the finding (≤ 3 short sentences),
//! the decisive numbers, further detail and the correction all come from the evidence alone, so
//! `check`, `check --json` and the report say the same thing at any configuration. The row's
//! evidence, one variant per claim, is [`crate::evidence::Evidence`].

use wingcheck_model::Quantity;

use crate::{Basis, Verdict};

/// Verdict and words from a row's evidence.
pub trait Explain {
    /// The verdict and what it rests on.
    fn verdict(&self) -> (Verdict, Basis);
    /// The finding: at most three short sentences, every number from the evidence.
    fn finding(&self) -> Vec<String>;
    /// The decisive numbers (two to four), with units and errors or bases.
    fn decisive(&self) -> Vec<Quantity>;
    /// The one comparison that decides the verdict, in a few words with its numbers (the
    /// report's first screen: one line per claim, so at most about 70 characters).
    fn deciding(&self) -> String;
    /// Further sentences for the detail section.
    fn details(&self) -> Vec<String> {
        Vec::new()
    }
    /// The correction under which the claim holds, if any.
    fn correction(&self) -> Option<String> {
        None
    }
}
