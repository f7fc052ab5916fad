//! Round trips and channel naming of the EXR writer and reader.

use super::*;
use candela_testkit::{SplitMix64, TempDir};

/// Random bit patterns, so the round trip checks every mantissa bit,
/// plus the special values an EXR must carry through.
fn awkward_image(width: usize, height: usize, seed: u64) -> RgbImage {
    let mut rng = SplitMix64::new(seed);
    let mut image = RgbImage::from_fn(width, height, |_, _| {
        [0; 3].map(|_| f32::from_bits(rng.next_u64() as u32 & 0x7f7f_ffff))
    })
    .unwrap();
    let specials = [f32::INFINITY, -0.0, f32::MIN_POSITIVE / 8.0, -1.5e-30];
    image.pixels_mut()[0] = [specials[0], specials[1], specials[2]];
    image.pixels_mut()[1] = [specials[3], 65504.0, 1.0e30];
    image
}

fn full_layers() -> ExrLayers {
    let (w, h) = (19, 7);
    let counts = (0..w * h).map(|i| (i * 3 % 64) as f32).collect();
    let error = GrayImage::from_values(w, h, vec![0.25; w * h]).unwrap();
    ExrLayers {
        beauty: awkward_image(w, h, 1),
        albedo: Some(awkward_image(w, h, 2)),
        normal: Some(awkward_image(w, h, 3)),
        sample_count: Some(GrayImage::from_values(w, h, counts).unwrap()),
        extra: vec![
            ("stderr".into(), LayerData::Rgb(awkward_image(w, h, 4))),
            ("depth".into(), LayerData::Gray(error)),
        ],
        info: RenderInfo::default(),
    }
}

fn bits(image: &RgbImage) -> Vec<u32> {
    image
        .pixels()
        .iter()
        .flat_map(|p| p.map(f32::to_bits))
        .collect()
}

#[test]
fn round_trip_is_bit_exact() {
    let dir = TempDir::new("exr-rt");
    let path = dir.path().join("all.exr");
    let layers = full_layers();
    write_exr(&path, &layers).unwrap();
    let back = read_exr_layers(&path).unwrap();
    assert_eq!(bits(&back.beauty), bits(&layers.beauty));
    assert_eq!(
        bits(back.albedo.as_ref().unwrap()),
        bits(layers.albedo.as_ref().unwrap())
    );
    assert_eq!(
        bits(back.normal.as_ref().unwrap()),
        bits(layers.normal.as_ref().unwrap())
    );
    assert_eq!(back.sample_count, layers.sample_count);
    // Channels come back sorted by name, so extra layers are compared by name.
    let mut extra = back.extra.clone();
    extra.sort_by(|a, b| a.0.cmp(&b.0));
    assert_eq!(extra[0].0, "depth");
    assert_eq!(extra[0].1, layers.extra[1].1);
    assert_eq!(extra[1].0, "stderr");
    match (&extra[1].1, &layers.extra[0].1) {
        (LayerData::Rgb(a), LayerData::Rgb(b)) => assert_eq!(bits(a), bits(b)),
        other => panic!("stderr layer came back as {other:?}"),
    }
    assert_eq!(bits(&read_exr(&path).unwrap()), bits(&layers.beauty));
}

#[test]
fn every_compression_round_trips_bit_exact() {
    let dir = TempDir::new("exr-compression");
    let layers = full_layers();
    for compression in [
        ExrCompression::None,
        ExrCompression::Rle,
        ExrCompression::Zip,
        ExrCompression::Piz,
    ] {
        let path = dir.path().join(format!("{compression:?}.exr"));
        write_exr_compressed(&path, &layers, compression).unwrap();
        let back = read_exr_layers(&path).unwrap();
        assert_eq!(bits(&back.beauty), bits(&layers.beauty), "{compression:?}");
        assert_eq!(
            bits(back.normal.as_ref().unwrap()),
            bits(layers.normal.as_ref().unwrap()),
            "{compression:?}"
        );
        assert_eq!(back.sample_count, layers.sample_count, "{compression:?}");
        // The file says which compression it holds.
        let meta = exr::meta::MetaData::read_from_file(&path, false).unwrap();
        let expected = compression.encoding().compression;
        assert_eq!(meta.headers[0].compression, expected, "{compression:?}");
    }
    // A flat image compresses: ZIP well below the raw size.
    let flat = ExrLayers::beauty(RgbImage::from_fn(64, 64, |_, _| [0.5, 0.25, 1.0]).unwrap());
    let (raw, zip) = (
        dir.path().join("flat-raw.exr"),
        dir.path().join("flat-zip.exr"),
    );
    write_exr_compressed(&raw, &flat, ExrCompression::None).unwrap();
    write_exr_compressed(&zip, &flat, ExrCompression::Zip).unwrap();
    let size = |p: &std::path::Path| std::fs::metadata(p).unwrap().len();
    assert!(
        size(&zip) * 10 < size(&raw),
        "{} vs {}",
        size(&zip),
        size(&raw)
    );
}

#[test]
fn channel_names_follow_the_documented_convention() {
    let dir = TempDir::new("exr-names");
    let path = dir.path().join("names.exr");
    write_exr(&path, &full_layers()).unwrap();
    let image = exr::prelude::read_first_flat_layer_from_file(&path).unwrap();
    let names: Vec<String> = image
        .layer_data
        .channel_data
        .list
        .iter()
        .map(|c| c.name.to_string())
        .collect();
    let expected = [
        "B", "G", "R", "albedo.B", "albedo.G", "albedo.R", "depth", "normal.B", "normal.G",
        "normal.R", "samples", "stderr.B", "stderr.G", "stderr.R",
    ];
    assert_eq!(names, expected);
}

