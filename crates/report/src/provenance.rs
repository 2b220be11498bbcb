//! Provenance of a report: the build (tool version, git commit and tree state, rustc) comes
//! from the binary's build script through [`wingcheck_io::build`]; the run (date, command
//! line) from run time. The run part varies between two renders of the same configuration and
//! is kept in the page's `walltime` block with the wall times.

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
