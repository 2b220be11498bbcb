//! Controllers and digital disturbance observers of the paper.
//!
//! Both observers measure the same auxiliary signal. For the bending channel
//! σ1 = −ξ EI q'''(s) − ν1 with ν̇1 = ĝ1 + τ1 + EI q'''(s) (corrected (16)–(17)); combined with
//! the tip boundary condition EI(q''' + ξ q̇''')(s) = −(τ1 + g1) this gives σ̇1 = g1 − ĝ1
//! whatever the plant does. The FTDO sets ĝ = φ(σ) with
//! φ(σ) = κ_lin σ + κ_sw sign(σ) + κ_frac sig^r(σ) (eq. (20)–(21)); DOBC (57, corrected)
//! has ĝ = −ξ EI q'''(s) + p1 with ṗ1 = −τ1 − EI q'''(s) − ĝ1, i.e. p1 = −ν1 and ĝ1 = σ1:
//! the DOBC is the same observer with φ(σ) = σ. This crate holds φ, its sampled
//! evaluation rules (explicit and implicit/set-valued) and the per-channel bookkeeping; the
//! simulator feeds it the measured tip quantities.

#![forbid(unsafe_code)]

mod controller;
mod law;
mod observer;

pub use controller::{BuiltIn, ControlError, Controller, Erased, Held, PeriodIntegrals, TipMeasurement};
pub use law::BoundaryLaw;
pub use observer::{ChannelObserver, ObserverGain, TipChannel};
