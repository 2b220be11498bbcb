//! Progress of long work on stderr, the one place the CLI shows it: a bar when stderr is a
//! terminal, plain lines otherwise (a Slurm log, CI, a pipe) so that a log shows the work is
//! alive — none for work shorter than [`line_interval`], then one at every further tenth of the
//! work and at least one every interval, and a closing line. Work without a known fraction
//! (`check`) gets a spinner or a line every interval.

use std::io::{IsTerminal, Write};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// The environment variable that sets the seconds between plain progress lines (default 5).
pub const INTERVAL_ENV: &str = "WINGCHECK_PROGRESS_SECONDS";

/// Seconds between plain progress lines: `WINGCHECK_PROGRESS_SECONDS` if it is a positive
/// number, else 5.
pub fn line_interval() -> Duration {
    std::env::var(INTERVAL_ENV)
        .ok()
        .and_then(|s| s.trim().parse::<f64>().ok())
        .filter(|s| s.is_finite() && *s > 0.0 && *s < 1e6)
        .map(Duration::from_secs_f64)
        .unwrap_or(Duration::from_secs(5))
}

/// Progress of one command's work, as a fraction.
pub struct Progress {
    what: String,
    started: Instant,
    shown: Shown,
}

enum Shown {
    Bar(indicatif::ProgressBar),
    Lines(Mutex<LastLine>),
}

struct LastLine {
    at: Instant,
    tenth: u32,
    printed: bool,
}

impl Progress {
    /// Progress of `what` (the command's name), shown as described in the module docs.
    pub fn new(what: &str) -> Progress {
        let shown = if std::io::stderr().is_terminal() {
            let bar = indicatif::ProgressBar::new(1000);
            bar.set_style(
                indicatif::ProgressStyle::with_template("{msg} [{bar:40}] {percent}% ({elapsed} / eta {eta})")
                    .expect("valid template")
                    .progress_chars("=> "),
            );
            bar.set_message(what.to_string());
            Shown::Bar(bar)
        } else {
            Shown::Lines(Mutex::new(LastLine { at: Instant::now(), tenth: 0, printed: false }))
        };
        Progress { what: what.to_string(), started: Instant::now(), shown }
    }

    /// `done` of `total` units (`unit`: "points", or empty for a fraction) in `stage` (may be
    /// empty).
    pub fn set(&self, done: u64, total: u64, unit: &str, stage: &str) {
        let fraction = if total == 0 { 1.0 } else { (done as f64 / total as f64).clamp(0.0, 1.0) };
        match &self.shown {
            Shown::Bar(bar) => {
                bar.set_position((fraction * 1000.0).round() as u64);
                if !stage.is_empty() {
                    bar.set_message(format!("{}: {stage}", self.what));
                }
            }
            Shown::Lines(last) => {
                let Ok(mut last) = last.lock() else { return };
                let (tenth, interval) = ((fraction * 10.0).floor() as u32, line_interval());
                let quiet = if last.printed {
                    tenth <= last.tenth && last.at.elapsed() < interval
                } else {
                    self.started.elapsed() < interval
                };
                if quiet {
                    return;
                }
                *last = LastLine { at: Instant::now(), tenth: last.tenth.max(tenth), printed: true };
                let count = if unit.is_empty() { String::new() } else { format!(" ({done} of {total} {unit})") };
                let stage = if stage.is_empty() { String::new() } else { format!(", {stage}") };
                line(&format!(
                    "{}: {:.0}% done{count}{stage}, {:.1} s",
                    self.what,
                    fraction * 100.0,
                    self.started.elapsed().as_secs_f64()
                ));
            }
        }
    }

    /// Remove the bar (a terminal) or print the closing line (a log).
    pub fn finish(self) {
        match self.shown {
            Shown::Bar(bar) => bar.finish_and_clear(),
            Shown::Lines(last) => {
                if last.into_inner().is_ok_and(|l| l.printed) {
                    line(&format!("{}: done, {:.1} s", self.what, self.started.elapsed().as_secs_f64()));
                }
            }
        }
    }
}

/// Run `work` while showing that it is alive: a spinner on a terminal, otherwise a line every
/// [`line_interval`] ("check: running, 10 s; estimated 9 s").
pub fn while_running<T: Send>(what: &str, estimated_seconds: f64, work: impl FnOnce() -> T + Send) -> T {
    let started = Instant::now();
    let (done_tx, done_rx) = std::sync::mpsc::channel::<()>();
    std::thread::scope(|scope| {
        let terminal = std::io::stderr().is_terminal();
        scope.spawn(move || {
            let spinner = terminal.then(|| {
                let s = indicatif::ProgressBar::new_spinner();
                s.set_message(format!("{what} (estimated {estimated_seconds:.0} s)"));
                s.enable_steady_tick(Duration::from_millis(200));
                s
            });
            let interval = if terminal { Duration::from_secs(3600) } else { line_interval() };
            while let Err(std::sync::mpsc::RecvTimeoutError::Timeout) = done_rx.recv_timeout(interval) {
                line(&format!(
                    "{what}: running, {:.1} s (estimated {estimated_seconds:.1} s)",
                    started.elapsed().as_secs_f64()
                ));
            }
            if let Some(s) = spinner {
                s.finish_and_clear();
            }
        });
        let out = work();
        let _ = done_tx.send(());
        out
    })
}

/// One line on stderr (errors writing it are ignored: progress is not output).
fn line(text: &str) {
    let _ = writeln!(std::io::stderr().lock(), "{text}");
}
