//! Provenance of a report: the build (tool version, git commit and tree state, rustc) comes
//! from the binary's build script through [`wingcheck_io::build`]; the run (date, command
//! line) from run time. The run part varies between two renders of the same configuration and
//! is kept in the page's `walltime` block with the wall times.

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
    let load = wingcheck_io::clock::load_averages()
        .map(|l| l.map(|x| format!("{x:.2}")).join(", "))
        .unwrap_or_else(|| "unknown".into());
    Machine { cpu, hardware_threads: wingcheck_io::clock::cores(), threads: rayon::current_num_threads(), load }
}

/// UTC date and time `YYYY-MM-DD HH:MM:SS UTC` of `t` (jiff's formatting, whole seconds).
pub fn utc_string(t: jiff::Timestamp) -> String {
    t.strftime("%Y-%m-%d %H:%M:%S UTC").to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dates_match_known_instants() {
        // Reference instants from `date -u -d @N`.
        let at = |s: i64| utc_string(jiff::Timestamp::from_second(s).unwrap());
        assert_eq!(at(0), "1970-01-01 00:00:00 UTC");
        assert_eq!(at(951_782_400), "2000-02-29 00:00:00 UTC");
        assert_eq!(at(1_796_122_953), "2026-12-01 11:02:33 UTC");
    }
}
