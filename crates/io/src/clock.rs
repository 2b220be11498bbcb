//! The one clock of wingcheck's self-measurements (`bench`, the search summary): wall time
//! beside the process's CPU time, and the machine's load when they were taken. On a shared
//! machine wall time moves with other processes' load; CPU time (user + system, all threads of
//! this process) does not, so every ratio a benchmark states is taken from CPU time where the
//! platform gives it, with the load printed beside.

use std::time::Instant;

use serde::Serialize;

/// CPU time of this process so far (s): user + system of all its threads, from
/// `clock_gettime(CLOCK_PROCESS_CPUTIME_ID)` (nanosecond resolution). None off Linux.
pub fn process_cpu_seconds() -> Option<f64> {
    #[cfg(target_os = "linux")]
    {
        let t = rustix::time::clock_gettime(rustix::time::ClockId::ProcessCPUTime);
        Some(t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9)
    }
    #[cfg(not(target_os = "linux"))]
    {
        None
    }
}

/// The machine's 1-minute load average (runnable processes, Linux `/proc/loadavg`); None
/// where the platform does not give it.
pub fn load_average() -> Option<f64> {
    load_averages().map(|l| l[0])
}

/// The 1-, 5- and 15-minute load averages (Linux `/proc/loadavg`); None elsewhere.
pub fn load_averages() -> Option<[f64; 3]> {
    let text = std::fs::read_to_string("/proc/loadavg").ok()?;
    let mut it = text.split_whitespace().map(|x| x.parse::<f64>().ok());
    Some([it.next()??, it.next()??, it.next()??])
}

/// Hardware threads available to this process.
pub fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// Wall and CPU time of one measured piece of work (s).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, schemars::JsonSchema)]
pub struct Elapsed {
    /// Wall time (s).
    pub wall_seconds: f64,
    /// CPU time of the whole process over the same interval (user + system, s); None where
    /// the platform does not give it. With other threads of this process idle it is the
    /// work's own CPU time.
    pub cpu_seconds: Option<f64>,
}

impl Elapsed {
    /// CPU time where known, else wall time: the figure a ratio is taken from.
    pub fn seconds(&self) -> f64 {
        self.cpu_seconds.unwrap_or(self.wall_seconds)
    }
}

/// A started measurement: [`Stopwatch::start`], then [`Stopwatch::elapsed`].
#[derive(Debug, Clone, Copy)]
pub struct Stopwatch {
    wall: Instant,
    cpu: Option<f64>,
}

impl Stopwatch {
    /// Start now.
    pub fn start() -> Self {
        Stopwatch { cpu: process_cpu_seconds(), wall: Instant::now() }
    }

    /// Wall and CPU time since [`Stopwatch::start`].
    pub fn elapsed(&self) -> Elapsed {
        let wall_seconds = self.wall.elapsed().as_secs_f64();
        let cpu_seconds = match (self.cpu, process_cpu_seconds()) {
            (Some(a), Some(b)) => Some((b - a).max(0.0)),
            _ => None,
        };
        Elapsed { wall_seconds, cpu_seconds }
    }
}

/// Time `f` (wall and CPU).
pub fn measure<T>(f: impl FnOnce() -> T) -> (T, Elapsed) {
    let watch = Stopwatch::start();
    let out = f();
    (out, watch.elapsed())
}

/// The machine a measurement ran on: cores and the load before and after, so a reader can
/// tell whether other processes shared the cores.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct MachineLoad {
    /// Hardware threads available to the process.
    pub cores: usize,
    /// 1-minute load average when the measurement started (None off Linux).
    pub load_average_start: Option<f64>,
    /// 1-minute load average when it ended (None off Linux, or before it ended).
    pub load_average_end: Option<f64>,
}

impl MachineLoad {
    /// Cores and the load now (the start).
    pub fn at_start() -> Self {
        MachineLoad { cores: cores(), load_average_start: load_average(), load_average_end: None }
    }

    /// Record the load at the end.
    pub fn finish(&mut self) {
        self.load_average_end = load_average();
    }

    /// "2 cores, load 1.23 → 1.40" (or "load unknown"): the line printed beside timings.
    pub fn describe(&self) -> String {
        let f = |l: Option<f64>| l.map_or("unknown".to_string(), |l| format!("{l:.2}"));
        match self.load_average_end {
            Some(_) => format!(
                "{} cores, load average {} at the start, {} at the end (other processes share the cores)",
                self.cores,
                f(self.load_average_start),
                f(self.load_average_end)
            ),
            None => format!("{} cores, load average {}", self.cores, f(self.load_average_start)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Busy work is charged to the process: CPU time grows by about the wall time of a
    /// single-threaded spin (at least half of it, even on a loaded machine, over 50 ms), and a
    /// sleep of the same length adds next to none.
    #[cfg(target_os = "linux")]
    #[test]
    fn cpu_time_counts_work_not_sleep() {
        let (_, spin) = measure(|| {
            let t = Instant::now();
            let mut x = 0u64;
            while t.elapsed().as_millis() < 50 {
                x = x.wrapping_mul(6364136223846793005).wrapping_add(1);
                std::hint::black_box(x);
            }
        });
        let (_, sleep) = measure(|| std::thread::sleep(std::time::Duration::from_millis(50)));
        let (spin_cpu, sleep_cpu) = (spin.cpu_seconds.unwrap(), sleep.cpu_seconds.unwrap());
        assert!(spin.wall_seconds >= 0.05 && spin_cpu <= spin.wall_seconds + 0.01, "{spin:?}");
        assert!(sleep.wall_seconds >= 0.05 && sleep_cpu < 0.02, "{sleep:?}");
        assert!(spin_cpu > 0.0, "{spin:?}");
    }

    #[test]
    fn load_line_names_cores_and_both_loads() {
        let m = MachineLoad { cores: 2, load_average_start: Some(1.234), load_average_end: Some(0.5) };
        assert_eq!(
            m.describe(),
            "2 cores, load average 1.23 at the start, 0.50 at the end (other processes share the cores)"
        );
    }
}
