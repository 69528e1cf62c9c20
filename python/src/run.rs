//! Long analyses off the interpreter: the work runs on its own thread with the GIL released,
//! while the calling thread waits in slices of [`POLL`] and checks Python's signals between
//! them, so that Ctrl-C raises `KeyboardInterrupt` in the caller within a slice.
//!
//! Stopping the work itself needs a place where the engine reports progress: the discount
//! analysis reports after every probe ([`Cancel::check`] stops it there); an exact solve has no
//! such report, so after Ctrl-C it runs to its end on its thread, unobserved.

use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{channel, RecvTimeoutError};
use std::sync::Arc;
use std::time::Duration;

use pyo3::prelude::*;

use crate::Error;

/// How long the caller waits between two checks of Python's signals.
pub const POLL: Duration = Duration::from_millis(50);

/// The flag the caller raises when Python is interrupted.
#[derive(Clone, Default)]
pub struct Cancel(Arc<AtomicBool>);

/// The unwinding payload of a cancelled analysis (never reported: the caller has raised
/// `KeyboardInterrupt` already).
struct Cancelled;

impl Cancel {
    /// Stops the work (unwinds its thread, without the panic hook) if the caller was
    /// interrupted: call it where the engine reports progress.
    pub fn check(&self) {
        if self.0.load(Ordering::Relaxed) {
            resume_unwind(Box::new(Cancelled));
        }
    }

    fn raise(&self) {
        self.0.store(true, Ordering::Relaxed);
    }
}

/// Runs `work` on its own thread with the GIL released; its `Err` is raised as
/// `truecost.Error` with the message on one line, as the command line prints it.
pub fn interruptible<T, F>(py: Python<'_>, work: F) -> PyResult<T>
where
    T: Send + 'static,
    F: FnOnce(&Cancel) -> Result<T, String> + Send + 'static,
{
    let cancel = Cancel::default();
    let flag = cancel.clone();
    let (tx, mut rx) = channel();
    std::thread::Builder::new()
        .name("truecost".into())
        .spawn(move || {
            let outcome = catch_unwind(AssertUnwindSafe(|| work(&flag)));
            // The caller has gone if it was interrupted: nothing to deliver then.
            let _ = tx.send(outcome);
        })
        .map_err(|e| Error::new_err(format!("cannot start the analysis thread: {e}")))?;
    loop {
        let (back, received) = py.detach(move || {
            let received = rx.recv_timeout(POLL);
            (rx, received)
        });
        rx = back;
        match received {
            Ok(Ok(result)) => {
                return result.map_err(|message| Error::new_err(truecost::echo::one_line(&message)))
            }
            Ok(Err(payload)) => {
                let message = payload
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| payload.downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "unknown".into());
                return Err(Error::new_err(format!(
                    "internal error (please report): {}",
                    truecost::echo::one_line(message.lines().next().unwrap_or(""))
                )));
            }
            Err(RecvTimeoutError::Timeout) => {
                if let Err(interrupt) = py.check_signals() {
                    cancel.raise();
                    return Err(interrupt);
                }
            }
            Err(RecvTimeoutError::Disconnected) => {
                return Err(Error::new_err(
                    "internal error (please report): the analysis thread ended without an answer",
                ))
            }
        }
    }
}
