//! One connection's renderer: a thread that owns the render scene, renders
//! progressively for each request and streams images back.
//!
//! A render request resolves the page's settings changes with
//! [`Settings::resolve`] (the scene's hints under them), moves the camera
//! of the built scene with [`Scene::camera_for`] (rebuilding the scene only
//! when a setting the build reads changes), then renders:
//! 1. a coarse frame: one sample per pixel at a fraction of the resolution
//!    (about [`COARSE_PIXELS`] pixels), so the image follows a camera stop
//!    at once;
//! 2. refinement passes over sample ranges of doubling length (`0..1`,
//!    `1..3`, `3..7`, ..., a short remainder joining the last) up to the
//!    target count, each added to the film (the film stores sums,
//!    so the result is the film of one render of `0..spp`, up to f64
//!    rounding), an image sent after each. Adaptive sampling and time
//!    budgets see all of a render's samples, so with either the refinement
//!    is one render.
//!
//! A newer request, or a cancel from the page, sets the render's
//! [`Cancel`] flag, which the render loop checks between pixels.

use crate::command_line::command_line;
use crate::protocol::{frame_message, FrameHeader, Layer, Reply, SaveFormat};
use crate::scene_pool::{scene_for, BuildKey, ScenePool};
use candela_image::denoise::Oidn;
use candela_image::{
    finite_percentile, heat_image, quantize_u8, rate_image, RgbImage, ToneCurve, ToneMap,
};
use candela_render::film::{denoise_film, write_film, Film, OutputOptions};
use candela_render::integrator::inspect::trace_paths;
use candela_render::render::{render_with, Cancel, RenderControl, RenderSettings, StopReason};
use candela_render::scene::Scene;
use candela_render::settings::Settings;
use candela_scene::Loaded;
use serde_json::{Map, Value};
use std::ops::Range;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::sync::Arc;
use std::time::Instant;

/// Pixels of the coarse frame, about: 200 × 150.
pub const COARSE_PIXELS: u32 = 200 * 150;

/// What the worker is asked to do.
pub enum Job {
    /// Render with these settings changes.
    Render(RenderJob),
    /// Show another layer of the last film.
    Layer {
        /// The page's id of the request, echoed in the frame.
        id: u64,
        /// The layer to show.
        layer: Layer,
    },
    /// Trace samples `0..samples` of pixel (x, y) of the last render.
    Inspect {
        /// The pixel.
        pixel: (u32, u32),
        /// How many samples.
        samples: u32,
    },
    /// Write the last film.
    Save(SaveFormat),
}

/// A render request, as the worker runs it and as the session keeps it:
/// to cancel it, to see whether it has finished, and to start it again
/// showing another layer.
#[derive(Clone)]
pub struct RenderJob {
    /// The page's id of the request; its frames carry it.
    pub id: u64,
    /// Changes to the scene's settings.
    pub changes: Map<String, Value>,
    /// The layer to show.
    pub layer: Layer,
    /// Set when a newer request or a cancel arrives.
    pub cancel: Cancel,
    /// Set by the worker once the render has sent its last frame, or has
    /// stopped (cancelled, or an error).
    pub finished: Arc<AtomicBool>,
    /// When the request arrived.
    pub received: Instant,
}

impl RenderJob {
    /// A new request, arrived now.
    pub fn new(id: u64, changes: Map<String, Value>, layer: Layer) -> Self {
        RenderJob {
            id,
            changes,
            layer,
            cancel: Cancel::new(),
            finished: Arc::new(AtomicBool::new(false)),
            received: Instant::now(),
        }
    }

    /// The same render showing `layer`, as request `id`, arrived now.
    pub fn again(&self, id: u64, layer: Layer) -> Self {
        RenderJob::new(id, self.changes.clone(), layer)
    }

    /// Whether the worker is done with it.
    pub fn is_finished(&self) -> bool {
        self.finished.load(Ordering::Acquire)
    }
}

