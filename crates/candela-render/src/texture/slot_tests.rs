//! A slot's reads checked analytically: the checkerboard's cells, the factors
//! (tint on colour reads, scale on all), the uv
//! transform's effect on an image (repeats, shifts, order of composition),
//! nearest texels, and bump gradients carried through the transform.

use super::*;
use candela_image::RgbImage;
use candela_scene::WrapMode;
use glam::Affine2;

const RED: Vec3 = Vec3::new(1.0, 0.0, 0.0);
const BLUE: Vec3 = Vec3::new(0.0, 0.0, 1.0);

/// Two texel columns: `RED` on the left half (u < ½), `BLUE` on the right.
fn halves() -> Arc<ImageTexture> {
    let image = RgbImage::from_pixels(2, 1, vec![RED.to_array(), BLUE.to_array()]).unwrap();
    Arc::new(ImageTexture::from_image(&image).unwrap())
}

/// A smooth-ish 5 × 3 image whose bilinear interpolant has a different
/// slope in every cell.
fn varied() -> Arc<ImageTexture> {
    let image = RgbImage::from_fn(5, 3, |i, j| {
        let v = ((i * 7 + j * 3) % 11) as f32 / 11.0;
        [v, 1.0 - v, 0.5 * v]
    })
    .unwrap();
    Arc::new(ImageTexture::from_image(&image).unwrap())
}

fn nearest(image: Arc<ImageTexture>, uv: Affine2) -> SlotTexture {
    SlotTexture {
        filter: TextureFilter::Nearest,
        uv: UvTransform(uv),
        ..SlotTexture::of_image(image)
    }
}

fn checkerboard(uv: Affine2) -> SlotTexture {
    SlotTexture {
        source: SlotSource::Checkerboard {
            color0: RED,
            color1: BLUE,
        },
        uv: UvTransform(uv),
        ..SlotTexture::of_image(halves())
    }
}

#[test]
fn a_checkerboard_of_scale_s_has_2s_alternating_cells_per_side() {
    for s in [1u32, 2, 4] {
        let slot = checkerboard(Affine2::from_scale(Vec2::splat(s as f32)));
        let n = 2 * s; // cells per side of the unit square
        let mut count = [0u32; 2];
        for i in 0..n {
            for j in 0..n {
                let centre = (Vec2::new(i as f32, j as f32) + 0.5) / n as f32;
                let expected = if (i + j) % 2 == 0 { RED } else { BLUE };
                assert_eq!(slot.rgb(centre), expected, "scale {s}, cell ({i}, {j})");
                count[((i + j) % 2) as usize] += 1;
            }
        }
        // Half of the n² cells each: 16 cells for scale 2, 64 for scale 4.
        assert_eq!(count, [n * n / 2; 2], "scale {s}");
    }
    // Outside [0, 1)² the pattern continues with period 1.
    let plain = checkerboard(Affine2::IDENTITY);
    for uv in [Vec2::new(0.25, 0.25), Vec2::new(0.75, 0.25)] {
        for k in [-3.0, -1.0, 1.0, 5.0] {
            assert_eq!(
                plain.rgb(uv + Vec2::new(k, -k)),
                plain.rgb(uv),
                "{uv} + {k}"
            );
        }
    }
}

#[test]
fn a_checkerboard_in_a_one_value_slot_reads_the_channel_and_has_no_slope() {
    let slot = SlotTexture {
        scale: 0.5,
        ..checkerboard(Affine2::IDENTITY)
    };
    let (in0, in1) = (Vec2::new(0.1, 0.2), Vec2::new(0.6, 0.2));
    assert_eq!(slot.value(in0, 0), 0.5);
    assert_eq!(slot.value(in1, 0), 0.0);
    assert_eq!(slot.value(in1, 2), 0.5);
    assert_eq!(slot.value(in1, 3), 0.5, "no alpha: opaque");
    assert!(!slot.has_alpha());
    assert_eq!(slot.gradient(in0, 0), Vec2::ZERO);
}

