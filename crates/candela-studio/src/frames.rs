//! Frames for the page: a film's layer as an 8-bit image in a PNG, and
//! when a refinement pass is worth a frame.
//!
//! A frame costs the render its time twice: on the server, the film of the
//! passes so far is copied out of the render's tiles, tone-mapped and
//! encoded while the render threads wait (the copy must be of a pass
//! boundary); in the browser, it is decoded and drawn, which on a machine
//! without a GPU (chromium compositing through SwiftShader) cost about 90 ms
//! of CPU per 800×600 frame, some three times the server's part, on the
//! same cores as the render. Showing every pass cost the studio up to a
//! fifth of the CLI's throughput on 2 cores (BENCHMARKS.md), so refinement
//! frames are paced by [`FramePacing`]: at most [`MAX_FRAMES_PER_SECOND`],
//! and no more often than keeps the server's part under [`FRAME_SHARE`] of
//! the render's time (the browser's part then about three times that, on
//! one of the two cores). The coarse frame and the last frame are always
//! sent; the first pass's frame (the first at full resolution) follows the
//! coarse one after at least `1 / MAX_FRAMES_PER_SECOND`, as the pacing
//! starts with no cost measured.

use crate::protocol::{frame_message, FrameHeader, Layer, Reply};
use crate::worker::Outgoing;
use candela_image::denoise::Oidn;
use candela_image::{
    finite_percentile, heat_image, quantize_u8, rate_image, RgbImage, ToneCurve, ToneMap,
};
use candela_render::film::{denoise_film, Film};
use candela_render::settings::Settings;
use std::time::{Duration, Instant};

/// Most refinement frames per second.
pub const MAX_FRAMES_PER_SECOND: u32 = 8;

/// The largest share of a render's wall-clock time the server may spend
/// building its refinement frames (while a frame is built the render
/// threads wait; the browser's cost of showing it comes on top).
pub const FRAME_SHARE: f64 = 0.01;

/// When the next refinement frame is due: after the last one, at least
/// `1 / MAX_FRAMES_PER_SECOND`, and at least the last frame's cost divided by
/// [`FRAME_SHARE`].
#[derive(Clone, Debug)]
pub struct FramePacing {
    last_sent: Instant,
    last_cost: Duration,
    total_cost: Duration,
}

impl FramePacing {
    /// Pacing from a frame sent at `now` (the coarse frame, or the start).
    pub fn new(now: Instant) -> Self {
        FramePacing {
            last_sent: now,
            last_cost: Duration::ZERO,
            total_cost: Duration::ZERO,
        }
    }

    /// Whether a frame built at `now` is due.
    pub fn due(&self, now: Instant) -> bool {
        let least = Duration::from_secs(1) / MAX_FRAMES_PER_SECOND;
        let wait = least.max(self.last_cost.div_f64(FRAME_SHARE));
        now.saturating_duration_since(self.last_sent) >= wait
    }

    /// A frame was started at `started` and sent at `sent`.
    pub fn sent(&mut self, started: Instant, sent: Instant) {
        self.last_cost = sent.saturating_duration_since(started);
        self.total_cost += self.last_cost;
        self.last_sent = sent;
    }

    /// The time spent building frames so far.
    pub fn total_cost(&self) -> Duration {
        self.total_cost
    }
}

/// The beauty image of a frame: denoised (Open Image Denoise, guided by the
/// albedo and normal layers) on the final frame when the `denoise` setting
/// is on, the raw mean otherwise and during refinement (denoising every
/// pass would slow the refinement down for images about to be replaced).
/// The render refused `denoise` up front if the library cannot be loaded;
/// should denoising itself fail, the raw image is shown.
fn beauty(film: &Film, settings: &Settings, header: &FrameHeader) -> RgbImage {
    if settings.output.denoise && header.done {
        if let Ok(image) = Oidn::load()
            .map_err(|e| e.to_string())
            .and_then(|oidn| denoise_film(film, oidn).map_err(|e| e.to_string()))
        {
            return image;
        }
    }
    film.resolve()
}

