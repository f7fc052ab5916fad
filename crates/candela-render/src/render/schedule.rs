//! How many samples per pixel each progressive pass takes.
//!
//! The image is rendered in passes over every pixel, so that stopping
//! (Ctrl-C, a time budget) leaves a uniformly sampled image. Short passes
//! stop promptly; long passes waste less on the per-pass overhead. The first
//! pass takes one sample per pixel, and each next pass is sized from the
//! last one's speed to take about [`PASS_TARGET`], never more than the time
//! budget left. The pass size never changes the image: each pixel's samples
//! and their order are fixed.

use std::time::Duration;

/// The wall-clock time a pass aims for.
pub const PASS_TARGET: Duration = Duration::from_millis(500);

/// Largest growth of the pass size from one pass to the next, so that a
/// fast first pass (e.g. most pixels empty) cannot launch a huge one.
const MAX_GROWTH: u32 = 4;

/// The samples per pixel of the next pass, after a pass of `last` samples
/// per pixel took `took`; `remaining` is the time budget left, if any.
/// Returns `None` when the budget is spent.
pub fn next_pass_size(last: u32, took: Duration, remaining: Option<Duration>) -> Option<u32> {
    if remaining.is_some_and(|r| r.is_zero()) {
        return None;
    }
    let target = remaining.map_or(PASS_TARGET, |r| r.min(PASS_TARGET));
    let took = took.as_secs_f64().max(1e-6);
    let ideal = last as f64 * target.as_secs_f64() / took;
    let cap = last.saturating_mul(MAX_GROWTH) as f64;
    Some(ideal.min(cap).max(1.0) as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: fn(u64) -> Duration = Duration::from_millis;

    #[test]
    fn passes_aim_at_the_target_time() {
        // 8 spp took 1 s: 4 spp take the 0.5 s target.
        assert_eq!(next_pass_size(8, MS(1000), None), Some(4));
        // Growth is bounded, and a pass never shrinks below one sample.
        assert_eq!(next_pass_size(2, MS(1), None), Some(8));
        assert_eq!(next_pass_size(1, MS(60_000), None), Some(1));
    }

    #[test]
    fn budget_limits_the_last_pass() {
        // 10 spp per second, 200 ms left: 2 spp.
        assert_eq!(next_pass_size(10, MS(1000), Some(MS(200))), Some(2));
        assert_eq!(next_pass_size(10, MS(1000), Some(Duration::ZERO)), None);
        assert_eq!(next_pass_size(10, MS(1000), Some(MS(1))), Some(1));
    }
}
