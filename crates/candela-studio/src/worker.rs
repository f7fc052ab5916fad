//! One connection's renderer: a thread that renders progressively for each
//! request and streams images back, and a second thread that answers the
//! requests about the film shown (path inspector, save, another layer)
//! without waiting for a render ([`crate::film_requests`]).
//!
//! A render request resolves the page's settings changes with
//! [`Settings::resolve`] (the scene's hints under them), moves the camera
//! of the built scene with [`Scene::camera_for`] (rebuilding the scene only
//! when a setting the build reads changes), then renders:
//! 1. a coarse frame: one sample per pixel at a fraction of the resolution
//!    (about [`COARSE_PIXELS`] pixels), so the image follows a camera stop
//!    at once;
//! 2. the render itself: one [`render_from`] of all the samples, exactly
//!    the CLI's render (the same film bit for bit), whose progressive
//!    passes (1 sample per pixel, then passes sized to about half a second)
//!    end with a frame of the film so far when [`FramePacing`] says one is
//!    due, and always with the last frame. Adaptive sampling and time
//!    budgets see all of the render's samples.
//!
//! A newer request, or a cancel from the page, sets the render's
//! [`Cancel`] flag, which the render loop checks between pixels.
//!
//! The two threads share the scene (read by both while a render runs;
//! written only to move the camera and for the coarse frame, which renders
//! at a smaller size) and the film shown last.

use crate::command_line::command_line;
use crate::frames::{encode, FramePacing};
use crate::protocol::{FrameHeader, Layer, Reply, SaveFormat};
use crate::scene_pool::{scene_for, BuildKey, ScenePool};
use candela_image::denoise::Oidn;
use candela_render::film::Film;
use candela_render::render::{
    render_from, render_with, Cancel, Continuation, PassEnd, RenderControl, RenderSettings,
    StopReason,
};
use candela_render::scene::Scene;
use candela_render::settings::Settings;
use candela_scene::Loaded;
use serde_json::{Map, Value};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Arc, Mutex, RwLock, RwLockReadGuard};
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

/// Where a connection's messages go.
pub type Sender = Arc<dyn Fn(Outgoing) + Send + Sync>;

/// What a connection's two threads share.
pub(crate) struct Connection {
    pub(crate) source: Arc<Source>,
    pub(crate) send: Sender,
    /// The film of the last frame sent (shared, so a save or an inspection
    /// can hold it while the render goes on).
    pub(crate) last: Mutex<Option<Arc<LastFilm>>>,
    pub(crate) scene: RwLock<SceneSlot>,
}

/// The connection's scene and the settings of the render that placed its
/// camera last.
#[derive(Default)]
pub(crate) struct SceneSlot {
    pub(crate) built: Option<(Scene, BuildKey)>,
    pub(crate) settings: Option<Settings>,
}

/// The film of a frame, with what it needs to be shown or saved again.
pub(crate) struct LastFilm {
    pub(crate) film: Film,
    pub(crate) settings: Settings,
    pub(crate) header: FrameHeader,
}

impl Connection {
    pub(crate) fn reply(&self, reply: Reply) {
        (self.send)(Outgoing::Text(reply.to_text()));
    }

    pub(crate) fn last_film(&self) -> Option<Arc<LastFilm>> {
        self.last.lock().unwrap_or_else(|e| e.into_inner()).clone()
    }

    fn show(&self, last: LastFilm) {
        let msg = encode(&last.film, &last.settings, &last.header);
        *self.last.lock().unwrap_or_else(|e| e.into_inner()) = Some(Arc::new(last));
        (self.send)(msg);
    }

    pub(crate) fn read_scene(&self) -> RwLockReadGuard<'_, SceneSlot> {
        self.scene.read().unwrap_or_else(|e| e.into_inner())
    }
}

impl Drop for Connection {
    /// The next tab (or this one, reloaded) takes the scene over.
    fn drop(&mut self) {
        let slot = self.scene.get_mut().unwrap_or_else(|e| e.into_inner());
        if let Some((scene, key)) = slot.built.take() {
            self.source.scenes.give(scene, key);
        }
    }
}

/// The job queues of a connection's two threads.
pub struct Jobs {
    render: mpsc::Sender<Job>,
    requests: mpsc::Sender<Job>,
}

impl Jobs {
    /// Queues `job` on the thread that runs it: renders on the render
    /// thread, the rest on the requests thread. Fails once the threads have
    /// ended.
    pub fn send(&self, job: Job) -> Result<(), mpsc::SendError<Job>> {
        match job {
            Job::Render(_) => self.render.send(job),
            _ => self.requests.send(job),
        }
    }
}

/// Starts a connection's threads; they run until [`Jobs`] is dropped.
pub fn spawn(
    source: Arc<Source>,
    send: impl Fn(Outgoing) + Send + Sync + 'static,
) -> std::io::Result<Jobs> {
    let conn = Arc::new(Connection {
        source,
        send: Arc::new(send),
        last: Mutex::new(None),
        scene: RwLock::new(SceneSlot::default()),
    });
    let (renders, render_rx) = mpsc::channel();
    let (requests, requests_rx) = mpsc::channel();
    let for_requests = conn.clone();
    std::thread::Builder::new()
        .name("studio-requests".into())
        .spawn(move || {
            for job in requests_rx {
                crate::film_requests::answer(&for_requests, job);
            }
        })?;
    std::thread::Builder::new()
        .name("studio-render".into())
        .spawn(move || {
            for job in render_rx {
                if let Job::Render(job) = job {
                    if !job.cancel.is_cancelled() {
                        if let Err(message) = render(&conn, &job) {
                            conn.reply(Reply::error(message));
                        }
                    }
                    job.finished.store(true, Ordering::Release);
                }
            }
        })?;
    Ok(Jobs {
        render: renders,
        requests,
    })
}

