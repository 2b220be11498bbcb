//! One processor-state detail that decides the stepper's speed on x86-64.
//!
//! faer's kernels run with AVX/AVX-512 (selected at run time); when such code leaves the upper
//! halves of the vector registers dirty, every following legacy-SSE instruction of this
//! crate's loops (compiled for baseline x86-64) pays a state-merge penalty. Measured on the
//! 2-core machine this project is developed on: the modal TR-BDF2 loop of the default run took
//! 29 ms right after a faer eigen-solve in the same thread against 5.7 ms in a fresh thread,
//! with identical results. `vzeroupper` clears that state; the loops call
//! [`clear_upper_vector_state`] once before stepping.

/// Execute `vzeroupper` if the CPU has AVX (no-op elsewhere). It zeroes bits 128 and up of
/// the vector registers only, which hold no live value between Rust statements.
pub fn clear_upper_vector_state() {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx") {
        // SAFETY: AVX is available (checked above), which is all `vzeroupper` requires.
        unsafe { zero_upper() }
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
unsafe fn zero_upper() {
    std::arch::x86_64::_mm256_zeroupper();
}