#[test]
fn a_scale_of_two_repeats_the_image_twice() {
    let image = varied();
    let once = SlotTexture::of_image(image.clone());
    let twice = SlotTexture {
        uv: UvTransform(Affine2::from_scale(Vec2::new(2.0, 2.0))),
        ..SlotTexture::of_image(image)
    };
    for uv in [
        Vec2::new(0.1, 0.2),
        Vec2::new(0.37, 0.41),
        Vec2::new(0.05, 0.49),
    ] {
        let expected = once.rgb(2.0 * uv);
        for shift in [
            Vec2::ZERO,
            Vec2::new(0.5, 0.0),
            Vec2::new(0.0, 0.5),
            Vec2::splat(0.5),
        ] {
            let got = twice.rgb(uv + shift);
            assert!(
                (got - expected).abs().max_element() < 1e-5,
                "{got} vs {expected} at {uv} + {shift}"
            );
        }
    }
}

#[test]
fn a_translation_by_a_half_swaps_the_halves() {
    let plain = nearest(halves(), Affine2::IDENTITY);
    let shifted = nearest(halves(), Affine2::from_translation(Vec2::new(0.5, 0.0)));
    for v in [0.1, 0.6] {
        assert_eq!(plain.rgb(Vec2::new(0.25, v)), RED);
        assert_eq!(plain.rgb(Vec2::new(0.75, v)), BLUE);
        assert_eq!(shifted.rgb(Vec2::new(0.25, v)), BLUE);
        assert_eq!(shifted.rgb(Vec2::new(0.75, v)), RED);
    }
}

#[test]
fn scale_then_translate_differs_from_translate_then_scale() {
    // Scale then shift reads u' = 2u + ¼, shift then scale u' = 2(u + ¼):
    // at u = 0.05 that is 0.35 (red) one way and 0.6 (blue) the other.
    let scale = UvTransform(Affine2::from_scale(Vec2::new(2.0, 1.0)));
    let shift = UvTransform(Affine2::from_translation(Vec2::new(0.25, 0.0)));
    let a = nearest(halves(), scale.then(shift).0);
    let b = nearest(halves(), shift.then(scale).0);
    let uv = Vec2::new(0.05, 0.5);
    assert_eq!(a.rgb(uv), RED);
    assert_eq!(b.rgb(uv), BLUE);
}

#[test]
fn nearest_reads_the_covering_texel_and_has_no_slope() {
    let image = varied();
    let slot = nearest(image.clone(), Affine2::IDENTITY);
    let (w, h) = image.size();
    for i in 0..w as i64 {
        for j in 0..h as i64 {
            // Anywhere inside texel (i, j), not only at its centre.
            for (fx, fy) in [(0.01, 0.02), (0.5, 0.5), (0.98, 0.97)] {
                let uv = Vec2::new((i as f32 + fx) / w as f32, (j as f32 + fy) / h as f32);
                assert_eq!(slot.rgb(uv), image.texel(i, j), "texel ({i}, {j}) at {uv}");
                assert_eq!(slot.value(uv, 1), image.texel(i, j).y);
            }
        }
    }
    assert_eq!(slot.gradient(Vec2::new(0.3, 0.3), 0), Vec2::ZERO);
}