/// The frame message of `layer` of `film`.
pub fn encode(film: &Film, settings: &Settings, header: &FrameHeader) -> Outgoing {
    let (w, h) = (film.width, film.height);
    let display = |image: &RgbImage| -> Vec<u8> {
        image
            .pixels()
            .iter()
            .flat_map(|p| p.map(quantize_u8))
            .collect()
    };
    let srgb = ToneMap {
        exposure: 0.0,
        curve: ToneCurve::Srgb,
    };
    let rgb = match header.layer {
        Layer::Beauty => settings
            .output
            .tone_map()
            .to_rgb8(&beauty(film, settings, header)),
        Layer::StdError => settings.output.tone_map().to_rgb8(&film.std_error()),
        Layer::Depth => {
            let depth = film.depth();
            let far = finite_percentile(depth.values(), 0.99)
                .unwrap_or(1.0)
                .max(1e-6);
            depth
                .values()
                .iter()
                .flat_map(|&d| {
                    let v = if d.is_finite() {
                        quantize_u8(1.0 - (d / far).min(1.0) * 0.9)
                    } else {
                        0
                    };
                    [v, v, v]
                })
                .collect()
        }
        Layer::Cost | Layer::CostNodes | Layer::CostTests => {
            let measure = header.layer.cost_measure().unwrap_or_default();
            let cost = film.cost(measure);
            let most = finite_percentile(cost.values(), 0.99)
                .unwrap_or(1.0)
                .max(1.0);
            match heat_image(&cost, most) {
                Ok(image) => display(&image),
                Err(e) => return Outgoing::Text(Reply::error(e.to_string()).to_text()),
            }
        }
        Layer::Albedo => srgb.to_rgb8(&film.albedo()),
        Layer::Normal => {
            let mut n = film.normal();
            for p in n.pixels_mut() {
                *p = p.map(|c| c * 0.5 + 0.5);
            }
            display(&n)
        }
        Layer::Samples => {
            let most = film.sample_counts().into_iter().max().unwrap_or(1).max(1);
            match rate_image(&film.sample_count_image(), most) {
                Ok(image) => display(&image),
                Err(e) => return Outgoing::Text(Reply::error(e.to_string()).to_text()),
            }
        }
    };
    match png_bytes(w, h, &rgb) {
        Ok(png) => Outgoing::Binary(frame_message(header, &png)),
        Err(e) => Outgoing::Text(Reply::error(format!("cannot encode the image: {e}")).to_text()),
    }
}

/// 8-bit RGB as a PNG in memory.
fn png_bytes(width: u32, height: u32, rgb: &[u8]) -> Result<Vec<u8>, png::EncodingError> {
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Fast);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(rgb)?;
    writer.finish()?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_paced_by_rate_and_by_their_cost() {
        let t0 = Instant::now();
        let ms = |m: u64| t0 + Duration::from_millis(m);
        let mut p = FramePacing::new(t0);
        assert!(!p.due(ms(100)), "8 frames/s at most");
        assert!(p.due(ms(125)));
        // A frame that took 30 ms: the next one after 30 / FRAME_SHARE.
        p.sent(ms(200), ms(230));
        let wait = Duration::from_millis(30).div_f64(FRAME_SHARE);
        assert!(
            wait >= Duration::from_millis(500),
            "a frame costs a few percent at most"
        );
        assert!(!p.due(ms(230) + wait - Duration::from_millis(1)));
        assert!(p.due(ms(230) + wait));
        // A frame of 1 ms: the rate limit again.
        p.sent(ms(2000), ms(2001));
        assert_eq!(p.total_cost(), Duration::from_millis(31));
        assert!(Duration::from_millis(1).div_f64(FRAME_SHARE) < Duration::from_millis(125));
        assert!(!p.due(ms(2001 + 124)));
        assert!(p.due(ms(2001 + 125)));
    }
}
