//! Bilinear lookups checked exactly on a tiny generated texture, and the
//! cache's load-once, report-once behaviour.

use super::*;
use candela_image::{write_exr, ExrLayers};
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
        assert_close(t.lookup(Vec2::new(u, 0.25)), v3(BOTTOM[i]));
        assert_close(t.lookup(Vec2::new(u, 0.75)), v3(TOP[i]));
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
    assert_close(t.lookup(uv), 0.25 * bottom + 0.75 * top);
    // The image's centre: on column 1's centre, half-way between the rows.
    assert_close(
        t.lookup(Vec2::new(0.5, 0.5)),
        0.5 * (v3(BOTTOM[1]) + v3(TOP[1])),
    );
}

#[test]
fn addressing_wraps_around() {
    let t = ImageTexture::from_image(&image()).unwrap();
    // u = 0 lies half-way between the last column and the first.
    assert_close(
        t.lookup(Vec2::new(0.0, 0.25)),
        0.5 * (v3(BOTTOM[2]) + v3(BOTTOM[0])),
    );
    // v = 0 lies half-way between the bottom row and (wrapped) the top.
    let u1 = 1.5 / 3.0;
    assert_close(
        t.lookup(Vec2::new(u1, 0.0)),
        0.5 * (v3(BOTTOM[1]) + v3(TOP[1])),
    );
    // Whole periods in either direction change nothing.
    for uv in [Vec2::new(0.1, 0.3), Vec2::new(0.77, 0.91)] {
        for shift in [Vec2::new(1.0, 0.0), Vec2::new(-2.0, 3.0)] {
            let a = t.lookup(uv);
            let b = t.lookup(uv + shift);
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
    let odd = dir.join("texture.tga");
    let mut cache = TextureCache::new();
    let a = cache.get(&good).expect("the EXR loads");
    let b = cache.get(&good).expect("and again");
    assert!(Arc::ptr_eq(&a, &b), "read once, shared");
    assert_close(a.lookup(Vec2::new(0.5 / 3.0, 0.75)), v3(TOP[0]));
    assert!(cache.get(&missing).is_none());
    assert!(cache.get(&missing).is_none());
    assert!(cache.get(&odd).is_none());
    let problems = cache.into_problems();
    assert_eq!(problems.len(), 2, "{problems:?}");
    assert!(problems[0].contains("missing.png"), "{problems:?}");
    assert!(problems[1].contains("unknown image format"), "{problems:?}");
    std::fs::remove_dir_all(&dir).ok();
}
