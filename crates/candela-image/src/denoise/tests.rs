use super::*;
use crate::metrics::rel_mse;
use candela_testkit::{optional_dependency, SplitMix64, TempDir};

/// CI sets it where it installed `pyoidn`: the tests below then fail
/// instead of skipping when the library cannot be loaded.
const REQUIRE: &str = "CANDELA_REQUIRE_OIDN";

#[test]
fn an_explicit_path_without_the_library_is_a_one_line_error_naming_it() {
    let dir = TempDir::new("oidn-missing");
    let file = dir.join("libOpenImageDenoise.so.2");
    std::fs::write(&file, b"not a library").unwrap();
    let search = locate::Search::Explicit(file.clone().into_os_string(), vec![file.clone()]);
    let err = load_from(search)
        .err()
        .expect("a text file is not a library");
    let text = err.to_string();
    assert!(matches!(err, DenoiseError::Unavailable(_)), "{err:?}");
    assert!(text.starts_with(&format!("{LIB_ENV}={}: cannot load", file.display())));
    assert!(!text.contains('\n'), "{text}");

    let empty = TempDir::new("oidn-empty");
    let search = locate::Search::Explicit(empty.path().as_os_str().to_owned(), vec![]);
    let text = load_from(search).err().unwrap().to_string();
    assert!(
        text.contains("no Open Image Denoise library there"),
        "{text}"
    );
}

#[test]
fn nothing_found_says_how_to_get_it() {
    let search =
        locate::Search::Candidates(vec![PathBuf::from("/nonexistent/libOpenImageDenoise.so.2")]);
    let text = load_from(search).err().unwrap().to_string();
    assert!(text.contains("pip install pyoidn"), "{text}");
    assert!(text.contains(LIB_ENV), "{text}");
    assert!(!text.contains('\n'), "{text}");
}

/// A smooth image (a bright-to-dark ramp times a soft bump) and the same
/// image with independent ±50% multiplicative noise per pixel and channel.
fn ramp_and_noisy(w: usize, h: usize) -> (RgbImage, RgbImage) {
    let clean = RgbImage::from_fn(w, h, |x, y| {
        let (u, v) = (x as f32 / w as f32, y as f32 / h as f32);
        let bump = (-((u - 0.5).powi(2) + (v - 0.5).powi(2)) * 8.0).exp();
        [0.2 + 0.8 * u * bump, 0.3 + 0.5 * v, 0.25 + 0.5 * bump]
    })
    .unwrap();
    let mut rng = SplitMix64::new(7);
    let noisy = RgbImage::from_pixels(
        w,
        h,
        clean
            .pixels()
            .iter()
            .map(|p| p.map(|c| c * (1.0 + rng.range(-0.5, 0.5))))
            .collect(),
    )
    .unwrap();
    (clean, noisy)
}

#[test]
fn denoising_a_noisy_smooth_image_removes_most_of_its_error() {
    let Some(oidn) = optional_dependency(Oidn::load(), REQUIRE) else {
        return;
    };
    let (w, h) = (96, 64);
    let (clean, noisy) = ramp_and_noisy(w, h);
    let albedo = RgbImage::from_fn(w, h, |_, _| [0.5; 3]).unwrap();
    let normal = RgbImage::from_fn(w, h, |_, _| [0.0, 0.0, 1.0]).unwrap();
    let guides = Guides {
        albedo: &albedo,
        normal: &normal,
    };
    let denoised = oidn.denoise(&noisy, Some(guides)).unwrap();
    let before = rel_mse(&noisy, &clean).unwrap();
    let after = rel_mse(&denoised, &clean).unwrap();
    eprintln!("relMSE before {before:.5}, after {after:.5}");
    // The noise alone gives E[relMSE] ≈ Var(U(-½, ½)) = 1/12 (times
    // c²/(c² + ε) ≈ 0.9 here); an unchanged image cannot pass a fifth of it,
    // nor can a black or flat one (relMSE near 1 and 0.2). (OIDN 2.5:
    // 0.077 before, 0.00075 after.)
    assert!(
        before > 0.06,
        "the test image is not noisy enough: {before}"
    );
    assert!(after < before / 10.0, "before {before}, after {after}");
    // Without guides the filter runs too (and also helps).
    let unguided = oidn.denoise(&noisy, None).unwrap();
    assert!(rel_mse(&unguided, &clean).unwrap() < before / 5.0);
}

#[test]
fn guides_of_another_size_are_refused() {
    let Some(oidn) = optional_dependency(Oidn::load(), REQUIRE) else {
        return;
    };
    let (_, noisy) = ramp_and_noisy(8, 6);
    let small = RgbImage::new(4, 6).unwrap();
    let guides = Guides {
        albedo: &small,
        normal: &small,
    };
    let err = oidn.denoise(&noisy, Some(guides)).unwrap_err();
    assert_eq!(
        err,
        DenoiseError::SizeMismatch {
            what: "albedo",
            got: (4, 6),
            want: (8, 6)
        }
    );
}
