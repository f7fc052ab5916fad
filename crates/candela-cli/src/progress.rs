//! A progress bar on stderr with samples done, rays per second and ETA;
//! hidden when stderr is not a terminal or with `-q`.
//!
//! The render reports after every tile from its worker threads. The bar's
//! length is the render's upper bound on samples, which shrinks as adaptive
//! sampling retires pixels; under a time budget the bar shows time instead.

use candela_render::render::Progress;
use indicatif::{HumanCount, ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

/// What the bar measures.
enum Measure {
    /// Samples out of the render's bound.
    Samples,
    /// Milliseconds out of the time budget.
    Time,
}

/// The render's progress bar.
pub struct RenderBar {
    bar: ProgressBar,
    measure: Measure,
    /// Largest position shown, so that reports from racing threads never
    /// move the bar back.
    shown: AtomicU64,
}

impl RenderBar {
    /// A bar for a render, by samples or, with a budget, by time.
    pub fn new(budget: Option<Duration>, quiet: bool) -> Self {
        let measure = if budget.is_some() {
            Measure::Time
        } else {
            Measure::Samples
        };
        let bar = if quiet || !std::io::stderr().is_terminal() {
            ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden())
        } else {
            ProgressBar::new(0)
        };
        let template = match measure {
            Measure::Samples => {
                "{spinner} [{elapsed_precise}] {wide_bar} {percent}% {human_pos}/{human_len} samples, {msg}, ETA {eta}"
            }
            Measure::Time => "{spinner} [{elapsed_precise}] {wide_bar} {percent}% of the time budget, {msg}",
        };
        let style =
            ProgressStyle::with_template(template).unwrap_or_else(|_| ProgressStyle::default_bar());
        bar.set_style(style);
        if let Some(budget) = budget {
            bar.set_length(budget.as_millis() as u64);
        }
        Self {
            bar,
            measure,
            shown: AtomicU64::new(0),
        }
    }

    /// Shows a report from the render.
    pub fn update(&self, p: &Progress) {
        let seconds = p.elapsed.as_secs_f64().max(1e-3);
        let rays = p.rays_done as f64 / seconds / 1e6;
        let position = match self.measure {
            Measure::Samples => {
                self.bar.set_length(p.samples_bound);
                p.samples_done
            }
            Measure::Time => p.elapsed.as_millis() as u64,
        };
        let before = self.shown.fetch_max(position, Ordering::Relaxed);
        if position > before {
            self.bar.set_position(position);
            let samples = match self.measure {
                Measure::Samples => String::new(),
                Measure::Time => format!("{} samples, ", HumanCount(p.samples_done)),
            };
            self.bar
                .set_message(format!("{samples}pass {}, {rays:.2} Mrays/s", p.pass + 1));
        }
    }

    /// Removes the bar before the statistics are printed.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}
