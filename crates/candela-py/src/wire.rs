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
use candela_render::film::{Film, PixelSums};
use glam::DVec3;

const MAGIC: &[u8; 8] = b"CNDLFLM3";
const HEADER: usize = 8 + 6 * 4 + 10 * 8 + 2 * 8;
/// Bytes per pixel in the wire format.
pub const PIXEL_BYTES: usize = 15 * 8 + 2 * 4 + 2 * 8;

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
    for p in &f.film.pixels {
        let (r, q, a, n) = (p.radiance, p.radiance_sq, p.albedo, p.normal);
        let sums = [
            r.x, r.y, r.z, q.x, q.y, q.z, p.lum, p.lum_sq, a.x, a.y, a.z, n.x, n.y, n.z, p.depth,
        ];
        for v in sums {
            out.extend_from_slice(&v.to_le_bytes());
        }
        out.extend_from_slice(&p.depth_count.to_le_bytes());
        out.extend_from_slice(&p.count.to_le_bytes());
        out.extend_from_slice(&p.nodes.to_le_bytes());
        out.extend_from_slice(&p.prim_tests.to_le_bytes());
    }
    out
}

struct Reader<'a> {
    bytes: &'a [u8],
}

impl Reader<'_> {
    fn take<const N: usize>(&mut self) -> [u8; N] {
        let (head, rest) = self.bytes.split_at(N);
        self.bytes = rest;
        let mut a = [0; N];
        a.copy_from_slice(head);
        a
    }
    fn u32(&mut self) -> u32 {
        u32::from_le_bytes(self.take())
    }
    fn u64(&mut self) -> u64 {
        u64::from_le_bytes(self.take())
    }
    fn f64(&mut self) -> f64 {
        f64::from_le_bytes(self.take())
    }
}

/// Decodes bytes written by [`encode`].
pub fn decode(bytes: &[u8]) -> Result<PlacedFilm, WireError> {
    if bytes.len() < HEADER || &bytes[..8] != MAGIC {
        return Err(WireError::Header);
    }
    let mut r = Reader { bytes: &bytes[8..] };
    let (w, h, ox, oy, fw, fh) = (r.u32(), r.u32(), r.u32(), r.u32(), r.u32(), r.u32());
    let fits = |o: u32, n: u32, full: u32| o.checked_add(n).is_some_and(|end| end <= full);
    if !fits(ox, w, fw) || !fits(oy, h, fh) {
        return Err(WireError::Placement);
    }
    let counters = std::array::from_fn(|_| r.u64());
    let stats = StatsRecord::from_parts(counters, r.f64(), r.f64());
    let n = w as usize * h as usize;
    let want = n * PIXEL_BYTES;
    if r.bytes.len() != want {
        return Err(WireError::Length {
            got: r.bytes.len(),
            want,
        });
    }
    let mut film = Film::new(w, h);
    for p in film.pixels.iter_mut() {
        *p = PixelSums {
            radiance: DVec3::new(r.f64(), r.f64(), r.f64()),
            radiance_sq: DVec3::new(r.f64(), r.f64(), r.f64()),
            lum: r.f64(),
            lum_sq: r.f64(),
            albedo: DVec3::new(r.f64(), r.f64(), r.f64()),
            normal: DVec3::new(r.f64(), r.f64(), r.f64()),
            depth: r.f64(),
            depth_count: r.u32(),
            count: r.u32(),
            nodes: r.u64(),
            prim_tests: r.u64(),
        };
    }
    Ok(PlacedFilm {
        film,
        origin: (ox, oy),
        full: (fw, fh),
        stats,
    })
}
