//! Timing helpers: wall clock and process CPU time, so throughput can be
//! normalised per core on a shared machine (as the Embree figures are).

use std::time::Instant;

/// CPU time of all the process's threads in seconds, summed from each
/// thread's `/proc/self/task/*/schedstat` (nanosecond run time; the tick
/// counts of `/proc/self/stat` are too coarse and sampled under contention).
/// `None` where those files do not exist.
pub fn cpu_seconds() -> Option<f64> {
    let mut ns = 0u64;
    for task in std::fs::read_dir("/proc/self/task").ok()? {
        let path = task.ok()?.path().join("schedstat");
        let text = std::fs::read_to_string(path).ok()?;
        ns += text.split_whitespace().next()?.parse::<u64>().ok()?;
    }
    Some(ns as f64 * 1e-9)
}

/// A measured run: rays traced, wall seconds and CPU seconds.
pub struct Measure {
    /// Rays traced in total.
    pub rays: u64,
    /// Wall-clock seconds.
    pub wall: f64,
    /// Process CPU seconds, if known.
    pub cpu: Option<f64>,
}

impl Measure {
    /// Mrays/s of wall time.
    pub fn wall_rate(&self) -> f64 {
        self.rays as f64 / self.wall / 1e6
    }
    /// Mrays/s per second of CPU time: per-core throughput, insensitive to
    /// other processes taking turns on the cores.
    pub fn cpu_rate(&self) -> Option<f64> {
        self.cpu
            .filter(|&c| c > 0.0)
            .map(|c| self.rays as f64 / c / 1e6)
    }
}

/// Runs `pass` (which traces `rays_per_pass` rays) repeatedly for at least
/// `min_seconds` after one untimed warm-up pass, and keeps the fastest pass
/// by CPU time (by wall time where CPU time is unknown): on a machine shared
/// with other work, the fastest pass is the least disturbed one.
pub fn measure(
    rays_per_pass: u64,
    min_seconds: f64,
    mut pass: impl FnMut() -> u64,
) -> (Measure, u64) {
    let mut hits = pass();
    let start = Instant::now();
    let mut best: Option<Measure> = None;
    while best.is_none() || start.elapsed().as_secs_f64() < min_seconds {
        let (t0, c0) = (Instant::now(), cpu_seconds());
        hits = std::hint::black_box(pass());
        let wall = t0.elapsed().as_secs_f64();
        let cpu = c0
            .zip(cpu_seconds())
            .map(|(a, b)| b - a)
            .filter(|&c| c > 0.0);
        let m = Measure {
            rays: rays_per_pass,
            wall,
            cpu,
        };
        let key = |m: &Measure| m.cpu_rate().unwrap_or(m.wall_rate());
        if best.as_ref().is_none_or(|b| key(&m) > key(b)) {
            best = Some(m);
        }
    }
    let best = best.unwrap_or(Measure {
        rays: 0,
        wall: 1.0,
        cpu: None,
    });
    (best, hits)
}
