//! A computation's panic as a typed error, caught quietly: [`catch`] runs a closure and turns a
//! panic inside it (on this thread or on a rayon worker running its parallel parts) into
//! [`Panicked`], with the panic's message and source location, instead of a backtrace on
//! stderr and an exit with status 101. The claim checker uses it so that a panic in one claim
//! row becomes that row's `inconclusive` with the reason, and the search so that it becomes
//! the point's `error`.
//!
//! The process-wide panic hook is wrapped once (the first [`catch`]): while a [`catch`] is
//! running on this thread, or on any thread when the panicking thread is a rayon worker (whose
//! panics rayon carries back to the caller of `join`/`par_iter`), the hook records the message
//! and location instead of printing them; every other panic goes to the previous hook
//! unchanged (a test's failed assertion still prints).

use std::cell::Cell;
use std::panic::{AssertUnwindSafe, PanicHookInfo};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, Once};

/// A panic caught by [`catch`]: what it said and where.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("an internal error of wingcheck (a panic at {location}: {message})")]
pub struct Panicked {
    /// The panic's message (`"exponent"`, `"Eigval error: Eigen(1)"`).
    pub message: String,
    /// `file:line:column` of the panic, or `unknown place` when it was not recorded.
    pub location: String,
}

/// Catches running on any thread (a rayon worker's panic is quiet while one runs).
static ACTIVE: AtomicUsize = AtomicUsize::new(0);
/// Panics recorded by the hook and not yet claimed by their [`catch`] (message, location); at
/// most [`RECORDED_MAX`] are kept.
static RECORDED: Mutex<Vec<(String, String)>> = Mutex::new(Vec::new());
const RECORDED_MAX: usize = 64;
static HOOK: Once = Once::new();

thread_local! {
    /// [`catch`]es running on this thread.
    static DEPTH: Cell<usize> = const { Cell::new(0) };
}

fn payload_text(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<String>()
        .cloned()
        .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
        .unwrap_or_else(|| "a panic without a message".to_string())
}

fn install_hook() {
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info: &PanicHookInfo<'_>| {
            let here = DEPTH.with(Cell::get) > 0;
            let worker = rayon::current_thread_index().is_some() && ACTIVE.load(Ordering::SeqCst) > 0;
            if !(here || worker) {
                return previous(info);
            }
            let location = info.location().map_or("unknown place".to_string(), |l| l.to_string());
            let mut recorded = RECORDED.lock().unwrap_or_else(|p| p.into_inner());
            if recorded.len() >= RECORDED_MAX {
                recorded.remove(0);
            }
            recorded.push((payload_text(info.payload()), location));
        }));
    });
}

/// Decrements the counters when a [`catch`] ends, however it ends.
struct Active;

impl Drop for Active {
    fn drop(&mut self) {
        DEPTH.with(|d| d.set(d.get() - 1));
        ACTIVE.fetch_sub(1, Ordering::SeqCst);
    }
}

/// Runs `f`; a panic inside it (also in the rayon jobs it waits for) is returned as
/// [`Panicked`] instead of unwinding further, without printing anything.
pub fn catch<T>(f: impl FnOnce() -> T) -> Result<T, Panicked> {
    install_hook();
    let result = {
        DEPTH.with(|d| d.set(d.get() + 1));
        ACTIVE.fetch_add(1, Ordering::SeqCst);
        let _active = Active;
        std::panic::catch_unwind(AssertUnwindSafe(f))
    };
    result.map_err(|payload| {
        let message = payload_text(payload.as_ref());
        let mut recorded = RECORDED.lock().unwrap_or_else(|p| p.into_inner());
        let location = match recorded.iter().rposition(|(m, _)| *m == message) {
            Some(i) => recorded.remove(i).1,
            None => "unknown place".to_string(),
        };
        Panicked { message, location }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_becomes_an_error_with_its_message_and_place() {
        let e = catch(|| -> u32 { panic!("boom {}", 7) }).unwrap_err();
        assert_eq!(e.message, "boom 7");
        assert!(e.location.contains("panics.rs"), "{}", e.location);
        assert_eq!(catch(|| 5).unwrap(), 5);
    }

    #[test]
    fn a_panic_in_a_rayon_job_is_caught_by_the_caller() {
        use rayon::prelude::*;
        let e = catch(|| (0..64).into_par_iter().map(|i| if i == 37 { panic!("row {i}") } else { i }).sum::<i32>())
            .unwrap_err();
        assert_eq!(e.message, "row 37");
        assert!(e.location.contains("panics.rs"), "{}", e.location);
    }

    #[test]
    fn nested_catches_report_the_inner_panic_once() {
        let outer = catch(|| catch(|| -> () { panic!("inner") }).unwrap_err()).unwrap();
        assert_eq!(outer.message, "inner");
    }
}
