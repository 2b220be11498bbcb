//! Link the extension with `-Bsymbolic` (Linux): its calls to its own symbols — above all the
//! BLAS/LAPACK routines `crates/lapack` defines for clarabel's SDP cone (`dsyevr_`, `dgemm_`, …)
//! — bind inside the library at link time, so a BLAS that the host process loaded
//! `RTLD_GLOBAL` before it (numpy's, scipy's, an MKL) cannot interpose them. Without it a
//! prototype's SDP gave 2.5 instead of 3.618 (python/tests/test_host.py builds such a BLAS and
//! checks the answer).

fn main() {
    let target = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    if target == "linux" {
        println!("cargo:rustc-cdylib-link-arg=-Wl,-Bsymbolic");
    }
    println!("cargo:rerun-if-changed=build.rs");
}
