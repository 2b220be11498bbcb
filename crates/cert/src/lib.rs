//! Exact-arithmetic certificates for wingcheck.
//!
//! A floating-point SDP/LP solution is only evidence; a certificate whose
//! claim is re-checked here in exact rational arithmetic is proof.
//!
//! * [`exact`] – exact parsing/conversion of rationals.
//! * [`poly`], [`fe`] – exact polynomials and FE element/global matrices.
//! * [`matrix`] – dense rational matrices.
//! * [`psd`] – positive (semi)definiteness via fraction-free LDLᵀ / witnesses.
//! * [`lp`] – Farkas infeasibility and feasible-point checks.
//! * [`banded`] – symmetric banded matrices and their exact inertia (fraction-free LDLᵀ).
//! * [`green`], [`enclosure`] – the certified enclosure ω̲₁ ≤ ω₁ ≤ ω̄₁ of the continuous
//!   wing's fundamental frequency (trace bound below, Rayleigh quotient above).
//!
//! The certificate files, their manifest and the verifier that re-derives each fact from its
//! parameters live in `wingcheck-claims` (`certify`), built on these checks.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod banded;
pub mod enclosure;
pub mod exact;
pub mod fe;
pub mod green;
pub mod lp;
pub mod matrix;
pub mod poly;
pub mod psd;

pub use matrix::RationalMatrix;
pub use num_bigint::BigInt;
pub use num_rational::BigRational;
