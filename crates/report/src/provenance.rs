//! Provenance of a report: the build (tool version, git commit, rustc) from build time, and
//! the run (date, command line) from run time. The run part varies between two renders of
//! the same configuration and is kept in the page's `walltime` block with the wall times.

/// Git commit the tool was built from (`unknown` outside a git checkout), set by `build.rs`.
pub const GIT_COMMIT: &str = env!("WINGCHECK_GIT_COMMIT");

/// Whether tracked files differed from [`GIT_COMMIT`] when the tool was built (`yes`, `no`,
/// `unknown`), set by `build.rs`.
pub const GIT_DIRTY: &str = env!("WINGCHECK_GIT_DIRTY");

/// The machine a run is on, read at run time (it varies between runs: kept in the page's
/// wall-time block): CPU model, hardware threads, the threads the report ran on, load average.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Machine {
    /// `model name` of /proc/cpuinfo (or `unknown`).
    pub cpu: String,
    /// Hardware threads available to the process.
    pub hardware_threads: usize,
    /// Worker threads of the report's thread pool.
    pub threads: usize,
    /// 1-, 5- and 15-minute load averages from /proc/loadavg (or `unknown`).
    pub load: String,
}

/// The machine now.
pub fn machine() -> Machine {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, v)| v.trim().to_string())
        })
        .unwrap_or_else(|| "unknown".into());
    let load = std::fs::read_to_string("/proc/loadavg")
        .ok()
        .map(|t| t.split_whitespace().take(3).collect::<Vec<_>>().join(", "))
        .filter(|s| !s.is_empty())
        .unwrap_or_else(|| "unknown".into());
    Machine {
        cpu,
        hardware_threads: std::thread::available_parallelism().map_or(1, |n| n.get()),
        threads: rayon::current_num_threads(),
        load,
    }
}

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
