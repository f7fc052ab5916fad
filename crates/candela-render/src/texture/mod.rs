//! Image textures: an RGB image looked up at surface `(u, v)` coordinates.
//!
//! Conventions (OpenGL's and COLLADA's): `u` runs left to right across the
//! image, `v` **bottom to top** (row 0 of the file, its top, is `v = 1`).
//! Texel `(i, j)` covers `[i, i+1)/W × [j, j+1)/H` with its value at the
//! centre; lookups are bilinear between the four nearest centres (or the
//! covering texel's, [`ImageTexture::nearest`]). Texel indices beyond the
//! image are folded back per axis by the texture's [`TextureWrap`]
//! (repeat: `u = 1.25` reads what `u = 0.25` reads; mirror; clamp), each
//! of a bilinear lookup's four texels on its own.
//!
//! Images are read once per path and colour space ([`TextureCache`]).
//! Texels of the 8-bit formats (PNG, JPEG, TGA, BMP, WebP) are taken from the
//! file's stored values: decoded from sRGB when the description says
//! [`ColorSpace::Srgb`] (colour, emission), and exactly `v / 255` when it
//! says [`ColorSpace::Linear`] (roughness, metalness, normal maps,
//! opacity), so data maps are not bent by a transfer curve and back. EXR
//! and Radiance HDR hold linear values; one declared sRGB is decoded. Alpha, when the file has it, is kept beside the colour (always
//! linear: it is coverage, not colour), for opacity slots. Texels are
//! linear RGB.

mod cache;
mod point;
mod slot;

pub use cache::TextureCache;
pub use point::TexturePoint;
pub use slot::{SlotSource, SlotTexture};

use candela_image::{
    read_exr, read_pfm, read_png_stored, read_radiance_hdr, read_stored, srgb_decode, ImageError,
    RgbImage, StoredImage, STORED_EXTENSIONS,
};
use candela_scene::{ColorSpace, TextureWrap};
use glam::{Vec2, Vec3};
use std::path::{Path, PathBuf};

/// Why an image could not be used as a texture or environment map.
#[derive(Debug, thiserror::Error)]
pub enum TextureError {
    /// The file could not be read or decoded.
    #[error(transparent)]
    Image(#[from] ImageError),
    /// The file's extension is not one of the formats read.
    #[error(
        "{0}: unknown image format (expected .png, .jpg, .tga, .bmp, .webp, .exr, .hdr or .pfm)"
    )]
    UnknownFormat(PathBuf),
    /// The image has no pixels.
    #[error("the image is empty (0 pixels)")]
    Empty,
}

/// `path`'s extension, lower case.
fn extension(path: &Path) -> Option<String> {
    path.extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
}

/// Whether `path` is an 8-bit format read as stored values (PNG, JPEG,
/// TGA, BMP, WebP), sRGB-encoded unless a scene says the data is linear.
fn is_stored_format(path: &Path) -> bool {
    extension(path).is_some_and(|e| e == "png" || STORED_EXTENSIONS.contains(&e.as_str()))
}

/// An 8-bit file's stored values (see [`is_stored_format`]).
fn read_stored_values(path: &Path) -> Result<StoredImage, TextureError> {
    Ok(match extension(path).as_deref() {
        Some("png") => read_png_stored(path)?,
        _ => read_stored(path)?,
    })
}

/// Reads an image file as linear RGB, by its extension: an 8-bit format
/// sRGB-decoded, EXR and Radiance HDR as they are.
pub fn read_linear_image(path: &Path) -> Result<RgbImage, TextureError> {
    match extension(path).as_deref() {
        Some("exr") => Ok(read_exr(path)?),
        Some("hdr") => Ok(read_radiance_hdr(path)?),
        Some("pfm") => Ok(read_pfm(path)?),
        _ if is_stored_format(path) => Ok(read_stored_values(path)?.srgb_decoded()?),
        _ => Err(TextureError::UnknownFormat(path.to_path_buf())),
    }
}

/// The colour space candela-image's reader assumes for `path`'s format:
/// sRGB for the 8-bit formats, linear otherwise (EXR, HDR).
pub fn native_color_space(path: &Path) -> ColorSpace {
    if is_stored_format(path) {
        ColorSpace::Srgb
    } else {
        ColorSpace::Linear
    }
}