/// A message for the page.
#[derive(Debug, PartialEq)]
pub enum Outgoing {
    /// JSON text.
    Text(String),
    /// A frame (see [`frame_message`]).
    Binary(Vec<u8>),
}

/// What every connection's worker shares: the loaded scene and where it
/// came from.
pub struct Source {
    /// The scene description and its hints.
    pub loaded: Loaded,
    /// The scene file (`None`: the demo), for the command line.
    pub path: Option<PathBuf>,
    /// Where saved images go.
    pub out_dir: PathBuf,
    /// Settings given on the command line, under the page's changes.
    pub base: Map<String, Value>,
    /// Built scenes no worker holds.
    pub scenes: ScenePool,
}

/// Starts a worker thread; it runs until the job sender is dropped.
pub fn spawn(
    source: Arc<Source>,
    send: impl Fn(Outgoing) + Send + 'static,
) -> std::io::Result<mpsc::Sender<Job>> {
    let (tx, rx) = mpsc::channel();
    std::thread::Builder::new()
        .name("studio-render".into())
        .spawn(move || {
            let mut worker = Worker {
                source,
                send: Box::new(send),
                scene: None,
                last: None,
                saved: 0,
            };
            for job in rx {
                worker.run(job);
            }
        })?;
    Ok(tx)
}

/// The film shown last, with what it needs to be shown or saved again.
struct LastFilm {
    film: Film,
    settings: Settings,
    header: FrameHeader,
}

struct Worker {
    source: Arc<Source>,
    send: Box<dyn Fn(Outgoing) + Send>,
    scene: Option<(Scene, BuildKey)>,
    last: Option<LastFilm>,
    saved: u32,
}

impl Drop for Worker {
    /// The next tab (or this one, reloaded) takes the scene over.
    fn drop(&mut self) {
        if let Some((scene, key)) = self.scene.take() {
            self.source.scenes.give(scene, key);
        }
    }
}

impl Worker {
    fn run(&mut self, job: Job) {
        match job {
            Job::Render(job) => {
                if !job.cancel.is_cancelled() {
                    if let Err(message) = self.render(&job) {
                        self.reply(Reply::error(message));
                    }
                }
                job.finished.store(true, Ordering::Release);
            }
            Job::Layer { id, layer } => match &mut self.last {
                Some(last) => {
                    last.header.layer = layer;
                    last.header.job = id;
                    let msg = encode(&last.film, &last.settings, &last.header);
                    (self.send)(msg);
                }
                None => self.reply(Reply::error("no image yet")),
            },
            Job::Inspect { pixel, samples } => {
                let reply = self.inspect(pixel, samples).unwrap_or_else(Reply::error);
                self.reply(reply);
            }
            Job::Save(format) => {
                let reply = self.save(format).unwrap_or_else(Reply::error);
                self.reply(reply);
            }
        }
    }

    fn reply(&self, reply: Reply) {
        (self.send)(Outgoing::Text(reply.to_text()));
    }

