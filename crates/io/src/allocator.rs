//! Process-wide allocator settings for the command-line tool.

/// Bytes below which glibc serves an allocation from its heap instead of a fresh mapping, and
/// free bytes at the heap's top it keeps instead of returning them: 64 MiB and 128 MiB.
///
/// A search point's eigenbasis setup allocates and frees some twenty dense N × N matrices
/// (170 KB each at N = 146, above glibc's default 128 KiB mapping threshold). Under the
/// defaults the freed top of the heap is trimmed and grown again at the next point, so every
/// point's matrices land on fresh pages the kernel must fault in and zero: measured 316 page
/// faults a point and 8 % of the setup's time (`wingcheck bench --what search`'s explicit
/// observer). With these limits the pages are reused. Only the timing changes, never a result.
pub const HEAP_LIMITS: (usize, usize) = (64 << 20, 128 << 20);

/// Apply [`HEAP_LIMITS`] (glibc on Linux; elsewhere nothing). Call once at the start of
/// `main`, before any thread starts.
pub fn tune_allocator() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        let (mmap, trim) = HEAP_LIMITS;
        // SAFETY: mallopt only changes glibc's allocation thresholds; it is called before any
        // other thread exists. A refusal (return 0) leaves the defaults, which are also correct.
        unsafe {
            libc::mallopt(libc::M_MMAP_THRESHOLD, mmap as libc::c_int);
            libc::mallopt(libc::M_TRIM_THRESHOLD, trim as libc::c_int);
        }
    }
}
