//! Image textures: an RGB image looked up at surface `(u, v)` coordinates.
//!
//! Conventions (OpenGL's and COLLADA's): `u` runs left to right across the
//! image, `v` **bottom to top** (row 0 of the file, its top, is `v = 1`).
//! Texel `(i, j)` covers `[i, i+1)/W × [j, j+1)/H` with its value at the
//! centre; lookups are bilinear between the four nearest centres, and
//! addressing wraps around (the image tiles the plane), so `u = 1.25` reads
//! what `u = 0.25` reads.
//!
//! Images are read once per path and colour space ([`TextureCache`])
//! through candela-image, whose readers decode PNG from sRGB and take EXR as
//! linear; a description that declares another [`ColorSpace`] for a file
//! (linear data in a PNG) has that undone. Texels are linear RGB.

mod cache;

pub use cache::TextureCache;

use candela_image::{read_exr, read_png, srgb_decode, srgb_encode, ImageError, RgbImage};
use candela_scene::ColorSpace;
use glam::{Vec2, Vec3};
use std::path::{Path, PathBuf};

/// Why an image could not be used as a texture or environment map.
#[derive(Debug, thiserror::Error)]
pub enum TextureError {
    /// The file could not be read or decoded.
    #[error(transparent)]
    Image(#[from] ImageError),
    /// The file's extension is neither `.png` nor `.exr`.
    #[error("{0}: unknown image format (expected .png or .exr)")]
    UnknownFormat(PathBuf),
    /// The image has no pixels.
    #[error("the image is empty (0 pixels)")]
    Empty,
}

/// Reads a PNG (sRGB-decoded) or EXR (linear) file as linear RGB, by its
/// extension.
pub fn read_linear_image(path: &Path) -> Result<RgbImage, TextureError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("png") => Ok(read_png(path)?),
        Some("exr") => Ok(read_exr(path)?),
        _ => Err(TextureError::UnknownFormat(path.to_path_buf())),
    }
}

/// The colour space candela-image's reader assumes for `path`'s format:
/// sRGB for PNG, linear otherwise (EXR).
pub fn native_color_space(path: &Path) -> ColorSpace {
    let png = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if png {
        ColorSpace::Srgb
    } else {
        ColorSpace::Linear
    }
}

/// A linear RGB image with bilinear, wrapping lookups.
#[derive(Clone, PartialEq)]
pub struct ImageTexture {
    width: usize,
    height: usize,
    /// Row-major, row 0 at the top of the image (`v = 1`).
    texels: Vec<Vec3>,
}

impl std::fmt::Debug for ImageTexture {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // The texels would flood any debug print of a material.
        write!(f, "ImageTexture({}x{})", self.width, self.height)
    }
}

impl ImageTexture {
    /// A texture of `image`'s pixels; non-finite values become 0.
    pub fn from_image(image: &RgbImage) -> Result<Self, TextureError> {
        let (width, height) = image.size();
        if width == 0 || height == 0 {
            return Err(TextureError::Empty);
        }
        let texels = image
            .pixels()
            .iter()
            .map(|p| Vec3::from_array(p.map(|c| if c.is_finite() { c } else { 0.0 })))
            .collect();
        Ok(Self {
            width,
            height,
            texels,
        })
    }

    /// Reads a PNG or EXR file (see [`read_linear_image`]).
    pub fn load(path: &Path) -> Result<Self, TextureError> {
        Self::from_image(&read_linear_image(path)?)
    }

    /// Reads a PNG or EXR file whose stored values are in `color_space`.
    pub fn load_in(path: &Path, color_space: ColorSpace) -> Result<Self, TextureError> {
        let mut texture = Self::load(path)?;
        let convert: Option<fn(f32) -> f32> = match (native_color_space(path), color_space) {
            // The reader decoded sRGB that was really linear data: undo it.
            (ColorSpace::Srgb, ColorSpace::Linear) => Some(srgb_encode),
            // The reader took as linear what is sRGB-encoded.
            (ColorSpace::Linear, ColorSpace::Srgb) => Some(srgb_decode),
            _ => None,
        };
        if let Some(f) = convert {
            for t in &mut texture.texels {
                *t = Vec3::new(f(t.x), f(t.y), f(t.z));
            }
        }
        Ok(texture)
    }

    /// Width and height in texels.
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// Texel at column `i`, row `j` counted from the **bottom**, wrapped
    /// into the image.
    pub fn texel(&self, i: i64, j: i64) -> Vec3 {
        let i = i.rem_euclid(self.width as i64) as usize;
        let j = j.rem_euclid(self.height as i64) as usize;
        self.texels[(self.height - 1 - j) * self.width + i]
    }

    /// Bilinear value at `uv`, wrapping around.
    pub fn lookup(&self, uv: Vec2) -> Vec3 {
        if !uv.is_finite() {
            return self.texel(0, 0);
        }
        // Continuous texel coordinates whose integers are texel centres.
        let x = f64::from(uv.x) * self.width as f64 - 0.5;
        let y = f64::from(uv.y) * self.height as f64 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = ((x - x0) as f32, (y - y0) as f32);
        let (i, j) = (x0 as i64, y0 as i64);
        let bottom = self.texel(i, j).lerp(self.texel(i + 1, j), fx);
        let top = self.texel(i, j + 1).lerp(self.texel(i + 1, j + 1), fx);
        bottom.lerp(top, fy)
    }

    /// Mean of the texels: the texture's average over one period.
    pub fn mean(&self) -> Vec3 {
        let sum: glam::DVec3 = self.texels.iter().map(|t| t.as_dvec3()).sum();
        (sum / self.texels.len() as f64).as_vec3()
    }
}

#[cfg(test)]
mod tests;
