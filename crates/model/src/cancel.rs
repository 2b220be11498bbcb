//! Stopping a long computation from outside: a [`Cancel`] token that a front end (the Python
//! binding's Ctrl-C, a progress callback that says stop) sets from another thread, and that
//! the simulator, the checker, the search and the report read at their checkpoints (every
//! output sample of a run, every point of a search, between the stages of a report). A
//! stopped computation returns [`Cancelled`] through its crate's error type — no panic
//! unwinds through the libraries — and writes nothing: the outputs are committed only after
//! the last checkpoint.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// A shared flag: once [`Cancel::cancel`] is called, every holder's [`Cancel::check`] fails.
/// Cloning shares the flag. `Cancel::default()` is a fresh token that nobody has set (a
/// computation run without a front end's token is simply never cancelled).
#[derive(Debug, Clone, Default)]
pub struct Cancel(Arc<AtomicBool>);

/// The computation was stopped through its [`Cancel`] token.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("cancelled")]
pub struct Cancelled;

impl Cancel {
    /// A token that nobody has set.
    pub fn new() -> Cancel {
        Cancel::default()
    }

    /// Ask every holder to stop at its next checkpoint.
    pub fn cancel(&self) {
        self.0.store(true, Ordering::Release);
    }

    /// Whether [`Cancel::cancel`] was called.
    pub fn is_cancelled(&self) -> bool {
        self.0.load(Ordering::Acquire)
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
}
