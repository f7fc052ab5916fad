//! Running untrusted-input code so that a panic or a hang becomes a test
//! failure naming the input rather than a crashed or stuck test run.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// How a guarded call ended.
#[derive(Debug)]
pub enum Outcome<T> {
    /// It returned this, after this long.
    Returned(T, Duration),
    /// It panicked with this message.
    Panicked(String),
    /// It was still running after the time limit (its thread is left
    /// behind; the test is failing anyway).
    TimedOut,
}

/// Calls `f` on a thread of its own inside `catch_unwind`, waiting at most
/// `limit`. A thread per call, so a hang cannot block the caller.
pub fn guarded<T, F>(limit: Duration, f: F) -> Outcome<T>
where
    T: Send + 'static,
    F: FnOnce() -> T + Send + 'static,
{
    let (tx, rx) = mpsc::channel();
    let start = Instant::now();
    std::thread::spawn(move || {
        let result = catch_unwind(AssertUnwindSafe(f)).map_err(|payload| panic_message(&*payload));
        let _ = tx.send(result);
    });
    match rx.recv_timeout(limit) {
        Ok(Ok(value)) => Outcome::Returned(value, start.elapsed()),
        Ok(Err(message)) => Outcome::Panicked(message),
        Err(mpsc::RecvTimeoutError::Timeout) => Outcome::TimedOut,
        Err(mpsc::RecvTimeoutError::Disconnected) => {
            Outcome::Panicked("the thread ended without a result".into())
        }
    }
}

fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "a panic without a message".into()
    }
}

/// The end of a sweep over `total` untrusted inputs: prints how long it
/// took and `summary`, then fails naming every input in `failures` (one
/// line each, the input first), so a sweep reports all its misbehaving
/// inputs at once rather than the first.
pub fn assert_all_behaved(total: usize, failures: &[String], started: Instant, summary: &str) {
    eprintln!("{total} inputs ({summary}) in {:.2?}", started.elapsed());
    assert!(
        failures.is_empty(),
        "{} of {total} inputs misbehaved:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
