//! Bilinear lookups checked exactly on a tiny generated texture, and the
//! cache's load-once, report-once behaviour.

use super::*;
use candela_image::{write_exr, ExrLayers};
use candela_scene::{ColorSpace, TextureWrap, WrapMode};
use std::sync::Arc;

/// 3 × 2 texels; image row 0 (the top, v = 1) is `TOP`.
const TOP: [[f32; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
const BOTTOM: [[f32; 3]; 3] = [[0.5, 0.5, 0.5], [0.25, 0.0, 0.75], [1.0, 1.0, 0.0]];

fn image() -> RgbImage {
    let pixels = TOP.iter().chain(BOTTOM.iter()).copied().collect();
    RgbImage::from_pixels(3, 2, pixels).unwrap()
}

fn v3(a: [f32; 3]) -> Vec3 {
    Vec3::from_array(a)
}

fn assert_close(a: Vec3, b: Vec3) {
    assert!((a - b).abs().max_element() < 1e-6, "{a} vs {b}");
}

#[test]
fn texel_centres_return_their_texels() {
    let t = ImageTexture::from_image(&image()).unwrap();
    for i in 0..3 {
        let u = (i as f32 + 0.5) / 3.0;
        assert_close(
            t.lookup(Vec2::new(u, 0.25), TextureWrap::REPEAT),
            v3(BOTTOM[i]),
        );
        assert_close(
            t.lookup(Vec2::new(u, 0.75), TextureWrap::REPEAT),
            v3(TOP[i]),
        );
    }
}

#[test]
fn lookups_between_centres_are_bilinear() {
    let t = ImageTexture::from_image(&image()).unwrap();
    // A quarter of the way from texel (0, bottom) to (1, bottom) and
    // three quarters of the way up to the top row.
    let uv = Vec2::new((0.5 + 0.25) / 3.0, 0.25 + 0.75 * 0.5);
    let bottom = 0.75 * v3(BOTTOM[0]) + 0.25 * v3(BOTTOM[1]);
    let top = 0.75 * v3(TOP[0]) + 0.25 * v3(TOP[1]);
    assert_close(
        t.lookup(uv, TextureWrap::REPEAT),
        0.25 * bottom + 0.75 * top,
    );
    // The image's centre: on column 1's centre, half-way between the rows.
    assert_close(
        t.lookup(Vec2::new(0.5, 0.5), TextureWrap::REPEAT),
        0.5 * (v3(BOTTOM[1]) + v3(TOP[1])),
    );
}

#[test]
fn addressing_wraps_around() {
    let t = ImageTexture::from_image(&image()).unwrap();
    // u = 0 lies half-way between the last column and the first.
    assert_close(
        t.lookup(Vec2::new(0.0, 0.25), TextureWrap::REPEAT),
        0.5 * (v3(BOTTOM[2]) + v3(BOTTOM[0])),
    );
    // v = 0 lies half-way between the bottom row and (wrapped) the top.
    let u1 = 1.5 / 3.0;
    assert_close(
        t.lookup(Vec2::new(u1, 0.0), TextureWrap::REPEAT),
        0.5 * (v3(BOTTOM[1]) + v3(TOP[1])),
    );
    // Whole periods in either direction change nothing.
    for uv in [Vec2::new(0.1, 0.3), Vec2::new(0.77, 0.91)] {
        for shift in [Vec2::new(1.0, 0.0), Vec2::new(-2.0, 3.0)] {
            let a = t.lookup(uv, TextureWrap::REPEAT);
            let b = t.lookup(uv + shift, TextureWrap::REPEAT);
            assert!((a - b).abs().max_element() < 1e-5, "{uv} + {shift}");
        }
    }
    assert_close(t.texel(-1, -1), v3(TOP[2]));
}

#[test]
fn empty_images_are_rejected() {
    let empty = RgbImage::new(0, 0);
    if let Ok(empty) = empty {
        assert!(matches!(
            ImageTexture::from_image(&empty),
            Err(TextureError::Empty)
        ));
    }
}

#[test]
fn the_cache_loads_once_and_reports_a_missing_file_once() {
    let dir = std::env::temp_dir().join(format!("candela-texcache-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let good = dir.join("good.exr");
    write_exr(&good, &ExrLayers::beauty(image())).unwrap();
    let missing = dir.join("missing.png");
    let odd = dir.join("texture.dds");
    let mut cache = TextureCache::new();
    let a = cache.get(&good).expect("the EXR loads");
    let b = cache.get(&good).expect("and again");
    assert!(Arc::ptr_eq(&a, &b), "read once, shared");
    assert_close(
        a.lookup(Vec2::new(0.5 / 3.0, 0.75), TextureWrap::REPEAT),
        v3(TOP[0]),
    );
    assert!(cache.get(&missing).is_none());
    assert!(cache.get(&missing).is_none());
    assert!(cache.get(&odd).is_none());
    let problems = cache.into_problems();
    assert_eq!(problems.len(), 2, "{problems:?}");
    assert!(problems[0].contains("missing.png"), "{problems:?}");
    assert!(problems[1].contains("unknown image format"), "{problems:?}");
    std::fs::remove_dir_all(&dir).ok();
}

/// 2 × 2 RGBA texels with known stored bytes, row 0 at the top.
const STORED: [[u8; 4]; 4] = [
    [0, 64, 128, 255],
    [255, 128, 32, 0],
    [10, 20, 30, 40],
    [200, 100, 50, 128],
];

fn write_rgba_png(path: &std::path::Path) {
    let file = std::fs::File::create(path).unwrap();
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), 2, 2);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().unwrap();
    writer.write_image_data(STORED.as_flattened()).unwrap();
}

#[test]
fn a_2x2_png_decodes_to_its_known_values_in_either_colour_space() {
    let dir = candela_testkit::TempDir::new("png-2x2");
    let path = dir.join("known.png");
    write_rgba_png(&path);
    let mut cache = TextureCache::new();
    let linear = cache.get_in(&path, ColorSpace::Linear).unwrap();
    let srgb = cache.get_in(&path, ColorSpace::Srgb).unwrap();
    assert!(linear.has_alpha() && srgb.has_alpha());
    for (k, texel) in STORED.iter().enumerate() {
        // Row k / 2 from the top is j = 1 − k / 2 from the bottom.
        let (i, j) = ((k % 2) as i64, 1 - (k / 2) as i64);
        let uv = Vec2::new((i as f32 + 0.5) / 2.0, (j as f32 + 0.5) / 2.0);
        let stored = texel.map(|b| f32::from(b) / 255.0);
        // Data: exactly the stored value, no transfer curve and back.
        assert_eq!(
            linear.texel(i, j),
            Vec3::new(stored[0], stored[1], stored[2])
        );
        for c in 0..4u8 {
            assert_eq!(
                linear.lookup_channel(uv, c, TextureWrap::REPEAT),
                stored[c as usize],
                "texel {k} channel {c}"
            );
        }
        // Colour: decoded from sRGB; alpha is coverage and stays linear.
        let decoded = Vec3::new(
            srgb_decode(stored[0]),
            srgb_decode(stored[1]),
            srgb_decode(stored[2]),
        );
        assert_eq!(srgb.texel(i, j), decoded);
        assert_eq!(srgb.lookup_channel(uv, 3, TextureWrap::REPEAT), stored[3]);
    }
    // A slot reading one channel (glTF roughness in G) sees it as grey.
    let slot = SlotTexture {
        scale: 0.5,
        channel: Some(1),
        ..SlotTexture::of_image(linear.clone())
    };
    let uv = Vec2::new(0.25, 0.75);
    assert_eq!(slot.color(uv), Vec3::splat(64.0 / 255.0 * 0.5));
    assert_eq!(slot.value(uv, 0), 64.0 / 255.0 * 0.5);
    // sRGB code 188 is linear 0.5 (to 3 digits), the classic check.
    assert!((srgb_decode(188.0 / 255.0) - 0.5029).abs() < 1e-3);
}

#[test]
fn the_gradient_is_the_bilinear_lookups_slope() {
    // Inside a cell the interpolant is linear in u along a row (and in v
    // along a column), so the gradient must equal a difference quotient of
    // `lookup_channel` taken within the same cell, for every channel.
    let t = ImageTexture::from_image(&image()).unwrap();
    let h = 1e-3;
    for &(u, v) in &[(0.3, 0.4), (0.55, 0.6), (0.9, 0.3), (0.05, 0.95)] {
        for c in 0..3 {
            let g = t.gradient_channel(Vec2::new(u, v), c, TextureWrap::REPEAT);
            let at = |du: f32, dv: f32| {
                t.lookup_channel(Vec2::new(u + du, v + dv), c, TextureWrap::REPEAT)
            };
            let du = (at(h, 0.0) - at(-h, 0.0)) / (2.0 * h);
            let dv = (at(0.0, h) - at(0.0, -h)) / (2.0 * h);
            assert!(
                (g.x - du).abs() < 1e-2 && (g.y - dv).abs() < 1e-2,
                "{g} vs ({du}, {dv}) at ({u}, {v}) channel {c}"
            );
        }
    }
    // A constant image has no slope; a missing alpha channel neither.
    let flat = RgbImage::from_pixels(2, 2, vec![[0.3, 0.3, 0.3]; 4]).unwrap();
    let flat = ImageTexture::from_image(&flat).unwrap();
    assert_eq!(
        flat.gradient_channel(Vec2::new(0.37, 0.81), 0, TextureWrap::REPEAT),
        Vec2::ZERO
    );
    assert_eq!(
        t.gradient_channel(Vec2::new(0.37, 0.81), 3, TextureWrap::REPEAT),
        Vec2::ZERO
    );
}

/// A 4 × 3 image whose texel (i, j) (j from the bottom) holds (i, j, 0):
/// a lookup's red and green say which texels it read.
fn index_image() -> ImageTexture {
    let image = RgbImage::from_fn(4, 3, |i, row| [i as f32, (2 - row) as f32, 0.0]).unwrap();
    ImageTexture::from_image(&image).unwrap()
}

/// The texel index `i` of an axis of `n` reads, written per mode as its
/// definition reads (tiles of period n; mirror reverses the odd tiles;
/// clamp holds the edges).
fn folded(mode: WrapMode, i: i64, n: i64) -> f32 {
    let tile = i.div_euclid(n);
    let within = i - tile * n;
    (match mode {
        WrapMode::Repeat => within,
        WrapMode::Mirror if tile % 2 == 0 => within,
        WrapMode::Mirror => n - 1 - within,
        WrapMode::Clamp => i.max(0).min(n - 1),
    }) as f32
}

/// Equal to rounding: texel coordinates up to 12 lose a few ulps.
fn assert_near(a: Vec3, b: Vec3) {
    assert!((a - b).abs().max_element() < 1e-4, "{a} vs {b}");
}

const MODES: [WrapMode; 3] = [WrapMode::Repeat, WrapMode::Mirror, WrapMode::Clamp];

#[test]
fn nearest_lookups_wrap_each_axis_at_texel_boundaries() {
    let t = index_image();
    let eps = 1e-4;
    for mode_u in MODES {
        for mode_v in MODES {
            let wrap = TextureWrap {
                u: mode_u,
                v: mode_v,
            };
            // Just either side of every texel boundary over three periods.
            for k in -8i64..=12 {
                for side in [-eps, eps] {
                    let u = k as f32 / 4.0 + side;
                    let v = k as f32 / 3.0 + side;
                    let i = if side < 0.0 { k - 1 } else { k };
                    let got = t.nearest(Vec2::new(u, v), wrap);
                    let expected = Vec3::new(folded(mode_u, i, 4), folded(mode_v, i, 3), 0.0);
                    assert_eq!(got, expected, "{wrap:?} at ({u}, {v})");
                    let green = t.nearest_channel(Vec2::new(u, v), 1, wrap);
                    assert_eq!(green, expected.y, "{wrap:?} channel at ({u}, {v})");
                }
            }
        }
    }
}

#[test]
fn bilinear_lookups_wrap_each_of_the_four_texels() {
    let t = index_image();
    for mode in MODES {
        let wrap = TextureWrap::both(mode);
        for k in -8i64..=12 {
            // At a texel centre: that texel, folded.
            let centre = Vec2::new((k as f32 + 0.5) / 4.0, (k as f32 + 0.5) / 3.0);
            let expected = Vec3::new(folded(mode, k, 4), folded(mode, k, 3), 0.0);
            assert_near(t.lookup(centre, wrap), expected);
            // On a texel boundary (halfway between centres k − 1 and k), a
            // quarter past it: weights ¾ and ¼ of the two folded texels.
            let at = Vec2::new((k as f32 + 0.25) / 4.0, (k as f32 + 0.25) / 3.0);
            let mix = |n| 0.25 * folded(mode, k - 1, n) + 0.75 * folded(mode, k, n);
            let expected = Vec3::new(mix(4), mix(3), 0.0);
            assert_near(t.lookup(at, wrap), expected);
            assert!(
                (t.lookup_channel(at, 0, wrap) - expected.x).abs() < 1e-5,
                "{mode:?} channel at {at}"
            );
        }
    }
    // Clamping makes the slope 0 beyond the edge; mirroring reverses it.
    let beyond = Vec2::new(1.3, 0.5);
    let clamp = t.gradient_channel(beyond, 0, TextureWrap::both(WrapMode::Clamp));
    assert_eq!(clamp.x, 0.0);
    let mirror = t.gradient_channel(beyond, 0, TextureWrap::both(WrapMode::Mirror));
    let repeat = t.gradient_channel(Vec2::new(0.7, 0.5), 0, TextureWrap::REPEAT);
    assert!((mirror.x + repeat.x).abs() < 1e-4, "{mirror} vs {repeat}");
}

/// [`STORED`] as an uncompressed 32-bit TGA, written by hand: BGRA bytes,
/// rows from the bottom (the format's default origin), so the reader's
/// row order is tested as well as its channel order.
fn write_rgba_tga(path: &std::path::Path) {
    let mut bytes = vec![0u8, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 2, 0, 32, 8];
    for row in STORED.chunks(2).rev() {
        for [r, g, b, a] in row {
            bytes.extend([*b, *g, *r, *a]);
        }
    }
    std::fs::write(path, bytes).unwrap();
}

#[test]
fn a_tga_reads_as_the_png_of_the_same_stored_values() {
    // Every 8-bit format goes through the same stored-value path: the TGA
    // must give the PNG's texels, alpha included, in both colour spaces.
    let dir = candela_testkit::TempDir::new("tga-2x2");
    let (png, tga) = (dir.join("known.png"), dir.join("known.tga"));
    write_rgba_png(&png);
    write_rgba_tga(&tga);
    let mut cache = TextureCache::new();
    for space in [ColorSpace::Linear, ColorSpace::Srgb] {
        let (a, b) = (
            cache.get_in(&png, space).unwrap(),
            cache.get_in(&tga, space).unwrap(),
        );
        assert!(b.has_alpha());
        for (i, j) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            assert_eq!(a.texel(i, j), b.texel(i, j), "{space:?} texel ({i}, {j})");
            let uv = Vec2::new((i as f32 + 0.5) / 2.0, (j as f32 + 0.5) / 2.0);
            assert_eq!(
                a.lookup_channel(uv, 3, TextureWrap::REPEAT),
                b.lookup_channel(uv, 3, TextureWrap::REPEAT)
            );
        }
    }
    assert_eq!(native_color_space(&tga), ColorSpace::Srgb);
    assert_eq!(native_color_space(&dir.join("sky.hdr")), ColorSpace::Linear);
}
