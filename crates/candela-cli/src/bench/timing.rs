//! Timing helpers: wall clock and process CPU time, so throughput can be
//! normalised per core on a shared machine (as the Embree figures are).

use std::time::Instant;

/// Process CPU time (user + system) in seconds, from `/proc/self/stat`
/// (10 ms resolution); `None` where that file does not exist.
pub fn cpu_seconds() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the parenthesised command name; utime and stime are 14 and 15.
    let rest = &s[s.rfind(')')? + 2..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks: f64 = f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
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

/// Runs `pass` (which traces `rays_per_pass` rays) until at least
/// `min_seconds` have passed, after one untimed warm-up pass.
pub fn measure(
    rays_per_pass: u64,
    min_seconds: f64,
    mut pass: impl FnMut() -> u64,
) -> (Measure, u64) {
    let mut hits = pass();
    let (start, cpu0) = (Instant::now(), cpu_seconds());
    let mut passes = 0u64;
    while passes == 0 || start.elapsed().as_secs_f64() < min_seconds {
        hits = std::hint::black_box(pass());
        passes += 1;
    }
    let wall = start.elapsed().as_secs_f64();
    let cpu = cpu0.zip(cpu_seconds()).map(|(a, b)| b - a);
    (
        Measure {
            rays: rays_per_pass * passes,
            wall,
            cpu,
        },
        hits,
    )
}
