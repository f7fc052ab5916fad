//! Talking to a running render: cancellation and progress reports.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

/// A cancellation flag shared between a render and whoever may stop it (a
/// Ctrl-C handler, a Python `KeyboardInterrupt`, a GUI button). Clones share
/// the flag. A cancelled render discards the pass in progress and returns
/// the film of the passes it finished, so the image stays uniformly sampled.
#[derive(Clone, Debug, Default)]
pub struct Cancel(Arc<AtomicBool>);

impl Cancel {
    /// A flag that is not set.
    pub fn new() -> Self {
        Self::default()
    }

    /// Asks the render to stop; safe from any thread or signal handler.
    pub fn cancel(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// Whether [`Cancel::cancel`] was called.
    pub fn is_cancelled(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }
}

/// A progress report, sent after every tile of every pass (from the worker
/// threads, so keep the handler cheap).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Progress {
    /// Samples the tile that just finished took.
    pub tile_samples: u64,
    /// Samples taken so far, the current pass included.
    pub samples_done: u64,
    /// An upper bound on the samples the whole render will take: every pixel
    /// still sampling runs to the end of its range. It shrinks as adaptive
    /// sampling retires pixels.
    pub samples_bound: u64,
    /// The pass in progress, from 0.
    pub pass: u32,
    /// Wall-clock time since the render started.
    pub elapsed: Duration,
}

/// Optional hooks into a render: a cancellation flag and a progress
/// handler. The default has neither.
#[derive(Clone, Default)]
pub struct RenderControl<'a> {
    /// Checked between pixels; see [`Cancel`].
    pub cancel: Option<Cancel>,
    /// Called after every tile.
    pub progress: Option<&'a (dyn Fn(&Progress) + Sync)>,
}

impl RenderControl<'_> {
    pub(crate) fn cancelled(&self) -> bool {
        self.cancel.as_ref().is_some_and(Cancel::is_cancelled)
    }
}
