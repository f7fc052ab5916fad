//! A texture in a material's slot: the image, the slot's scale, and for
//! one-value slots the channel that holds the value.

use super::{ImageTexture, TextureCache};
use candela_scene::TextureRef;
use glam::{Vec2, Vec3};
use std::sync::Arc;

/// An image read for one material parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct SlotTexture {
    /// The image, shared by every slot that names the same file and colour
    /// space.
    pub image: Arc<ImageTexture>,
    /// Factor on every value read.
    pub scale: f32,
    /// The channel of a one-value slot (0 R, 1 G, 2 B, 3 alpha); `None`
    /// reads the slot's default (see [`SlotTexture::value`]).
    pub channel: Option<u8>,
}

impl SlotTexture {
    /// Reads `t` through `cache`; `None` (and a message in the cache) when
    /// the file cannot be used.
    pub fn load(t: &TextureRef, cache: &mut TextureCache) -> Option<Self> {
        Some(Self {
            image: cache.get_in(&t.path, t.color_space)?,
            scale: t.scale,
            channel: t.channel,
        })
    }

    /// The colour at `uv`, times the scale. A slot that names a channel
    /// reads that channel as grey.
    pub fn color(&self, uv: Vec2) -> Vec3 {
        match self.channel {
            Some(c) => Vec3::splat(self.image.lookup_channel(uv, c) * self.scale),
            None => self.image.lookup(uv) * self.scale,
        }
    }

    /// The value at `uv`, times the scale: the named channel, else
    /// `default_channel`.
    pub fn value(&self, uv: Vec2, default_channel: u8) -> f32 {
        self.image
            .lookup_channel(uv, self.channel.unwrap_or(default_channel))
            * self.scale
    }

    /// The gradient (∂/∂u, ∂/∂v) of [`SlotTexture::value`] at `uv`.
    pub fn gradient(&self, uv: Vec2, default_channel: u8) -> Vec2 {
        self.image
            .gradient_channel(uv, self.channel.unwrap_or(default_channel))
            * self.scale
    }
}
