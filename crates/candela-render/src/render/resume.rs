//! Continuing a render from a film, and looking at it between passes: what
//! checkpoints need.
//!
//! The state of a render at a pass boundary is its film's sums and nothing
//! else: a pixel's sample count says which of its sample indices are done
//! (the next is `range.start + count`), each pixel adds its samples one by
//! one in index order (so how the samples were cut into passes never
//! changes a bit of the sums), and the adaptive rule's decision is read back
//! from the same sums ([`TileState::from_film`]). A render continued from the
//! film of a stopped one therefore ends bit for bit where the uninterrupted
//! render ends.

use super::tile::TileState;
use super::{RenderError, RenderSettings};
use crate::film::{Film, PixelRect};
use crate::stats::RenderStats;
use std::time::Duration;

/// Where a render starts and who looks at it between passes.
#[derive(Clone, Copy, Default)]
pub struct Continuation<'a> {
    /// The sums to continue from (a checkpoint's film), of the full frame;
    /// `None` starts from an empty film.
    pub start: Option<&'a Film>,
    /// Called after every finished pass (not after a cancelled one), from
    /// the render's calling thread: a checkpoint writer decides there
    /// whether it is time to save [`PassEnd::film`].
    pub after_pass: Option<&'a (dyn Fn(&PassEnd<'_>) + Sync)>,
}

/// A render between two passes.
pub struct PassEnd<'a> {
    pub(super) tiles: &'a [TileState],
    pub(super) size: (u32, u32),
    pub(super) layer_names: &'a [String],
    pub(super) splats: &'a crate::film::SplatLayer,
    /// The statistics so far (of this render, not of the film it continued).
    pub stats: &'a RenderStats,
    /// Wall-clock time since this render started.
    pub elapsed: Duration,
}

impl PassEnd<'_> {
    /// The full-frame film of every finished pass (a copy of the sums).
    pub fn film(&self) -> Film {
        let mut film = super::assemble(
            self.tiles,
            self.size.0,
            self.size.1,
            self.layer_names.to_vec(),
        );
        film.splats = self.splats.clone();
        film
    }
}

impl TileState {
    /// The tile `rect` with the sums of `film` (a full-frame film). A pixel
    /// the adaptive rule stopped is recognised from its sums: it stopped at
    /// the first batch boundary where the rule held, and the rule is checked
    /// on exactly those sums, so `should_stop(count, ...)` is true for it
    /// and false for every pixel still sampling.
    pub(super) fn from_film(
        rect: PixelRect,
        film: &Film,
        settings: &RenderSettings,
        layer_names: &[String],
    ) -> Self {
        let mut tile = TileState::new(rect, layer_names);
        for (i, (x, y)) in rect.pixels().enumerate() {
            let sums = *film.pixel(x, y);
            tile.sums[i] = sums;
            if !tile.layers.is_empty() {
                let pixel = y as usize * film.width as usize + x as usize;
                tile.layers.copy_pixel(i, &film.layers, pixel);
            }
            tile.converged[i] = settings
                .adaptive
                .is_some_and(|a| a.should_stop(sums.count, sums.lum, sums.lum_sq));
        }
        tile
    }
}

/// Checks that `film` can be continued by a render of `settings` on a
/// `width` × `height` frame: the same size, and no pixel past the end of its
/// sample range.
pub(super) fn check_start(
    film: &Film,
    settings: &RenderSettings,
    (width, height): (u32, u32),
) -> Result<(), RenderError> {
    if (film.width, film.height) != (width, height) {
        return Err(RenderError::Settings(format!(
            "cannot continue a {}x{} film in a {width}x{height} render",
            film.width, film.height
        )));
    }
    let len = settings.samples().len() as u64;
    let most = film.pixels.iter().map(|p| p.count).max().unwrap_or(0);
    if most as u64 > len {
        return Err(RenderError::Settings(format!(
            "cannot continue a film whose pixels have up to {most} samples in a render of {len}"
        )));
    }
    Ok(())
}
