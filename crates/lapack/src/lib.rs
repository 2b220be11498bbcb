//! # wingcheck-lapack
//!
//! Pure-Rust providers of the Fortran BLAS/LAPACK symbols that clarabel's SDP
//! (PSD cone) support links against. The SDP modelling layer over clarabel is
//! `wingcheck_theory::sdp::problem`.
//!
//! ## Why this crate exists
//!
//! clarabel 0.11 with its `sdp` feature calls dense linear algebra through the
//! `blas`/`lapack` wrapper crates, which are thin `extern` declarations
//! (`blas-sys`/`lapack-sys`) of the Fortran ABI. Someone has to define those
//! symbols at link time; clarabel's own options (`sdp-openblas`, `sdp-netlib`,
//! `sdp-mkl`, `sdp-accelerate`, `sdp-r`) all need a native library or a
//! C/Fortran toolchain, and this project must build from pure crates. Linked
//! on its own, clarabel's SDP path needs exactly eight symbols:
//! `dgemm_`, `dsyrk_`, `dsyr2k_`, `dpotrf_`, `dpotrs_`, `dsyevr_`, `dgesdd_`,
//! `dgesvd_` (verified from the linker's undefined-symbol list). No maintained
//! pure-Rust crate exports these Fortran symbols (the `blas-src`/`lapack-src`
//! providers are all native), so they are hand-written here on top of
//! [`faer`] 0.24: each `extern "C"` function decodes the Fortran arguments
//! (pointers to `char`/`int`/`double`, column-major storage with leading
//! dimensions), builds strided faer views, and runs the faer kernel.
//!
//! Conventions honoured: `uplo` (only that triangle read/written), `trans`,
//! BLAS `alpha`/`beta` semantics (`beta == 0` never reads `C`), LAPACK `info`
//! codes (negative = index of the bad argument, positive = numerical failure),
//! workspace queries (`lwork = -1` / `liwork = -1`), and leading dimensions
//! larger than the row count (padding rows are never touched). Known
//! departures from reference LAPACK, all permitted by its documentation:
//! inputs documented as "destroyed on exit" are left unchanged, `dsyevr`
//! ignores `abstol` (faer works to full accuracy) and fills `isuppz` with
//! full support, `dpotrf` leaves `A` unchanged when it fails, and BLAS
//! argument errors are printed and recorded ([`take_blas_error`]) instead of
//! stopping the program as reference `XERBLA` would.
//!
//! ## How to link it
//!
//! The symbols are only linked into a binary if this crate is actually used
//! by it. Any crate that uses clarabel SDPs (directly or through
//! `wingcheck_theory::sdp::problem`) must
//! depend on `wingcheck-lapack` and reference it, e.g.
//!
//! ```ignore
//! use wingcheck_lapack as _; // provides dgemm_, dsyevr_, ... for clarabel
//! ```
//!
//! or call [`link()`] once (it is a no-op that keeps every symbol alive); the
//! SDP layer `wingcheck_theory::sdp::problem` calls [`link()`] itself. clarabel
//! must be built with the features `sdp`, `blas-src`, `lapack-src` (no provider
//! selected) and `serde` (clarabel 0.11.1 does not compile without `serde`);
//! `wingcheck-theory` also enables `faer-sparse` so clarabel's `"auto"` KKT
//! solver is faer's supernodal LDLᵀ (≈8x faster than QDLDL on a dense 60x60
//! LMI). Cargo feature unification applies these features workspace-wide.
//! This crate itself does not depend on clarabel.

#![warn(missing_docs)]

mod blas;
mod chol;
mod eig;
mod svd;
mod util;

pub use blas::{dgemm_, dsyr2k_, dsyrk_};
pub use chol::{dpotrf_, dpotrs_};
pub use eig::dsyevr_;
pub use svd::{dgesdd_, dgesvd_};
pub use util::{take_blas_error, BlasArgError};

/// Force the linker to keep every exported BLAS/LAPACK symbol.
///
/// Calling this (or writing `use wingcheck_lapack as _;`) from a binary that
/// uses clarabel's SDP cone guarantees the Fortran symbols resolve. It does
/// no work at run time beyond an optimisation barrier.
#[inline(never)]
pub fn link() {
    let syms: [*const (); 8] = [
        dgemm_ as *const (),
        dsyrk_ as *const (),
        dsyr2k_ as *const (),
        dpotrf_ as *const (),
        dpotrs_ as *const (),
        dsyevr_ as *const (),
        dgesdd_ as *const (),
        dgesvd_ as *const (),
    ];
    std::hint::black_box(syms);
}
