//! Provenance of a report: the build (tool version, git commit, rustc) from build time, and
//! the run (date, command line) from run time. The run part varies between two renders of
//! the same configuration and is kept in the page's `walltime` block with the wall times.

/// Git commit the tool was built from (`unknown` outside a git checkout), set by `build.rs`.
pub const GIT_COMMIT: &str = env!("WINGCHECK_GIT_COMMIT");

/// `rustc --version` of the compiler that built the tool, set by `build.rs`.
pub const RUSTC_VERSION: &str = env!("WINGCHECK_RUSTC_VERSION");

/// UTC date and time `YYYY-MM-DD HH:MM:SS UTC` of `t` (proleptic Gregorian calendar).
///
/// Written by hand (days-from-civil inverse, H. Hinnant's algorithm) rather than adding a
/// date crate for one line of output.
pub fn utc_string(t: std::time::SystemTime) -> String {
    let secs = t.duration_since(std::time::UNIX_EPOCH).map(|d| d.as_secs() as i64).unwrap_or(0);
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!("{year:04}-{month:02}-{day:02} {:02}:{:02}:{:02} UTC", rem / 3600, rem % 3600 / 60, rem % 60)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::{Duration, UNIX_EPOCH};

    #[test]
    fn dates_match_known_instants() {
        // Reference instants from `date -u -d @N`.
        assert_eq!(utc_string(UNIX_EPOCH), "1970-01-01 00:00:00 UTC");
        assert_eq!(utc_string(UNIX_EPOCH + Duration::from_secs(951_782_400)), "2000-02-29 00:00:00 UTC");
        assert_eq!(utc_string(UNIX_EPOCH + Duration::from_secs(1_796_122_953)), "2026-12-01 11:02:33 UTC");
    }
}