/// A linear RGB image with bilinear or nearest lookups, wrapped as each
/// lookup's [`TextureWrap`] says.
#[derive(Clone, PartialEq)]
pub struct ImageTexture {
    width: usize,
    height: usize,
    /// Row-major, row 0 at the top of the image (`v = 1`).
    texels: Vec<Vec3>,
    /// The alpha channel, laid out as `texels`, when the file has one.
    alpha: Option<Vec<f32>>,
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
            alpha: None,
        })
    }

    /// Reads an image file (see [`read_linear_image`]).
    pub fn load(path: &Path) -> Result<Self, TextureError> {
        Self::from_image(&read_linear_image(path)?)
    }

    /// Reads an image file whose stored values are in `color_space` (see
    /// the module docs); an 8-bit file's alpha channel is kept.
    pub fn load_in(path: &Path, color_space: ColorSpace) -> Result<Self, TextureError> {
        if is_stored_format(path) {
            return Self::load_stored(path, color_space);
        }
        let mut texture = Self::load(path)?;
        if color_space == ColorSpace::Srgb {
            // The reader took as linear what is sRGB-encoded.
            for t in &mut texture.texels {
                *t = t.to_array().map(srgb_decode).into();
            }
        }
        Ok(texture)
    }

    /// An 8-bit file from its stored values, decoded from sRGB or not.
    fn load_stored(path: &Path, color_space: ColorSpace) -> Result<Self, TextureError> {
        let stored = read_stored_values(path)?;
        if stored.width == 0 || stored.height == 0 {
            return Err(TextureError::Empty);
        }
        let decode = |v: f32| match color_space {
            ColorSpace::Srgb => srgb_decode(v),
            ColorSpace::Linear => v,
        };
        let texels = stored
            .pixels
            .iter()
            .map(|p| Vec3::new(decode(p[0]), decode(p[1]), decode(p[2])))
            .collect();
        let alpha = stored
            .has_alpha
            .then(|| stored.pixels.iter().map(|p| p[3]).collect());
        Ok(Self {
            width: stored.width,
            height: stored.height,
            texels,
            alpha,
        })
    }

    /// Whether the image has an alpha channel.
    pub fn has_alpha(&self) -> bool {
        self.alpha.is_some()
    }

    /// Width and height in texels.
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// Texel at column `i`, row `j` counted from the **bottom**, repeated
    /// into the image.
    pub fn texel(&self, i: i64, j: i64) -> Vec3 {
        self.texels[self.texel_index(i, j, TextureWrap::REPEAT)]
    }

    /// Bilinear value at `uv`, wrapped as `wrap` says.
    pub fn lookup(&self, uv: Vec2, wrap: TextureWrap) -> Vec3 {
        self.bilinear(uv, |i, j| self.texels[self.texel_index(i, j, wrap)])
    }

    /// Bilinear value of channel `c` (0 R, 1 G, 2 B, 3 alpha; 1 when the
    /// image has no alpha) at `uv`, wrapped as `wrap` says.
    pub fn lookup_channel(&self, uv: Vec2, c: u8, wrap: TextureWrap) -> f32 {
        match (c, &self.alpha) {
            (0..=2, _) => {
                self.bilinear(uv, |i, j| {
                    Vec3::splat(self.texels[self.texel_index(i, j, wrap)][c as usize])
                })
                .x
            }
            (_, Some(alpha)) => {
                self.bilinear(uv, |i, j| Vec3::splat(alpha[self.texel_index(i, j, wrap)]))
                    .x
            }
            (_, None) => 1.0,
        }
    }

    /// The texel that covers `uv` (nearest-neighbour), wrapped as `wrap`
    /// says.
    pub fn nearest(&self, uv: Vec2, wrap: TextureWrap) -> Vec3 {
        let (i, j) = self.covering_texel(uv);
        self.texels[self.texel_index(i, j, wrap)]
    }

    /// Channel `c` of [`ImageTexture::nearest`] (3: alpha, 1 when the
    /// image has none).
    pub fn nearest_channel(&self, uv: Vec2, c: u8, wrap: TextureWrap) -> f32 {
        let (i, j) = self.covering_texel(uv);
        let k = self.texel_index(i, j, wrap);
        match (c, &self.alpha) {
            (0..=2, _) => self.texels[k][c as usize],
            (_, Some(alpha)) => alpha[k],
            (_, None) => 1.0,
        }
    }

    /// Column and row (from the bottom) of the texel whose square holds
    /// `uv`, before wrapping; texel (0, 0) for a non-finite `uv`.
    fn covering_texel(&self, uv: Vec2) -> (i64, i64) {
        if !uv.is_finite() {
            return (0, 0);
        }
        let x = (f64::from(uv.x) * self.width as f64).floor();
        let y = (f64::from(uv.y) * self.height as f64).floor();
        (x as i64, y as i64)
    }

    /// The gradient (∂/∂u, ∂/∂v) of [`ImageTexture::lookup_channel`] at
    /// `uv`: the exact derivative of the bilinear interpolant of the
    /// wrapped texels (constant in u along a row of cells, so it jumps at
    /// texel centres; 0 where clamping repeats one texel), as a bump map's
    /// slope. Zero for an alpha channel the image lacks.
    pub fn gradient_channel(&self, uv: Vec2, c: u8, wrap: TextureWrap) -> Vec2 {
        match (c, &self.alpha) {
            (0..=2, _) => self.bilinear_gradient(uv, |i, j| {
                self.texels[self.texel_index(i, j, wrap)][c as usize]
            }),
            (_, Some(alpha)) => {
                self.bilinear_gradient(uv, |i, j| alpha[self.texel_index(i, j, wrap)])
            }
            (_, None) => Vec2::ZERO,
        }
    }

    /// ∂/∂u and ∂/∂v of the bilinear interpolation of `texel` at `uv`.
    fn bilinear_gradient(&self, uv: Vec2, texel: impl Fn(i64, i64) -> f32) -> Vec2 {
        if !uv.is_finite() {
            return Vec2::ZERO;
        }
        let (w, h) = (self.width as f64, self.height as f64);
        let x = f64::from(uv.x) * w - 0.5;
        let y = f64::from(uv.y) * h - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = ((x - x0) as f32, (y - y0) as f32);
        let (i, j) = (x0 as i64, y0 as i64);
        let (t00, t10) = (texel(i, j), texel(i + 1, j));
        let (t01, t11) = (texel(i, j + 1), texel(i + 1, j + 1));
        // d/dx of the interpolant, then dx/du = width (likewise for v).
        let d_dx = (1.0 - fy) * (t10 - t00) + fy * (t11 - t01);
        let d_dy = (1.0 - fx) * (t01 - t00) + fx * (t11 - t10);
        Vec2::new(d_dx * w as f32, d_dy * h as f32)
    }

    /// Row-major index of texel `(i, j)` (`j` from the bottom), wrapped as
    /// `wrap` says. Rows fold alike counted from the top or the bottom
    /// (every mode is symmetric under j ↦ n − 1 − j), so a loader whose v
    /// runs down the image needs no conversion of its wrap mode.
    #[inline]
    fn texel_index(&self, i: i64, j: i64, wrap: TextureWrap) -> usize {
        let i = wrap.u.texel_index(i, self.width as i64) as usize;
        let j = wrap.v.texel_index(j, self.height as i64) as usize;
        (self.height - 1 - j) * self.width + i
    }

    /// Bilinear interpolation of `texel` between the four centres nearest `uv`.
    fn bilinear(&self, uv: Vec2, texel: impl Fn(i64, i64) -> Vec3) -> Vec3 {
        if !uv.is_finite() {
            return texel(0, 0);
        }
        // Continuous texel coordinates whose integers are texel centres.
        let x = f64::from(uv.x) * self.width as f64 - 0.5;
        let y = f64::from(uv.y) * self.height as f64 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = ((x - x0) as f32, (y - y0) as f32);
        let (i, j) = (x0 as i64, y0 as i64);
        let bottom = texel(i, j).lerp(texel(i + 1, j), fx);
        let top = texel(i, j + 1).lerp(texel(i + 1, j + 1), fx);
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