    fn render(&mut self, job: &RenderJob) -> Result<(), String> {
        let RenderJob {
            id,
            changes,
            layer,
            cancel,
            received,
            ..
        } = job;
        let (id, layer, received) = (*id, *layer, *received);
        let mut changes_all = self.source.base.clone();
        changes_all.extend(changes.iter().map(|(k, v)| (k.clone(), v.clone())));
        let settings = Settings::resolve(&self.source.loaded.hints, &changes_all)
            .map_err(|e| e.to_string())?;
        if settings.output.denoise {
            // As the CLI: a denoiser that cannot be loaded is refused before
            // anything renders, never silently skipped.
            Oidn::load().map_err(|e| format!("--denoise: {e}"))?;
        }
        let path = self.source.path.as_deref();
        let command = command_line(path, &settings, &changes_all, "candela.png");
        let base = settings.render_settings();
        let control = RenderControl {
            cancel: Some(cancel.clone()),
            progress: None,
        };
        let (width, height) = (settings.image.width, settings.image.height);
        // A cell is drawn over the last image of the same size (CS184's
        // black elsewhere when there is none).
        let backdrop = match (&self.last, base.cell) {
            (Some(last), Some(_)) if (last.film.width, last.film.height) == (width, height) => {
                last.film.clone()
            }
            _ => Film::new(width, height),
        };
        let scene = scene_for(&mut self.scene, &self.source, &settings)?;
        let mut header = FrameHeader {
            job: id,
            coarse: true,
            spp: 1,
            target_spp: base.spp,
            done: false,
            width,
            height,
            render_width: width,
            render_height: height,
            layer,
            elapsed_ms: 0.0,
            render_ms: 0.0,
            command,
        };
        let send = &self.send;
        if base.cell.is_none() {
            let t = Instant::now();
            let coarse = render_coarse(scene, &base, &control)?;
            header.render_ms += t.elapsed().as_secs_f64() * 1e3;
            let Some(film) = coarse else {
                return Ok(());
            };
            (header.width, header.height) = (film.width, film.height);
            header.elapsed_ms = received.elapsed().as_secs_f64() * 1e3;
            send(encode(&film, &settings, &header));
        }
        (header.coarse, header.width, header.height) = (false, width, height);
        // The film shown is summed in place, pass by pass: a film at
        // 800×600 is some 70 MB, and a copy of it per pass costs as much
        // as a pass of a few samples. A cell is summed over the backdrop
        // with the cell's own pixels cleared (outside the cell a pass's
        // film is zero, and adding zero is exact). The previous film stays
        // the last one until the first pass lands.
        let mut first = Some(backdrop);
        if let (Some(film), Some(cell)) = (&mut first, base.cell) {
            let w = film.width as usize;
            for (x, y) in cell.pixels() {
                film.pixels[y as usize * w + x as usize] = Default::default();
            }
        }
        let ranges = refinement_ranges(&base);
        let last_range = ranges.len() - 1;
        for (k, range) in ranges.into_iter().enumerate() {
            let pass = RenderSettings {
                sample_range: Some(range.clone()),
                ..base.clone()
            };
            let t = Instant::now();
            let out = render_with(scene, &pass, &control).map_err(|e| e.to_string())?;
            header.render_ms += t.elapsed().as_secs_f64() * 1e3;
            if out.stop == StopReason::Cancelled {
                return Ok(());
            }
            let last = match first.take() {
                Some(film) => self.last.insert(LastFilm {
                    film,
                    settings: settings.clone(),
                    header: header.clone(),
                }),
                None => self
                    .last
                    .as_mut()
                    .ok_or("the film of the first pass is gone")?,
            };
            last.film.merge(&out.film).map_err(|e| e.to_string())?;
            header.spp = range.end.min(base.spp);
            if base.adaptive.is_some() || base.time_budget.is_some() {
                header.spp = last.film.sample_spread(settings.image.region()).max;
            }
            header.done = k == last_range;
            header.elapsed_ms = received.elapsed().as_secs_f64() * 1e3;
            last.header = header.clone();
            let frame = encode(&last.film, &settings, &header);
            if header.done {
                // Before the page can see the last frame and ask for
                // another layer of this film.
                job.finished.store(true, Ordering::Release);
            }
            send(frame);
        }
        Ok(())
    }

    /// The path inspector: the last render's samples of one pixel, traced
    /// by the renderer's own sample function with a recorder.
    fn inspect(&mut self, pixel: (u32, u32), samples: u32) -> Result<Reply, String> {
        let last = self.last.as_ref().ok_or("no image to inspect yet")?;
        let settings = last.settings.clone();
        let (w, h) = (last.film.width, last.film.height);
        if pixel.0 >= w || pixel.1 >= h {
            return Err(format!(
                "pixel ({}, {}) lies outside the {w}x{h} image",
                pixel.0, pixel.1
            ));
        }
        let sums = *last.film.pixel(pixel.0, pixel.1);
        let film_mean = if sums.count > 0 {
            (sums.radiance / sums.count as f64).to_array()
        } else {
            [0.0; 3]
        };
        let scene = scene_for(&mut self.scene, &self.source, &settings)?;
        let paths = trace_paths(scene, &settings.render_settings(), pixel, 0..samples)
            .map_err(|e| e.to_string())?;
        Ok(Reply::Paths {
            pixel: [pixel.0, pixel.1],
            paths,
            film_mean,
            film_samples: sums.count,
        })
    }

