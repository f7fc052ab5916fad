//! The requests about the film shown: the path inspector, save, and another
//! layer of a finished render. They run on a connection's second thread,
//! beside the render thread, so they are answered while a render refines
//! (they used to wait until it finished). They read only what the render
//! shares: the film of the last frame sent, and the scene, which a running
//! render only reads too; the render never waits for them except to move
//! the camera of the next render. Rendering is untouched by them, so its
//! film stays the same bit for bit.

use crate::protocol::{Reply, SaveFormat};
use crate::worker::{Connection, Job};
use candela_image::denoise::Oidn;
use candela_render::film::{
    denoise_film, denoised_path, write_denoised, write_film, OutputOptions,
};
use candela_render::integrator::inspect::trace_paths;
use std::sync::atomic::{AtomicU32, Ordering};

/// Saves so far by this process, for distinct file names.
static SAVED: AtomicU32 = AtomicU32::new(0);

/// Answers `job` (anything but a render).
pub(crate) fn answer(conn: &Connection, job: Job) {
    match job {
        Job::Render(_) => conn.reply(Reply::error("a render is not a film request")),
        Job::Layer { id, layer } => match conn.last_film() {
            Some(last) => {
                let mut header = last.header.clone();
                (header.layer, header.job) = (layer, id);
                (conn.send)(crate::frames::encode(&last.film, &last.settings, &header));
            }
            None => conn.reply(Reply::error("no image yet")),
        },
        Job::Inspect { pixel, samples } => {
            let reply = inspect(conn, pixel, samples).unwrap_or_else(Reply::error);
            conn.reply(reply);
        }
        Job::Save(format) => {
            let reply = save(conn, format).unwrap_or_else(Reply::error);
            conn.reply(reply);
        }
    }
}

/// The path inspector: samples `0..samples` of one pixel of the view shown,
/// traced by the renderer's own sample function with a recorder, beside the
/// pixel's mean in the last frame's film when that film is of the same
/// settings (right after a camera move it is still the old view's: then
/// the film's figures are left out, as zero samples).
fn inspect(conn: &Connection, pixel: (u32, u32), samples: u32) -> Result<Reply, String> {
    let slot = conn.read_scene();
    let (Some((scene, _)), Some(settings)) = (&slot.built, &slot.settings) else {
        return Err("no image to inspect yet".into());
    };
    let (w, h) = (settings.image.width, settings.image.height);
    if pixel.0 >= w || pixel.1 >= h {
        return Err(format!(
            "pixel ({}, {}) lies outside the {w}x{h} image",
            pixel.0, pixel.1
        ));
    }
    let (mut film_mean, mut film_samples) = ([0.0; 3], 0);
    if let Some(last) = conn.last_film().filter(|l| &l.settings == settings) {
        let sums = *last.film.pixel(pixel.0, pixel.1);
        if sums.count > 0 {
            film_mean = (sums.radiance / sums.count as f64).to_array();
        }
        film_samples = sums.count;
    }
    let paths = trace_paths(scene, &settings.render_settings(), pixel, 0..samples)
        .map_err(|e| e.to_string())?;
    Ok(Reply::Paths {
        pixel: [pixel.0, pixel.1],
        paths,
        film_mean,
        film_samples,
    })
}

/// Writes the last frame's film as the CLI would: the image with its
/// layers, and with the `denoise` setting the denoised image beside it
/// (`<name>.denoised.<ext>`), refused in one line when Open Image Denoise
/// cannot be loaded.
fn save(conn: &Connection, format: SaveFormat) -> Result<Reply, String> {
    let last = conn.last_film().ok_or("no image to save yet")?;
    let oidn = if last.settings.output.denoise {
        Some(Oidn::load().map_err(|e| format!("--denoise: {e}"))?)
    } else {
        None
    };
    let n = SAVED.fetch_add(1, Ordering::Relaxed) + 1;
    let name = format!("studio-{}-{n}.{}", std::process::id(), format.extension());
    let path = conn.source.out_dir.join(name);
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
        exr_compression: last.settings.output.exr_compression,
    };
    let mut written = write_film(&path, &last.film, &opts).map_err(|e| e.to_string())?;
    if let Some(oidn) = oidn {
        let image = denoise_film(&last.film, oidn).map_err(|e| format!("--denoise: {e}"))?;
        let denoised = denoised_path(&path);
        write_denoised(&denoised, &image, &opts.tone).map_err(|e| e.to_string())?;
        written.push(denoised);
    }
    Ok(Reply::Saved {
        files: written.iter().map(|p| p.display().to_string()).collect(),
    })
}
