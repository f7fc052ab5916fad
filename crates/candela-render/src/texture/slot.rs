//! A texture in a material's slot: its source (an image or a checkerboard),
//! the slot's factors (a scale on every read, a tint on colour reads), for
//! one-value slots the channel that holds the value, the image filter, and
//! the uv transform. Every slot (colour, roughness,
//! metalness, normal and bump maps, emission, opacity) reads through the
//! methods here, so each gets every source, the filter and the transform
//! alike: the surface's uv is transformed first, then the source is read
//! there (an image outside [0, 1) repeats, mirrors or clamps as its
//! [`TextureWrap`] says). The vertex colour is read at the point's own
//! colour, and a slot marked `times_vertex_color` multiplies whatever it
//! reads by it.

use super::{ImageTexture, TextureCache, TexturePoint};
use candela_scene::{TextureFilter, TextureRef, TextureSource, TextureWrap, UvTransform};
use glam::{Vec2, Vec3};
use std::sync::Arc;

/// What a slot reads.
#[derive(Clone, Debug, PartialEq)]
pub enum SlotSource {
    /// An image, shared by every slot that names the same file and colour
    /// space.
    Image(Arc<ImageTexture>),
    /// Two linear colours in a checkerboard
    /// ([`TextureSource::Checkerboard`]).
    Checkerboard {
        /// The colour of the cell `[0, ½)²`.
        color0: Vec3,
        /// The colour of its neighbours.
        color1: Vec3,
    },
    /// The mesh's vertex colour at the point
    /// ([`TextureSource::VertexColor`]).
    VertexColor,
}

/// A texture read for one material parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct SlotTexture {
    /// What is read.
    pub source: SlotSource,
    /// Factor on every value read.
    pub scale: f32,
    /// Factor per channel on colour reads ([`SlotTexture::color`]); one-value
    /// reads ([`SlotTexture::value`], [`SlotTexture::gradient`]) ignore it.
    pub tint: Vec3,
    /// The channel of a one-value slot (0 R, 1 G, 2 B, 3 alpha); `None`
    /// reads the slot's default (see [`SlotTexture::value`]).
    pub channel: Option<u8>,
    /// How an image is read between texel centres.
    pub filter: TextureFilter,
    /// How an image is addressed beyond its edges.
    pub wrap: TextureWrap,
    /// Applied to the surface's uv before the lookup.
    pub uv: UvTransform,
    /// Whether every value read is multiplied by the point's vertex colour
    /// (its channel, for a one-value read).
    pub times_vertex_color: bool,
}

impl SlotTexture {
    /// `image`, unscaled and untinted, bilinear, repeating, at the
    /// surface's own uv.
    pub fn of_image(image: Arc<ImageTexture>) -> Self {
        Self {
            source: SlotSource::Image(image),
            scale: 1.0,
            tint: Vec3::ONE,
            channel: None,
            filter: TextureFilter::Bilinear,
            wrap: TextureWrap::REPEAT,
            uv: UvTransform::IDENTITY,
            times_vertex_color: false,
        }
    }

    /// Reads `t` through `cache`; `None` (and a message in the cache) when
    /// its image cannot be used.
    pub fn load(t: &TextureRef, cache: &mut TextureCache) -> Option<Self> {
        let source = match &t.source {
            TextureSource::Image(path) => SlotSource::Image(cache.get_in(path, t.color_space)?),
            TextureSource::Checkerboard { color0, color1 } => SlotSource::Checkerboard {
                color0: *color0,
                color1: *color1,
            },
            TextureSource::VertexColor => SlotSource::VertexColor,
        };
        Some(Self {
            source,
            scale: t.scale,
            tint: t.tint,
            channel: t.channel,
            filter: t.filter,
            wrap: t.wrap,
            uv: t.uv,
            times_vertex_color: t.times_vertex_color,
        })
    }

    /// Whether the source has an alpha channel (only an image can).
    pub fn has_alpha(&self) -> bool {
        matches!(&self.source, SlotSource::Image(i) if i.has_alpha())
    }

    /// The source's mean colour over one period, unscaled: the texture's
    /// average over any surface whose (transformed) uv covers whole
    /// periods. Vertex colours are not known here: they count as white (a
    /// light's power is then an estimate, not its value).
    pub fn mean(&self) -> Vec3 {
        match &self.source {
            SlotSource::Image(image) => image.mean(),
            SlotSource::Checkerboard { color0, color1 } => 0.5 * (*color0 + *color1),
            SlotSource::VertexColor => TexturePoint::NO_VERTEX_COLOR,
        }
    }

    /// The colour at a point (its uv, or its vertex colour), without the
    /// factors (a normal map's encoded direction).
    #[inline]
    pub fn rgb(&self, at: impl Into<TexturePoint>) -> Vec3 {
        let at = at.into();
        let rgb = self.source_rgb(at);
        if self.times_vertex_color {
            rgb * at.vertex_color
        } else {
            rgb
        }
    }

