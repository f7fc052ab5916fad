//! The glTF model's transmission, specular strength and specular colour
//! slots at a hit: a texture of constant value gives the BSDF the factor
//! of that value would (the same parameters, so the same `f`, `pdf` and
//! samples), each slot reading its own channel (transmission red, specular
//! strength alpha, 1 where the image has none) and leaving every other
//! parameter as it was.

use super::MetallicRoughnessSlots;
use crate::bsdf::{Bsdf, MetallicRoughness};
use crate::shading::MaterialTextures;
use crate::texture::{ImageTexture, SlotTexture};
use candela_image::RgbImage;
use candela_scene::TextureFilter;
use glam::{Vec2, Vec3};
use std::sync::Arc;

/// A texture of one texel, `rgb` everywhere (no alpha), read nearest so
/// the texel comes back exactly (bilinear weights round).
fn constant(rgb: Vec3) -> SlotTexture {
    let image = RgbImage::from_pixels(1, 1, vec![rgb.to_array()]).unwrap();
    SlotTexture {
        filter: TextureFilter::Nearest,
        ..SlotTexture::of_image(Arc::new(ImageTexture::from_image(&image).unwrap()))
    }
}

/// A metallic-roughness BSDF with every parameter away from its default,
/// transmission and the specular layer as given.
fn model(transmission: f32, specular: f32, specular_color: Vec3) -> MetallicRoughness {
    MetallicRoughness::new(Vec3::new(0.7, 0.5, 0.3), 0.2, 0.45, transmission, 1.4)
        .with_specular(specular, specular_color)
        .with_clearcoat(0.3, 0.25)
}

/// A material's textures holding only `layers`, applied to the untextured
/// model at some uv (through the material's whole texture path).
fn textured(layers: MetallicRoughnessSlots) -> Bsdf {
    let textures = MaterialTextures {
        metallic_roughness: Some(Box::new(layers)),
        ..MaterialTextures::default()
    };
    let untextured = model(0.2, 0.9, Vec3::new(0.9, 1.0, 1.1));
    textures.apply(Bsdf::MetallicRoughness(untextured), Vec2::new(0.3, 0.7))
}

/// Asserts the textured BSDF is the model of `expected`, and (so the slot
/// is seen to act) that it differs from the untextured one in `f`.
fn assert_model(got: Bsdf, expected: MetallicRoughness, slot: &str) {
    assert_eq!(got, Bsdf::MetallicRoughness(expected), "{slot}");
    let untextured = Bsdf::MetallicRoughness(model(0.2, 0.9, Vec3::new(0.9, 1.0, 1.1)));
    let (wo, wi) = (
        Vec3::new(0.3, 0.1, 0.9).normalize(),
        Vec3::new(-0.4, 0.2, 0.8).normalize(),
    );
    assert_ne!(
        got.f(wo, wi),
        untextured.f(wo, wi),
        "{slot} changes nothing"
    );
}

#[test]
fn a_constant_transmission_texture_is_its_value_as_the_factor() {
    // Red 0.7 (green and blue other values, unread) times the scale.
    let texel = Vec3::new(0.7, 0.1, 0.9);
    for (scale, channel) in [(1.0, None), (0.5, Some(0))] {
        let layers = MetallicRoughnessSlots {
            transmission: Some(SlotTexture {
                scale,
                channel,
                ..constant(texel)
            }),
            ..MetallicRoughnessSlots::default()
        };
        let expected = model(0.7 * scale, 0.9, Vec3::new(0.9, 1.0, 1.1));
        assert_model(textured(layers), expected, "transmission");
    }
}

#[test]
fn a_constant_specular_texture_is_its_value_as_the_factor() {
    // No alpha in the image: the default channel (alpha) reads 1, so the
    // strength is the scale (glTF's specularFactor) alone.
    let layers = MetallicRoughnessSlots {
        specular: Some(SlotTexture {
            scale: 0.6,
            ..constant(Vec3::new(0.25, 0.5, 0.75))
        }),
        ..MetallicRoughnessSlots::default()
    };
    let expected = model(0.2, 0.6, Vec3::new(0.9, 1.0, 1.1));
    assert_model(textured(layers), expected, "specular, alpha");
    // A named channel: its value times the scale.
    let layers = MetallicRoughnessSlots {
        specular: Some(SlotTexture {
            scale: 0.8,
            channel: Some(1),
            ..constant(Vec3::new(0.25, 0.5, 0.75))
        }),
        ..MetallicRoughnessSlots::default()
    };
    let expected = model(0.2, 0.5 * 0.8, Vec3::new(0.9, 1.0, 1.1));
    assert_model(textured(layers), expected, "specular, green");
}

#[test]
fn a_constant_specular_colour_texture_is_texel_times_tint_as_the_factor() {
    // glTF's specularColorFactor × texel, per channel, unclamped (the
    // factor may exceed 1; the model caps F0 itself).
    let (texel, tint) = (Vec3::new(0.8, 0.5, 0.2), Vec3::new(1.0, 0.5, 2.5));
    let layers = MetallicRoughnessSlots {
        specular_color: Some(SlotTexture {
            tint,
            ..constant(texel)
        }),
        ..MetallicRoughnessSlots::default()
    };
    let expected = model(0.2, 0.9, texel * tint);
    assert_model(textured(layers), expected, "specular colour");
}
