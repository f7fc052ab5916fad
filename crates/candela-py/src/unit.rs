//! One render of a pixel rectangle × sample range, as a placed film.
//!
//! The library renders a full-frame film with samples only in
//! `RenderSettings::cell`; a part that travels between processes needs only
//! that rectangle, so it is cropped here (at 144 bytes a pixel, cropping is
//! what keeps a work unit's result small).

use crate::stats::StatsRecord;
use crate::wire::PlacedFilm;
use candela_render::film::{Film, PixelRect};
use candela_render::render::{
    render_with, Cancel, RenderControl, RenderError, RenderSettings, StopReason,
};
use candela_render::scene::Scene;

/// Renders `settings` (whose `cell` must be set) and crops the film to the
/// cell. Returns `None` if `cancel` stopped it.
pub fn render_cell(
    scene: &Scene,
    settings: &RenderSettings,
    cancel: &Cancel,
) -> Result<Option<PlacedFilm>, RenderError> {
    let (w, h) = (scene.camera.width, scene.camera.height);
    let cell = settings.cell.unwrap_or(PixelRect::full(w, h));
    let control = RenderControl {
        cancel: Some(cancel.clone()),
        progress: None,
    };
    let out = render_with(scene, settings, &control)?;
    if out.stop == StopReason::Cancelled {
        return Ok(None);
    }
    if !out.film.splats.is_empty() {
        // Light subpaths splat over the whole frame, which a cropped cell
        // and the wire format (`wire.rs`) do not carry yet.
        return Err(RenderError::Settings(
            "light tracing and BDPT cannot be rendered in distributed cells yet".into(),
        ));
    }
    Ok(Some(PlacedFilm {
        film: crop(&out.film, cell),
        origin: (cell.x, cell.y),
        full: (w, h),
        stats: StatsRecord::from(&out.stats),
    }))
}

/// The pixels of `rect` (which lies inside `film`) as a film of their own.
pub fn crop(film: &Film, rect: PixelRect) -> Film {
    let mut out = Film::new(rect.width, rect.height);
    for (dst, (x, y)) in out.pixels.iter_mut().zip(rect.pixels()) {
        *dst = *film.pixel(x, y);
    }
    out
}