    fn save(&mut self, format: SaveFormat) -> Result<Reply, String> {
        let last = self.last.as_ref().ok_or("no image to save yet")?;
        self.saved += 1;
        let name = format!(
            "studio-{}-{}.{}",
            std::process::id(),
            self.saved,
            format.extension()
        );
        let path = self.source.out_dir.join(name);
        let adaptive = last.settings.sampling.adaptive.is_some();
        let opts = OutputOptions {
            tone: last.settings.output.tone_map(),
            aovs: true,
            sample_counts: true,
            depth: true,
            cost: true,
            variance: true,
            info: Default::default(),
            rate_image: adaptive.then_some(last.header.target_spp),
        };
        let written = write_film(&path, &last.film, &opts).map_err(|e| e.to_string())?;
        Ok(Reply::Saved {
            files: written.iter().map(|p| p.display().to_string()).collect(),
        })
    }
}

/// One sample per pixel of the scene's camera at about [`COARSE_PIXELS`]
/// pixels; `None` if cancelled.
fn render_coarse(
    scene: &mut Scene,
    base: &RenderSettings,
    control: &RenderControl,
) -> Result<Option<Film>, String> {
    let full = scene.camera.clone();
    let (w, h) = (full.width, full.height);
    let shrink = ((w as f64 * h as f64 / COARSE_PIXELS as f64).sqrt().ceil() as u32).max(1);
    // The same view at fewer pixels: rays depend on the pixel's position
    // relative to the image size only.
    scene.camera.width = w.div_ceil(shrink);
    scene.camera.height = h.div_ceil(shrink);
    let coarse = RenderSettings {
        sample_range: Some(0..1),
        adaptive: None,
        time_budget: None,
        ..base.clone()
    };
    let out = render_with(scene, &coarse, control);
    scene.camera = full;
    let out = out.map_err(|e| e.to_string())?;
    Ok((out.stop != StopReason::Cancelled).then_some(out.film))
}

/// The sample ranges of the refinement: doubling from one sample, or the
/// whole render at once when adaptive sampling or a time budget needs to
/// see all of its samples.
pub fn refinement_ranges(base: &RenderSettings) -> Vec<Range<u32>> {
    let all = base.samples();
    if base.adaptive.is_some() || base.time_budget.is_some() {
        return vec![all];
    }
    let mut ranges = Vec::new();
    let mut start = all.start;
    let mut step = 1u32;
    while start < all.end {
        let mut end = start.saturating_add(step).min(all.end);
        // A remainder shorter than the next step joins this range: each
        // range costs a film's worth of set-up, summing and encoding
        // besides its samples, which a short last range would not repay.
        if all.end - end < step.saturating_mul(2) {
            end = all.end;
        }
        ranges.push(start..end);
        start = end;
        step = step.saturating_mul(2);
    }
    ranges
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
    fn refinement_ranges_double_and_cover_the_samples_once() {
        let base = RenderSettings {
            spp: 13,
            ..Default::default()
        };
        let r = refinement_ranges(&base);
        assert_eq!(r, vec![0..1, 1..3, 3..13], "6 left after 3..7: joined");
        let sixteen = RenderSettings {
            spp: 16,
            ..Default::default()
        };
        assert_eq!(
            refinement_ranges(&sixteen),
            vec![0..1, 1..3, 3..7, 7..16],
            "no range of one sample at the end"
        );
        let one = RenderSettings {
            spp: 1,
            ..Default::default()
        };
        assert_eq!(refinement_ranges(&one), vec![0..1]);
    }
}
