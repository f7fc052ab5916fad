//! Textures as the description names them: what is read (an image file or
//! a procedural pattern), how its values become linear ones, how it is
//! filtered, and the affine map applied to the surface's uv before the
//! lookup. Every texture slot of a material holds one [`TextureRef`], so a
//! slot (colour, roughness, normal or bump map, emission, opacity) gets
//! every kind of texture and the uv transform through the same type.
//!
//! UV convention (every loader converts to it): `u` runs left to right
//! across an image, `v` bottom to top (an image's top row is at `v = 1`).
//! Outside [0, 1) an image repeats, mirrors or clamps per axis
//! ([`TextureWrap`]); procedural patterns tile the plane with period 1.
//!
//! Vertex colours: [`TextureSource::VertexColor`] reads the mesh's
//! per-vertex colour ([`crate::MeshDesc::colors`]) interpolated at the hit,
//! in any slot; [`TextureRef::times_vertex_color`] multiplies any other
//! texture by it (glTF's `COLOR_0`, which multiplies the base colour
//! texture). Where a mesh has no colours the vertex colour is white, so
//! either leaves such a mesh as it would be without it.

use glam::{Affine2, Mat2, Vec2, Vec3};
use std::path::{Path, PathBuf};

/// How a texture's stored values map to linear values.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ColorSpace {
    /// The sRGB transfer curve (8-bit colour images): decoded to linear.
    #[default]
    Srgb,
    /// Stored values are linear already (data maps: roughness, normals, and
    /// every floating-point image).
    Linear,
}

impl ColorSpace {
    /// The convention of an image file's format, for files that name no
    /// colour space: floating-point formats (`.exr`, `.hdr`, `.pfm`) hold
    /// linear values, 8-bit ones (PNG, JPEG, ...) sRGB.
    pub fn of_image_file(path: &Path) -> ColorSpace {
        let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
        if ["exr", "hdr", "pfm"]
            .iter()
            .any(|f| ext.eq_ignore_ascii_case(f))
        {
            ColorSpace::Linear
        } else {
            ColorSpace::Srgb
        }
    }
}

/// What a texture reads: an image, or a pattern computed from uv.
#[derive(Clone, Debug, PartialEq)]
pub enum TextureSource {
    /// An image file, resolved relative to the scene file.
    Image(PathBuf),
    /// Two linear colours in a checkerboard of period 1 in u and v:
    /// `color0` where ⌊2u⌋ + ⌊2v⌋ is even (the cell `[0, ½)²` and every
    /// second cell from it), `color1` elsewhere. Not filtered: its edges
    /// are sharp at any distance, as Mitsuba's `checkerboard` is.
    Checkerboard {
        /// The colour of the cell `[0, ½)²`.
        color0: Vec3,
        /// The colour of its neighbours.
        color1: Vec3,
    },
    /// The mesh's vertex colours, interpolated barycentrically at the hit
    /// (linear; white on meshes without colours and on spheres). Ignores
    /// the uv transform and the filter.
    VertexColor,
}

impl TextureSource {
    /// Whether `uv` lies in one of the checkerboard's `color0` cells (see
    /// [`TextureSource::Checkerboard`]).
    pub fn checker_cell_is_even(uv: Vec2) -> bool {
        let cell = (2.0 * uv).floor();
        // f64 so huge coordinates do not lose the parity in rounding.
        (f64::from(cell.x) + f64::from(cell.y)).rem_euclid(2.0) == 0.0
    }
}

/// How an image is read between texel centres.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum TextureFilter {
    /// Bilinear between the four nearest texel centres.
    #[default]
    Bilinear,
    /// The texel that covers the point (Mitsuba's `filter_type` `nearest`):
    /// piecewise constant, so a bump map of it has slope 0.
    Nearest,
}

/// How an image is addressed beyond its edge along one axis (Mitsuba's
/// `wrap_mode`, glTF's `wrapS`/`wrapT`). Applied to whole texel indices,
/// after the uv transform: each of a bilinear lookup's four texels is
/// wrapped on its own, as Mitsuba's and glTF's samplers do.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum WrapMode {
    /// The image tiles the axis with period 1.
    #[default]
    Repeat,
    /// Every second tile is the image mirrored: period 2, texel `-1` reads
    /// texel `0`, texel `n` reads `n - 1`.
    Mirror,
    /// The edge texels extend outward.
    Clamp,
}