#[test]
fn nan_is_stored_not_hidden() {
    let dir = TempDir::new("exr-nan");
    let path = dir.path().join("nan.exr");
    let image = RgbImage::from_pixels(1, 1, vec![[f32::NAN, 1.0, 2.0]]).unwrap();
    write_exr(&path, &ExrLayers::beauty(image)).unwrap();
    let back = read_exr(&path).unwrap().pixels()[0];
    assert!(back[0].is_nan());
    assert_eq!([back[1], back[2]], [1.0, 2.0]);
}

#[test]
fn mismatched_and_duplicate_layers_are_rejected_before_writing() {
    let dir = TempDir::new("exr-bad");
    let path = dir.path().join("bad.exr");
    let mut layers = ExrLayers::beauty(RgbImage::new(4, 4).unwrap());
    layers.albedo = Some(RgbImage::new(4, 3).unwrap());
    assert!(matches!(
        write_exr(&path, &layers),
        Err(ImageError::SizeMismatch { .. })
    ));
    layers.albedo = None;
    layers.extra = vec![(
        "samples".into(),
        LayerData::Gray(GrayImage::new(4, 4).unwrap()),
    )];
    layers.sample_count = Some(GrayImage::new(4, 4).unwrap());
    assert!(matches!(
        write_exr(&path, &layers),
        Err(ImageError::InvalidArgument(_))
    ));
    layers.sample_count = None;
    layers.extra[0].0 = "\u{6cd5}\u{7ebf}".into();
    assert!(matches!(
        write_exr(&path, &layers),
        Err(ImageError::InvalidArgument(_))
    ));
    assert!(std::fs::read_dir(dir.path()).unwrap().next().is_none());
}

#[test]
fn reading_a_missing_or_corrupt_file_names_it() {
    let dir = TempDir::new("exr-missing");
    let path = dir.path().join("absent.exr");
    let err = read_exr(&path).unwrap_err().to_string();
    assert!(err.contains("absent.exr"), "{err}");
    let corrupt = dir.path().join("corrupt.exr");
    std::fs::write(&corrupt, [0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0, 1, 2, 3]).unwrap();
    let err = read_exr(&corrupt).unwrap_err();
    assert!(matches!(err, ImageError::Read { .. }));
    assert!(err.to_string().contains("corrupt.exr"));
}

/// Writes an EXR with exactly these channels (half floats, as Mitsuba and
/// Blender often write), each filled with `value(channel index)`.
fn foreign_exr(path: &Path, names: &[&str], value: impl Fn(usize) -> f32) {
    use exr::prelude::f16;
    let (w, h) = (3, 2);
    let channels = names
        .iter()
        .enumerate()
        .map(|(i, name)| {
            let samples = vec![f16::from_f32(value(i)); w * h];
            AnyChannel::new(Text::from(*name), FlatSamples::F16(samples))
        })
        .collect();
    let layer = Layer::new(
        Vec2(w, h),
        LayerAttributes::default(),
        Encoding::UNCOMPRESSED,
        AnyChannels::sort(channels),
    );
    Image::from_layer(layer).write().to_file(path).unwrap();
}

#[test]
fn other_programs_beauty_channels_are_found() {
    let dir = TempDir::new("exr-foreign");
    // Mitsuba 3 / pbrt-v4: bare R, G, B (and A, kept as a scalar layer).
    let plain = dir.path().join("plain.exr");
    foreign_exr(&plain, &["R", "G", "B", "A"], |i| [0.25, 0.5, 0.75, 1.0][i]);
    let layers = read_exr_layers(&plain).unwrap();
    assert_eq!(layers.beauty.pixels()[0], [0.25, 0.5, 0.75]);
    assert!(matches!(layers.layer("A"), Some(LayerData::Gray(_))));
    assert_eq!(layers.info, RenderInfo::default());
    // Blender's multilayer naming: the Combined layer among others.
    let blender = dir.path().join("blender.exr");
    let names = [
        "ViewLayer.Combined.R",
        "ViewLayer.Combined.G",
        "ViewLayer.Combined.B",
        "ViewLayer.Denoising Albedo.R",
        "ViewLayer.Denoising Albedo.G",
        "ViewLayer.Denoising Albedo.B",
    ];
    foreign_exr(&blender, &names, |i| if i < 3 { 2.0 } else { 0.5 });
    assert_eq!(read_exr(&blender).unwrap().pixels()[0], [2.0; 3]);
    // A single prefixed RGB layer, whatever its name.
    let single = dir.path().join("single.exr");
    foreign_exr(
        &single,
        &["image.R", "image.G", "image.B", "depth.Z"],
        |i| i as f32,
    );
    assert_eq!(read_exr(&single).unwrap().pixels()[0], [0.0, 1.0, 2.0]);
    // Two RGB layers with no conventional name: no guess, an error naming the file.
    let ambiguous = dir.path().join("ambiguous.exr");
    foreign_exr(
        &ambiguous,
        &["a.R", "a.G", "a.B", "b.R", "b.G", "b.B"],
        |_| 1.0,
    );
    let err = read_exr(&ambiguous).unwrap_err().to_string();
    assert!(
        err.contains("ambiguous.exr") && err.contains("no R, G, B"),
        "{err}"
    );
}