#[test]
fn a_bump_gradient_follows_the_transform_by_the_chain_rule() {
    // Central differences of the value through a rotated, scaled and
    // shifted uv, against the slot's analytic gradient, away from the
    // kinks of the bilinear interpolant (where the difference straddles
    // two cells).
    let m = Affine2::from_scale_angle_translation(Vec2::new(2.0, 3.0), 0.4, Vec2::new(0.3, -0.2));
    let slot = SlotTexture {
        uv: UvTransform(m),
        ..SlotTexture::of_image(varied())
    };
    let h = 1e-4f32;
    let mut checked = 0;
    for k in 0..40 {
        let uv = Vec2::new(0.013 + 0.0237 * k as f32, 0.71 - 0.0173 * k as f32);
        let g = slot.gradient(uv, 0);
        let du = (slot.value(uv + Vec2::X * h, 0) - slot.value(uv - Vec2::X * h, 0)) / (2.0 * h);
        let dv = (slot.value(uv + Vec2::Y * h, 0) - slot.value(uv - Vec2::Y * h, 0)) / (2.0 * h);
        // The four probes in one bilinear cell: their gradients differ by
        // the interpolant's small twist only, not by a jump between cells.
        let near = 1e-2 * (1.0 + g.abs().max_element());
        let same_cell = [Vec2::X, -Vec2::X, Vec2::Y, -Vec2::Y]
            .iter()
            .all(|d| (slot.gradient(uv + *d * h, 0) - g).abs().max_element() < near);
        if !same_cell {
            continue;
        }
        checked += 1;
        // f32 differences of values ~1 over 2h: error ~1e-7/1e-4 per unit slope.
        let tol = 0.02 * (1.0 + g.abs().max_element());
        assert!(
            (Vec2::new(du, dv) - g).abs().max_element() < tol,
            "{g} vs ({du}, {dv}) at {uv}"
        );
    }
    assert!(checked >= 20, "only {checked} points away from kinks");
}

#[test]
fn a_vertex_colour_slot_reads_the_points_colour_whatever_its_uv() {
    let slot = SlotTexture {
        source: SlotSource::VertexColor,
        scale: 0.5,
        // Ignored by vertex colours: they are not read at uv.
        uv: UvTransform(Affine2::from_scale(Vec2::splat(3.0))),
        ..SlotTexture::of_image(halves())
    };
    let color = Vec3::new(0.2, 0.6, 0.9);
    for uv in [Vec2::new(0.1, 0.2), Vec2::new(0.7, -4.0)] {
        let at = TexturePoint::new(uv, color);
        assert_eq!(slot.color(at), 0.5 * color);
        assert_eq!(slot.value(at, 1), 0.5 * color.y);
        assert_eq!(slot.value(at, 3), 0.5, "vertex colours are opaque");
        assert_eq!(slot.gradient(at, 0), Vec2::ZERO);
    }
    // A point given by uv alone (a mesh without colours) reads white.
    assert_eq!(slot.color(Vec2::new(0.3, 0.3)), Vec3::splat(0.5));
}

#[test]
fn a_texture_times_the_vertex_colour_is_their_product_channel_by_channel() {
    let color = Vec3::new(0.25, 0.5, 0.75);
    let product = |slot: &SlotTexture| SlotTexture {
        times_vertex_color: true,
        ..slot.clone()
    };
    let image = varied();
    for plain in [
        SlotTexture {
            scale: 0.8,
            ..SlotTexture::of_image(image.clone())
        },
        nearest(image, Affine2::from_scale(Vec2::new(2.0, 3.0))),
        checkerboard(Affine2::IDENTITY),
    ] {
        let times = product(&plain);
        for uv in [Vec2::new(0.13, 0.41), Vec2::new(0.62, 0.77)] {
            let at = TexturePoint::new(uv, color);
            // Equal up to the order of the products (an ulp or two).
            let close =
                |a: Vec3, b: Vec3| (a - b).abs().max_element() <= 1e-6 * b.abs().max_element();
            assert!(close(times.color(at), plain.color(uv) * color), "{uv}");
            assert!(close(times.rgb(at), plain.rgb(uv) * color), "{uv}");
            for c in 0..3u8 {
                let k = color[c as usize];
                let value = Vec3::splat(times.value(at, c));
                assert!(
                    close(value, Vec3::splat(plain.value(uv, c) * k)),
                    "{uv} {c}"
                );
                let g = times.gradient(at, c).extend(0.0);
                assert!(
                    close(g, (plain.gradient(uv, c) * k).extend(0.0)),
                    "{uv} {c}"
                );
            }
            // Alpha is not coloured.
            assert_eq!(times.value(at, 3), plain.value(uv, 3));
            // Without a vertex colour, the product is the plain texture.
            assert_eq!(times.color(uv), plain.color(uv));
        }
    }
}