impl WrapMode {
    /// The texel, in `0..n`, that index `i` of an axis of `n` texels reads.
    #[inline]
    pub fn texel_index(self, i: i64, n: i64) -> i64 {
        match self {
            WrapMode::Repeat => i.rem_euclid(n),
            WrapMode::Mirror => {
                let k = i.rem_euclid(2 * n);
                if k < n {
                    k
                } else {
                    2 * n - 1 - k
                }
            }
            WrapMode::Clamp => i.clamp(0, n - 1),
        }
    }
}

/// An image's [`WrapMode`] along u and along v (glTF names one per axis;
/// Mitsuba one for both).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct TextureWrap {
    /// Along u (image columns).
    pub u: WrapMode,
    /// Along v (image rows).
    pub v: WrapMode,
}

impl TextureWrap {
    /// Repeat along both axes: the image tiles the plane.
    pub const REPEAT: Self = Self::both(WrapMode::Repeat);

    /// `mode` along both axes.
    pub const fn both(mode: WrapMode) -> Self {
        Self { u: mode, v: mode }
    }
}

/// An affine map from the surface's uv to the texture's: the texture is
/// read at `matrix · uv` (glTF's `KHR_texture_transform`, Mitsuba's
/// `to_uv`). The identity reads at the surface's own uv.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvTransform(pub Affine2);

impl Default for UvTransform {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl UvTransform {
    /// Reads at the surface's own uv.
    pub const IDENTITY: Self = Self(Affine2::IDENTITY);

    /// The texture coordinates of surface coordinates `uv`.
    #[inline]
    pub fn apply(&self, uv: Vec2) -> Vec2 {
        self.0.transform_point2(uv)
    }

    /// Whether the map leaves uv as it is.
    pub fn is_identity(&self) -> bool {
        *self == Self::IDENTITY
    }

    /// This map followed by `after` (the texture is read at
    /// `after · self · uv`).
    pub fn then(self, after: UvTransform) -> Self {
        Self(after.0 * self.0)
    }

    /// The linear part (∂ texture uv / ∂ surface uv).
    pub fn jacobian(&self) -> Mat2 {
        self.0.matrix2
    }

    /// A gradient taken in the texture's coordinates, as one in the
    /// surface's: the chain rule, Jᵀ·g (a bump map tiled twice in u has
    /// twice the slope along u).
    #[inline]
    pub fn pull_back_gradient(&self, g: Vec2) -> Vec2 {
        self.jacobian().transpose() * g
    }
}

/// A texture in a material slot: its source, how to read its values, the
/// factors applied to them, and where on the surface it is read.
///
/// Two factors, because a slot reads either a colour or one value: a
/// colour read is texel × `tint` × `scale` per channel (glTF's
/// `baseColorFactor` times its texture, exactly), a one-value read
/// (roughness, metalness, opacity, a bump's height, a normal map's
/// strength) is the channel × `scale`, the tint unread.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureRef {
    /// An image or a procedural pattern.
    pub source: TextureSource,
    /// How an image's stored values become linear ones (procedural colours
    /// are linear already).
    pub color_space: ColorSpace,
    /// Multiplies every (linear) value read, colour or one value.
    pub scale: f32,
    /// Multiplies a colour read per channel (linear RGB; white by
    /// default): a colour factor on a colour texture, kept whole rather
    /// than reduced to one number. One-value reads ignore it.
    pub tint: Vec3,
    /// For a one-value slot (roughness, metalness, opacity): the channel
    /// holding it (0 R, 1 G, 2 B, 3 A), as glTF packs roughness in G and
    /// metalness in B of one image. `None`: the renderer's default.
    pub channel: Option<u8>,
    /// How an image is read between texel centres.
    pub filter: TextureFilter,
    /// How an image is addressed beyond its edges.
    pub wrap: TextureWrap,
    /// Applied to the surface's uv before the lookup.
    pub uv: UvTransform,
    /// Whether every value read is multiplied by the surface's vertex
    /// colour (see the module docs): glTF's `baseColorTexture × COLOR_0`.
    pub times_vertex_color: bool,
}

impl TextureRef {
    /// The image at `path`, read in `color_space`, unscaled and untinted,
    /// bilinear, repeating, at the surface's own uv.
    pub fn new(path: impl Into<PathBuf>, color_space: ColorSpace) -> Self {
        Self::of(TextureSource::Image(path.into()), color_space)
    }

    /// A checkerboard of `color0` and `color1` (linear), at the surface's
    /// own uv.
    pub fn checkerboard(color0: Vec3, color1: Vec3) -> Self {
        Self::of(
            TextureSource::Checkerboard { color0, color1 },
            ColorSpace::Linear,
        )
    }

