//! Stopping a long computation from outside: a [`Cancel`] token that a front end (the Python
//! binding's Ctrl-C, a progress callback that says stop) sets from another thread, and that
//! the simulator, the checker, the search and the report read at their checkpoints (every
//! output sample of a run, every point of a search, between the stages of a report). A
//! stopped computation returns [`Cancelled`] through its crate's error type — no panic
//! unwinds through the libraries — and writes nothing: the outputs are committed only after
//! the last checkpoint, through [`Cancel::commit`]: the gate that makes "stopped" and
//! "committed" exclusive, so a front end may return as soon as [`Cancel::cancel`] returns,
//! without waiting for the computation to reach its next checkpoint.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, PoisonError};

/// A shared flag: once [`Cancel::cancel`] is called, every holder's [`Cancel::check`] fails.
/// Cloning shares the flag. `Cancel::default()` is a fresh token that nobody has set (a
/// computation run without a front end's token is simply never cancelled).
#[derive(Debug, Clone, Default)]
pub struct Cancel(Arc<Token>);

#[derive(Debug, Default)]
struct Token {
    set: AtomicBool,
    /// Held while an output is moved into place ([`Cancel::commit`]) and while the flag is set.
    gate: Mutex<()>,
}

/// The computation was stopped through its [`Cancel`] token.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("cancelled")]
pub struct Cancelled;

impl Cancel {
    /// A token that nobody has set.
    pub fn new() -> Cancel {
        Cancel::default()
    }

    /// Ask every holder to stop at its next checkpoint. Waits for a commit in progress
    /// ([`Cancel::commit`]) to end; once it returns, no commit of this token starts any more.
    pub fn cancel(&self) {
        let _gate = self.0.gate.lock().unwrap_or_else(PoisonError::into_inner);
        self.0.set.store(true, Ordering::Release);
    }

    /// Whether [`Cancel::cancel`] was called.
    pub fn is_cancelled(&self) -> bool {
        self.0.set.load(Ordering::Acquire)
    }

    /// The last checkpoint of a computation that writes: run `move_into_place` (a rename that
    /// makes the output visible) unless the token is set, holding the gate that
    /// [`Cancel::cancel`] takes. So after `cancel` returns, the output either is complete
    /// already or never appears.
    pub fn commit<T, E: From<Cancelled>>(&self, move_into_place: impl FnOnce() -> Result<T, E>) -> Result<T, E> {
        let _gate = self.0.gate.lock().unwrap_or_else(PoisonError::into_inner);
        self.check()?;
        move_into_place()
    }

    /// A checkpoint: `Err(Cancelled)` once the token is set.
    pub fn check(&self) -> Result<(), Cancelled> {
        if self.is_cancelled() {
            Err(Cancelled)
        } else {
            Ok(())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_clone_sees_the_cancel_and_a_fresh_token_does_not() {
        let a = Cancel::new();
        let b = a.clone();
        assert_eq!(b.check(), Ok(()));
        a.cancel();
        assert_eq!(b.check(), Err(Cancelled));
        assert!(!Cancel::default().is_cancelled());
    }

    #[test]
    fn a_commit_runs_before_a_cancel_and_never_after_it() {
        let a = Cancel::new();
        assert_eq!(a.commit(|| Ok::<_, Cancelled>(1)), Ok(1));
        a.cancel();
        let mut ran = false;
        assert_eq!(
            a.commit(|| {
                ran = true;
                Ok::<_, Cancelled>(2)
            }),
            Err(Cancelled)
        );
        assert!(!ran);
    }

    #[test]
    fn cancel_waits_for_a_commit_in_progress() {
        use std::sync::mpsc::channel;
        use std::time::Duration;
        let a = Cancel::new();
        let (inside, started) = channel();
        let b = a.clone();
        let committer = std::thread::spawn(move || {
            b.commit(|| {
                inside.send(()).unwrap();
                std::thread::sleep(Duration::from_millis(200));
                Ok::<_, Cancelled>(std::time::Instant::now())
            })
        });
        started.recv().unwrap();
        a.cancel();
        let cancelled_at = std::time::Instant::now();
        let committed_at = committer.join().unwrap().unwrap();
        // the commit had begun, so it finished before cancel returned
        assert!(committed_at <= cancelled_at);
    }
}