#[test]
fn the_uv_transform_applies_before_the_wrap() {
    // Scaled by 2 about the origin, uv 0.75 reads texture u 1.5: past the
    // right edge, where clamp holds the right column (BLUE), mirror reads
    // the reversed tile's texel at 1.5 (RED, the image's left half
    // mirrored to the right) and repeat reads u 0.5 (BLUE).
    let scaled = Affine2::from_scale(Vec2::splat(2.0));
    let at = Vec2::new(0.76, 0.5);
    for (mode, expected) in [
        (WrapMode::Clamp, BLUE),
        (WrapMode::Mirror, RED),
        (WrapMode::Repeat, BLUE),
    ] {
        let slot = SlotTexture {
            wrap: TextureWrap::both(mode),
            ..nearest(halves(), scaled)
        };
        assert_eq!(slot.rgb(at), expected, "{mode:?}");
        // Texture u 1.52 sits 0.02 past the right edge: the bilinear
        // weights are taken between the folded texels, so clamp is pure
        // BLUE there and repeat mixes in the RED of texel 2 ≡ 0.
        let bilinear = SlotTexture {
            filter: TextureFilter::Bilinear,
            ..slot
        };
        let got = bilinear.rgb(at);
        match mode {
            WrapMode::Clamp => assert_eq!(got, BLUE),
            WrapMode::Mirror | WrapMode::Repeat => assert!(got.x > 0.0 && got.z > 0.0, "{got}"),
        }
    }
}

#[test]
fn a_colour_read_is_texel_times_tint_times_scale_and_a_value_read_ignores_the_tint() {
    let tint = Vec3::new(1.0, 0.5, 0.25);
    let plain = SlotTexture::of_image(varied());
    let tinted = SlotTexture {
        tint,
        scale: 0.8,
        ..plain.clone()
    };
    let scaled = SlotTexture {
        scale: 0.8,
        ..plain.clone()
    };
    for uv in [Vec2::new(0.13, 0.41), Vec2::new(0.62, 0.77)] {
        let texel = plain.color(uv);
        assert!(texel.x != texel.y && texel.y != texel.z, "a coloured texel");
        let expected = texel * tint * 0.8;
        assert!(
            (tinted.color(uv) - expected).abs().max_element() < 1e-6,
            "{} vs {expected} at {uv}",
            tinted.color(uv)
        );
        // One-value reads (and their slope) see the scale alone.
        for c in 0..4u8 {
            assert_eq!(tinted.value(uv, c), scaled.value(uv, c), "{uv} {c}");
            assert_eq!(tinted.gradient(uv, c), scaled.gradient(uv, c), "{uv} {c}");
        }
        // The raw colour (a normal map's direction) has no factor at all.
        assert_eq!(tinted.rgb(uv), plain.rgb(uv));
    }
    // The mean colour (an emitter's power) carries both factors.
    let mean = tinted.mean_color();
    assert!(
        (mean - plain.mean() * tint * 0.8).abs().max_element() < 1e-6,
        "{mean}"
    );
    // Untinted, a colour read is exactly the scaled texel.
    let uv = Vec2::new(0.3, 0.6);
    assert_eq!(scaled.color(uv), plain.rgb(uv) * 0.8);
}

#[test]
fn a_tinted_vertex_colour_is_the_factor_times_the_colour_per_channel() {
    // glTF's baseColorFactor × COLOR_0 without a texture, and with one.
    let tint = Vec3::new(0.9, 0.5, 0.1);
    let color = Vec3::new(0.2, 0.6, 0.8);
    let vertex = SlotTexture {
        source: SlotSource::VertexColor,
        tint,
        ..SlotTexture::of_image(halves())
    };
    let textured = SlotTexture {
        tint,
        times_vertex_color: true,
        ..nearest(halves(), Affine2::IDENTITY)
    };
    let uv = Vec2::new(0.25, 0.5); // the red half
    let at = TexturePoint::new(uv, color);
    assert_eq!(vertex.color(at), tint * color);
    assert_eq!(vertex.value(at, 1), color.y, "one value: no tint");
    assert_eq!(textured.color(at), RED * color * tint);
}