    /// The mesh's vertex colours, unscaled and untinted.
    pub fn vertex_color() -> Self {
        Self::of(TextureSource::VertexColor, ColorSpace::Linear)
    }

    fn of(source: TextureSource, color_space: ColorSpace) -> Self {
        Self {
            source,
            color_space,
            scale: 1.0,
            tint: Vec3::ONE,
            channel: None,
            filter: TextureFilter::default(),
            wrap: TextureWrap::REPEAT,
            uv: UvTransform::IDENTITY,
            times_vertex_color: false,
        }
    }

    /// The image file, if the texture reads one.
    pub fn image_path(&self) -> Option<&Path> {
        match &self.source {
            TextureSource::Image(p) => Some(p),
            TextureSource::Checkerboard { .. } | TextureSource::VertexColor => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checkerboard_cells_alternate_in_u_and_v_with_period_one() {
        // Cell centres of a 4×4 grid over [-1, 1)²: even exactly when the
        // cell indices' sum is.
        for i in -2..2 {
            for j in -2..2 {
                let centre = Vec2::new(i as f32 + 0.5, j as f32 + 0.5) * 0.5;
                let even = (i + j) % 2 == 0;
                assert_eq!(
                    TextureSource::checker_cell_is_even(centre),
                    even,
                    "cell ({i}, {j})"
                );
            }
        }
        // The cell [0, ½)² is color0's, closed at 0 and open at ½.
        assert!(TextureSource::checker_cell_is_even(Vec2::ZERO));
        assert!(!TextureSource::checker_cell_is_even(Vec2::new(0.5, 0.0)));
    }

    #[test]
    fn wrap_modes_fold_indices_as_their_formulas_say() {
        let n = 4;
        // Indices -9..=12 against the closed forms, written out per mode.
        for i in -9i64..=12 {
            let repeat = ((i % n) + n) % n;
            // Mirror: the tile index t = ⌊i / n⌋ is even (as is) or odd
            // (reversed).
            let t = i.div_euclid(n);
            let mirror = if t % 2 == 0 { repeat } else { n - 1 - repeat };
            let clamp = i.max(0).min(n - 1);
            assert_eq!(WrapMode::Repeat.texel_index(i, n), repeat, "repeat {i}");
            assert_eq!(WrapMode::Mirror.texel_index(i, n), mirror, "mirror {i}");
            assert_eq!(WrapMode::Clamp.texel_index(i, n), clamp, "clamp {i}");
        }
        // At the edges: mirror reads the edge texel twice, clamp forever.
        assert_eq!(WrapMode::Mirror.texel_index(-1, n), 0);
        assert_eq!(WrapMode::Mirror.texel_index(n, n), n - 1);
        assert_eq!(WrapMode::Mirror.texel_index(2 * n, n), 0);
        assert_eq!(WrapMode::Repeat.texel_index(-1, n), n - 1);
        // One texel: every mode reads it.
        for mode in [WrapMode::Repeat, WrapMode::Mirror, WrapMode::Clamp] {
            assert_eq!(mode.texel_index(-7, 1), 0);
            assert_eq!(mode.texel_index(5, 1), 0);
        }
    }

    #[test]
    fn uv_transforms_compose_in_order_and_pull_gradients_back() {
        let scale = UvTransform(Affine2::from_scale(Vec2::new(2.0, 3.0)));
        let shift = UvTransform(Affine2::from_translation(Vec2::new(0.5, 0.0)));
        let uv = Vec2::new(0.1, 0.2);
        // Scale then shift: 2·0.1 + 0.5, 3·0.2.
        let a = scale.then(shift).apply(uv);
        assert!((a - Vec2::new(0.7, 0.6)).abs().max_element() < 1e-6, "{a}");
        // Shift then scale: 2·(0.1 + 0.5), 3·0.2.
        let b = shift.then(scale).apply(uv);
        assert!((b - Vec2::new(1.2, 0.6)).abs().max_element() < 1e-6, "{b}");
        assert!(UvTransform::default().is_identity());
        assert_eq!(
            scale.pull_back_gradient(Vec2::new(1.0, 1.0)),
            Vec2::new(2.0, 3.0)
        );
        // A rotation's gradient turns back by the transpose.
        let quarter = UvTransform(Affine2::from_angle(std::f32::consts::FRAC_PI_2));
        let g = quarter.pull_back_gradient(Vec2::new(1.0, 0.0));
        assert!((g - Vec2::new(0.0, -1.0)).abs().max_element() < 1e-6, "{g}");
    }
}