    /// [`SlotTexture::rgb`] before the vertex colour's product.
    fn source_rgb(&self, at: TexturePoint) -> Vec3 {
        let st = self.uv.apply(at.uv);
        match &self.source {
            SlotSource::Image(image) => match self.filter {
                TextureFilter::Bilinear => image.lookup(st, self.wrap),
                TextureFilter::Nearest => image.nearest(st, self.wrap),
            },
            SlotSource::Checkerboard { color0, color1 } => checker(st, *color0, *color1),
            SlotSource::VertexColor => at.vertex_color,
        }
    }

    /// The colour at a point times the tint and the scale, per channel. A
    /// slot that names a channel reads that channel as grey (then tinted).
    /// With the default tint the product is bit for bit the scaled colour
    /// alone (1 × scale is exact).
    pub fn color(&self, at: impl Into<TexturePoint>) -> Vec3 {
        let at = at.into();
        let texel = match self.channel {
            Some(c) => Vec3::splat(self.channel_at(at, c)),
            None => self.rgb(at),
        };
        texel * self.color_factor()
    }

    /// The mean of [`SlotTexture::color`] over one period (see
    /// [`SlotTexture::mean`]), negative channels at 0: an emission
    /// texture's power.
    pub fn mean_color(&self) -> Vec3 {
        (self.mean() * self.color_factor()).max(Vec3::ZERO)
    }

    /// What a colour read is multiplied by: tint × scale.
    #[inline]
    fn color_factor(&self) -> Vec3 {
        self.tint * self.scale
    }

    /// The value at a point, times the scale (not the tint): the named
    /// channel, else `default_channel`.
    pub fn value(&self, at: impl Into<TexturePoint>, default_channel: u8) -> f32 {
        self.channel_at(at.into(), self.channel.unwrap_or(default_channel)) * self.scale
    }

    /// The gradient (∂/∂u, ∂/∂v in the surface's uv) of
    /// [`SlotTexture::value`] at `uv`: the bilinear interpolant's exact
    /// derivative, carried back through the uv transform (chain rule). A
    /// piecewise-constant source (nearest texels, a checkerboard) has
    /// slope 0, as Mitsuba's is. Vertex colours are taken as constant
    /// here (their slope in uv is not known to the slot): a bump map of
    /// them has slope 0, and one multiplied by them is scaled.
    pub fn gradient(&self, at: impl Into<TexturePoint>, default_channel: u8) -> Vec2 {
        let at = at.into();
        let c = self.channel.unwrap_or(default_channel);
        let in_texture = match (&self.source, self.filter) {
            (SlotSource::Image(image), TextureFilter::Bilinear) => {
                image.gradient_channel(self.uv.apply(at.uv), c, self.wrap)
            }
            (SlotSource::Image(_), TextureFilter::Nearest)
            | (SlotSource::Checkerboard { .. } | SlotSource::VertexColor, _) => Vec2::ZERO,
        };
        self.uv.pull_back_gradient(in_texture) * self.scale * self.vertex_factor(at, c)
    }

    /// Channel `c` (0 R, 1 G, 2 B, 3 alpha: 1 where the source has none)
    /// at a point, unscaled.
    fn channel_at(&self, at: TexturePoint, c: u8) -> f32 {
        let st = self.uv.apply(at.uv);
        let value = match &self.source {
            SlotSource::Image(image) => match self.filter {
                TextureFilter::Bilinear => image.lookup_channel(st, c, self.wrap),
                TextureFilter::Nearest => image.nearest_channel(st, c, self.wrap),
            },
            SlotSource::Checkerboard { color0, color1 } => match c {
                0..=2 => checker(st, *color0, *color1)[c as usize],
                _ => 1.0,
            },
            SlotSource::VertexColor => vertex_channel(at, c),
        };
        value * self.vertex_factor(at, c)
    }

    /// The factor `times_vertex_color` puts on channel `c`: the vertex
    /// colour's channel (1 for alpha), or 1.
    fn vertex_factor(&self, at: TexturePoint, c: u8) -> f32 {
        if self.times_vertex_color {
            vertex_channel(at, c)
        } else {
            1.0
        }
    }
}

/// Channel `c` of the vertex colour at `at` (alpha: 1, vertex colours are
/// opaque).
fn vertex_channel(at: TexturePoint, c: u8) -> f32 {
    match c {
        0..=2 => at.vertex_color[c as usize],
        _ => 1.0,
    }
}

/// The checkerboard of `color0` and `color1` at texture coordinates `st`.
fn checker(st: Vec2, color0: Vec3, color1: Vec3) -> Vec3 {
    if TextureSource::checker_cell_is_even(st) {
        color0
    } else {
        color1
    }
}

#[cfg(test)]
#[path = "slot_tests.rs"]
mod tests;
