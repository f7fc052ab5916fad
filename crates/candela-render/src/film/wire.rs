//! A film's per-pixel sums as bytes: the one encoding of the film that
//! checkpoints ([`crate::checkpoint`]) and the Python package's film wire
//! format (`CNDLFLM3`, which Dask moves between processes) share.
//!
//! Per pixel, row-major, little-endian, the sums of [`PixelSums`] in
//! declaration order: radiance (3 f64), radiance squared (3), luminance,
//! luminance squared, albedo (3), normal (3), depth as f64; the depth count
//! and the sample count as u32; nodes visited and primitive tests as u64:
//! [`PIXEL_BYTES`] bytes a pixel. Floats travel as their bits, so a film
//! survives the trip exactly.

use super::{Film, PixelSums};
use glam::DVec3;

/// Bytes per pixel.
pub const PIXEL_BYTES: usize = 15 * 8 + 2 * 4 + 2 * 8;

/// Appends the sums of `pixels` to `out`.
pub fn encode_pixels(pixels: &[PixelSums], out: &mut Vec<u8>) {
    out.reserve(pixels.len() * PIXEL_BYTES);
    for p in pixels {
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
}

/// Reads a `width` × `height` film written by [`encode_pixels`] from
/// `bytes`; `None` if they are too few.
pub fn decode_film(bytes: &mut ByteReader<'_>, width: u32, height: u32) -> Option<Film> {
    let n = (width as usize).checked_mul(height as usize)?;
    if bytes.remaining() < n.checked_mul(PIXEL_BYTES)? {
        return None;
    }
    let mut film = Film::new(width, height);
    for p in film.pixels.iter_mut() {
        *p = PixelSums {
            radiance: bytes.dvec3()?,
            radiance_sq: bytes.dvec3()?,
            lum: bytes.f64()?,
            lum_sq: bytes.f64()?,
            albedo: bytes.dvec3()?,
            normal: bytes.dvec3()?,
            depth: bytes.f64()?,
            depth_count: bytes.u32()?,
            count: bytes.u32()?,
            nodes: bytes.u64()?,
            prim_tests: bytes.u64()?,
        };
    }
    Some(film)
}

/// Little-endian reads from a byte slice that never panic: a read past the
/// end is `None`.
pub struct ByteReader<'a> {
    bytes: &'a [u8],
}

impl<'a> ByteReader<'a> {
    /// Reads from the start of `bytes`.
    pub fn new(bytes: &'a [u8]) -> Self {
        Self { bytes }
    }

    /// Bytes not read yet.
    pub fn remaining(&self) -> usize {
        self.bytes.len()
    }

    /// The next `n` bytes.
    pub fn take(&mut self, n: usize) -> Option<&'a [u8]> {
        if n > self.bytes.len() {
            return None;
        }
        let (head, rest) = self.bytes.split_at(n);
        self.bytes = rest;
        Some(head)
    }

    fn array<const N: usize>(&mut self) -> Option<[u8; N]> {
        self.take(N)?.try_into().ok()
    }

    /// A little-endian u32.
    pub fn u32(&mut self) -> Option<u32> {
        self.array().map(u32::from_le_bytes)
    }

    /// A little-endian u64.
    pub fn u64(&mut self) -> Option<u64> {
        self.array().map(u64::from_le_bytes)
    }

    /// A little-endian f64.
    pub fn f64(&mut self) -> Option<f64> {
        self.array().map(f64::from_le_bytes)
    }

    fn dvec3(&mut self) -> Option<DVec3> {
        Some(DVec3::new(self.f64()?, self.f64()?, self.f64()?))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::SampleValue;
    use glam::Vec3;

    #[test]
    fn sums_survive_the_trip_exactly() {
        let mut film = Film::new(3, 2);
        for (i, p) in film.pixels.iter_mut().enumerate() {
            for k in 0..=i {
                p.add(&SampleValue {
                    radiance: Vec3::new(0.1 * k as f32, 1.0 / 3.0, f32::MAX),
                    albedo: Vec3::splat(0.7),
                    normal: Vec3::Z,
                    depth: if k % 2 == 0 { 1.5 } else { f32::INFINITY },
                    ..Default::default()
                });
            }
            p.nodes = u64::MAX - i as u64;
        }
        let mut bytes = Vec::new();
        encode_pixels(&film.pixels, &mut bytes);
        assert_eq!(bytes.len(), 6 * PIXEL_BYTES);
        let back = decode_film(&mut ByteReader::new(&bytes), 3, 2).expect("decodes");
        assert_eq!(back, film);
        // One byte short is refused, not a panic.
        let short = &bytes[..bytes.len() - 1];
        assert!(decode_film(&mut ByteReader::new(short), 3, 2).is_none());
        assert!(decode_film(&mut ByteReader::new(&bytes), u32::MAX, u32::MAX).is_none());
    }
}
