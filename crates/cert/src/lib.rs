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
//! * [`certificate`], [`recipe`], [`verify`] – the JSON envelope, matrix
//!   recipes and file/directory verification.

#![warn(missing_docs)]

pub mod certificate;
pub mod exact;
pub mod fe;
pub mod lp;
pub mod matrix;
pub mod poly;
pub mod psd;
pub mod recipe;
pub mod verify;

pub use certificate::{write_certificate, CertError, CertKind, Certificate, Payload};
pub use matrix::RationalMatrix;
pub use num_bigint::BigInt;
pub use num_rational::BigRational;
pub use recipe::{explicit_recipe, FnRecipe, MatrixRecipe, RecipeRef, RecipeRegistry};
pub use verify::{verify_certificate, verify_dir, verify_dir_with, verify_file, verify_file_with, Verified};
