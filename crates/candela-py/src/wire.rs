//! A film's raw sums as bytes, so Dask (or any pickle user) can move them.
//!
//! Layout, little-endian: magic `CNDLFLM3`; u32 width, height, origin x,
//! origin y, full width, full height; 10 u64 statistics counters; f64 render
//! and wall time; then per pixel, row-major, the sums of `PixelSums` in
//! declaration order -- radiance (3), radiance squared (3), luminance,
//! luminance squared, albedo (3), normal (3), depth as f64; the depth
//! count and the sample count as u32; nodes visited and primitive tests as
//! u64. 144 bytes per pixel: a 64×64 cell is 576 KiB. Floats travel as
//! their bits, so a film survives the trip exactly.

use crate::stats::StatsRecord;
use candela_render::film::wire::{decode_film, encode_pixels, ByteReader, PIXEL_BYTES};
use candela_render::film::Film;

const MAGIC: &[u8; 8] = b"CNDLFLM3";
const HEADER: usize = 8 + 6 * 4 + 10 * 8 + 2 * 8;

/// A film with where it sits in the full image and what it cost.
#[derive(Clone, Debug, PartialEq)]
pub struct PlacedFilm {
    /// The sums of the covered rectangle.
    pub film: Film,
    /// Top-left pixel of `film` in the full image.
    pub origin: (u32, u32),
    /// Size of the full image.
    pub full: (u32, u32),
    /// Render statistics.
    pub stats: StatsRecord,
}

/// Why bytes are not a film.
#[derive(Debug, thiserror::Error)]
pub enum WireError {
    /// Wrong magic number or truncated header.
    #[error("not a candela film (bad header)")]
    Header,
    /// The pixel data does not match the header's size.
    #[error("film data has {got} bytes, the header announces {want}")]
    Length {
        /// Bytes present.
        got: usize,
        /// Bytes the size calls for.
        want: usize,
    },
    /// The rectangle does not fit in the full image.
    #[error("film rectangle lies outside its image")]
    Placement,
}

/// Encodes `f` (see the module docs for the layout).
pub fn encode(f: &PlacedFilm) -> Vec<u8> {
    let mut out = Vec::with_capacity(HEADER + f.film.pixels.len() * PIXEL_BYTES);
    out.extend_from_slice(MAGIC);
    for v in [
        f.film.width,
        f.film.height,
        f.origin.0,
        f.origin.1,
        f.full.0,
        f.full.1,
    ] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    for v in f.stats.counters() {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out.extend_from_slice(&f.stats.render_time_s.to_le_bytes());
    out.extend_from_slice(&f.stats.wall_time_s.to_le_bytes());
    encode_pixels(&f.film.pixels, &mut out);
    out
}

/// Decodes bytes written by [`encode`].
pub fn decode(bytes: &[u8]) -> Result<PlacedFilm, WireError> {
    if bytes.len() < HEADER || &bytes[..8] != MAGIC {
        return Err(WireError::Header);
    }
    let mut r = ByteReader::new(&bytes[8..]);
    let mut u32 = || r.u32().ok_or(WireError::Header);
    let (w, h, ox, oy, fw, fh) = (u32()?, u32()?, u32()?, u32()?, u32()?, u32()?);
    let fits = |o: u32, n: u32, full: u32| o.checked_add(n).is_some_and(|end| end <= full);
    if !fits(ox, w, fw) || !fits(oy, h, fh) {
        return Err(WireError::Placement);
    }
    let mut counters = [0u64; 10];
    for c in counters.iter_mut() {
        *c = r.u64().ok_or(WireError::Header)?;
    }
    let times = (r.f64(), r.f64());
    let (Some(render_time), Some(wall_time)) = times else {
        return Err(WireError::Header);
    };
    let stats = StatsRecord::from_parts(counters, render_time, wall_time);
    let want = w as usize * h as usize * PIXEL_BYTES;
    if r.remaining() != want {
        return Err(WireError::Length {
            got: r.remaining(),
            want,
        });
    }
    let film: Film = decode_film(&mut r, w, h).ok_or(WireError::Length {
        got: bytes.len() - HEADER,
        want,
    })?;
    Ok(PlacedFilm {
        film,
        origin: (ox, oy),
        full: (fw, fh),
        stats,
    })
}