fn render(conn: &Connection, job: &RenderJob) -> Result<(), String> {
    let RenderJob {
        id,
        changes,
        layer,
        cancel,
        received,
        ..
    } = job;
    let (id, layer, received) = (*id, *layer, *received);
    let source = &conn.source;
    let mut changes_all = source.base.clone();
    changes_all.extend(changes.iter().map(|(k, v)| (k.clone(), v.clone())));
    let settings =
        Settings::resolve(&source.loaded.hints, &changes_all).map_err(|e| e.to_string())?;
    if settings.output.denoise {
        // As the CLI: a denoiser that cannot be loaded is refused before
        // anything renders, never silently skipped.
        Oidn::load().map_err(|e| format!("--denoise: {e}"))?;
    }
    let command = command_line(
        source.path.as_deref(),
        &settings,
        &changes_all,
        "candela.png",
    );
    let base = settings.render_settings();
    let control = RenderControl {
        cancel: Some(cancel.clone()),
        progress: None,
    };
    let (width, height) = (settings.image.width, settings.image.height);
    // A cell is drawn over the last image of the same size (CS184's black
    // elsewhere when there is none), with the cell's own pixels cleared:
    // outside the cell the render's film is zero, and adding zero is exact.
    let backdrop = base.cell.map(|cell| {
        let mut film = match conn.last_film() {
            Some(last) if (last.film.width, last.film.height) == (width, height) => {
                last.film.clone()
            }
            _ => Film::new(width, height),
        };
        let w = film.width as usize;
        for (x, y) in cell.pixels() {
            film.pixels[y as usize * w + x as usize] = Default::default();
        }
        film
    });
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
    {
        // The camera moves, and the coarse frame renders at another size:
        // the requests thread waits meanwhile.
        let mut slot = conn.scene.write().unwrap_or_else(|e| e.into_inner());
        slot.settings = None;
        let scene = scene_for(&mut slot.built, source, &settings)?;
        if base.cell.is_none() {
            let t = Instant::now();
            let coarse = render_coarse(scene, &base, &control)?;
            header.render_ms += t.elapsed().as_secs_f64() * 1e3;
            let Some(film) = coarse else {
                return Ok(());
            };
            let mut coarse_header = header.clone();
            (coarse_header.width, coarse_header.height) = (film.width, film.height);
            coarse_header.elapsed_ms = received.elapsed().as_secs_f64() * 1e3;
            (conn.send)(encode(&film, &settings, &coarse_header));
        }
        slot.settings = Some(settings.clone());
    }
    header.coarse = false;
    let slot = conn.read_scene();
    let (scene, _) = slot.built.as_ref().ok_or("the scene is gone")?;
    let region = settings.image.region();
    let coarse_ms = header.render_ms;
    let pacing = Mutex::new(FramePacing::new(Instant::now()));
    // A frame of `film` (the render's sums so far) over the backdrop.
    let frame = |film: Film, done: bool, rendering: std::time::Duration| {
        let film = match &backdrop {
            Some(backdrop) => {
                let mut over = backdrop.clone();
                over.merge(&film).map_err(|e| e.to_string())?;
                over
            }
            None => film,
        };
        let mut header = header.clone();
        header.spp = film.sample_spread(region).max;
        header.done = done;
        header.render_ms = coarse_ms + rendering.as_secs_f64() * 1e3;
        header.elapsed_ms = received.elapsed().as_secs_f64() * 1e3;
        Ok::<_, String>(LastFilm {
            film,
            settings: settings.clone(),
            header,
        })
    };
    // Every sample of the render: its last pass ends with the last frame,
    // not with a refinement frame too.
    let all = region.width as u64 * region.height as u64 * base.samples().len() as u64;
    let after_pass = |end: &PassEnd<'_>| {
        let mut pacing = pacing.lock().unwrap_or_else(|e| e.into_inner());
        let started = Instant::now();
        if cancel.is_cancelled() || end.stats.samples >= all || !pacing.due(started) {
            return;
        }
        let rendering = end.elapsed.saturating_sub(pacing.total_cost());
        match frame(end.film(), false, rendering) {
            Ok(last) => conn.show(last),
            Err(message) => conn.reply(Reply::error(message)),
        }
        pacing.sent(started, Instant::now());
    };
    let from = Continuation {
        start: None,
        after_pass: Some(&after_pass),
    };
    let out = render_from(scene, &base, &control, &from).map_err(|e| e.to_string())?;
    if out.stop == StopReason::Cancelled {
        return Ok(());
    }
    let frames_cost = pacing
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .total_cost();
    let rendering = out.stats.render_time.saturating_sub(frames_cost);
    let last = frame(out.film, true, rendering)?;
    // Before the page can see the last frame and ask for another layer of
    // this film (which goes to the requests thread once this is set).
    let msg = encode(&last.film, &last.settings, &last.header);
    *conn.last.lock().unwrap_or_else(|e| e.into_inner()) = Some(Arc::new(last));
    job.finished.store(true, Ordering::Release);
    (conn.send)(msg);
    Ok(())
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
