//! Tests of the reconstruction filters: sampling against the tabulated
//! density (chi-square), the weights' normalisation, the spelling.

use super::{FilmFilter, PixelFilter};
use crate::sampling::chi2::Chi2Test;
use crate::sampling::{Sampler, SamplerKind};
use glam::{Vec2, Vec3};

/// Every filter other than the one-pixel box (which takes the old path),
/// with parameters off their defaults where they have any.
fn filters() -> Vec<PixelFilter> {
    vec![
        PixelFilter::Box { radius: 1.0 },
        PixelFilter::Tent { radius: 1.0 },
        PixelFilter::Tent { radius: 1.5 },
        PixelFilter::MITSUBA_DEFAULT,
        PixelFilter::Gaussian {
            stddev: 0.5,
            radius: 1.5,
        },
        PixelFilter::Mitchell {
            b: 1.0 / 3.0,
            c: 1.0 / 3.0,
        },
        PixelFilter::CatmullRom,
        PixelFilter::Lanczos { lobes: 2 },
        PixelFilter::Lanczos { lobes: 3 },
        PixelFilter::BlackmanHarris { width: 1.5 },
    ]
}

/// Table cells per axis, as `filter_table.rs` makes them (32 per pixel).
fn cells(spec: &PixelFilter) -> usize {
    (2.0 * spec.radius() * 32.0).ceil() as usize
}

/// The density the samples should have, written from the filter's formula
/// alone: per axis `|f₁|` at the centre of the cell holding `x`, over its
/// sum times the cell width.
fn reference_pdf_1d(spec: &PixelFilter) -> impl Fn(f32) -> f32 {
    let r = spec.radius();
    let n = cells(spec);
    let cw = 2.0 * r / n as f32;
    let mid = move |i: usize| -r + (i as f32 + 0.5) * cw;
    let spec = *spec;
    let total: f32 = (0..n).map(|i| spec.eval_1d(mid(i)).abs()).sum::<f32>() * cw;
    move |x: f32| {
        if !(-r..r).contains(&x) {
            return 0.0;
        }
        let i = (((x + r) / cw) as usize).min(n - 1);
        spec.eval_1d(mid(i)).abs() / total
    }
}

#[test]
fn samples_follow_the_tabulated_filter() {
    for spec in filters() {
        let filter = FilmFilter::new(spec);
        let r = spec.radius();
        // Histogram bins of four table cells, one quadrature panel per
        // cell: the piecewise-constant density is integrated exactly.
        let bins = cells(&spec) / 4;
        let pdf_1d = reference_pdf_1d(&spec);
        Chi2Test::plane(&format!("filter {spec}"), Vec2::splat(-r), Vec2::splat(r))
            .with_resolution(bins, bins)
            .with_quadrature_panels(4)
            .run(
                |u| {
                    let (offset, _) = filter.sample(Vec2::new(u[0], u[1]));
                    Some((offset.extend(0.0), filter.pdf(offset)))
                },
                |p: Vec3| pdf_1d(p.x) * pdf_1d(p.y),
            )
            .assert_ok();
    }
}

/// `mean ± 5 σ/√n` holds `expected`, with `σ²` the variance of one value.
fn assert_mean(name: &str, values: &[f64], expected: f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    let bound = 5.0 * (var / n).sqrt() + 1e-6;
    eprintln!("{name}: mean {mean:.6}, expected {expected:.6}, bound {bound:.2e}");
    assert!(
        (mean - expected).abs() <= bound,
        "{name}: mean {mean} differs from {expected} by more than {bound}"
    );
}

#[test]
fn weights_average_to_one_and_weigh_like_the_filter() {
    const N: u32 = 400_000;
    for spec in filters() {
        let filter = FilmFilter::new(spec);
        let mut sampler = Sampler::new(SamplerKind::Independent, 7);
        let mut weights = Vec::with_capacity(N as usize);
        let mut beyond_one = Vec::with_capacity(N as usize);
        for i in 0..N {
            sampler.start_pixel_sample(0, 0, i);
            let (offset, w) = filter.sample(sampler.next_2d());
            weights.push(f64::from(w));
            beyond_one.push(if offset.x >= 1.0 { f64::from(w) } else { 0.0 });
        }
        // E[w] = ∫ f_n = 1 (exactly 1 for every sample of a non-negative
        // filter, whose variance is then 0).
        assert_mean(&format!("{spec}: E[w]"), &weights, 1.0);
        // E[w 1(x ≥ 1)] = ∫_{x ≥ 1} f_n, from the formula at the cell
        // centres (x = 1 is a cell boundary: 32 cells per pixel).
        let r = spec.radius();
        let n = cells(&spec);
        let cw = 2.0 * r / n as f32;
        let mids = (0..n).map(|i| -r + (i as f32 + 0.5) * cw);
        let total: f64 = mids.clone().map(|x| f64::from(spec.eval_1d(x))).sum();
        let part: f64 = mids
            .filter(|&x| x >= 1.0)
            .map(|x| f64::from(spec.eval_1d(x)))
            .sum();
        assert_mean(&format!("{spec}: E[w; x >= 1]"), &beyond_one, part / total);
    }
}

#[test]
fn negative_lobes_give_negative_weights_of_the_right_size() {
    let filter = FilmFilter::new(PixelFilter::CatmullRom);
    let mut sampler = Sampler::new(SamplerKind::Independent, 3);
    let (mut negative, mut positive) = (0, 0);
    for i in 0..10_000 {
        sampler.start_pixel_sample(0, 0, i);
        let (offset, w) = filter.sample(sampler.next_2d());
        let sign =
            PixelFilter::CatmullRom.eval_1d(offset.x) * PixelFilter::CatmullRom.eval_1d(offset.y);
        assert!(w * sign >= 0.0, "weight {w} at {offset}");
        if w < 0.0 {
            negative += 1;
        } else {
            positive += 1;
        }
        assert!(w.abs() > 1.0, "|w| = (∫|f|/∫f)² > 1 with negative lobes");
    }
    assert!(negative > 0 && positive > negative);
}

#[test]
fn splats_reach_every_pixel_the_filter_covers() {
    let filter = FilmFilter::new(PixelFilter::MITSUBA_DEFAULT);
    let film = Vec2::new(10.3, 20.9);
    let hits: Vec<(u32, u32, f32)> = filter.pixels_covering(film, 64, 64).collect();
    // Radius 2: pixel centres within 2 of 10.3 are 8.5 .. 11.5 (x = 8..=11),
    // of 20.9 are 19.5 .. 22.5 (y = 19..=22).
    assert_eq!(hits.len(), 16, "{hits:?}");
    for &(x, y, w) in &hits {
        assert!((8..=11).contains(&x) && (19..=22).contains(&y));
        let expected = filter.eval(film - Vec2::new(x as f32 + 0.5, y as f32 + 0.5));
        assert_eq!(w, expected);
    }
    // At the corner of the frame only the pixels inside it receive.
    let corner: Vec<_> = filter
        .pixels_covering(Vec2::new(0.2, 0.2), 64, 64)
        .collect();
    assert_eq!(corner.len(), 4, "{corner:?}");
    // The one-pixel box: its own pixel with weight 1.
    let b = FilmFilter::default();
    let one: Vec<_> = b.pixels_covering(film, 64, 64).collect();
    assert_eq!(one, vec![(10, 20, 1.0)]);
}

#[test]
fn the_margin_is_how_far_edge_samples_reach() {
    assert_eq!(FilmFilter::default().margin(), 0.0);
    assert_eq!(FilmFilter::new(PixelFilter::MITSUBA_DEFAULT).margin(), 1.5);
    assert_eq!(
        FilmFilter::new(PixelFilter::Tent { radius: 1.0 }).margin(),
        0.5
    );
    let f = FilmFilter::new(PixelFilter::MITSUBA_DEFAULT);
    for u in [Vec2::ZERO, Vec2::splat(0.999_999)] {
        let (offset, _) = f.sample(u);
        assert!(offset.abs().max_element() <= 2.0, "{offset}");
    }
}

#[test]
fn filters_are_spelled_and_checked() {
    for spec in filters().into_iter().chain([PixelFilter::default()]) {
        let text = spec.to_string();
        assert_eq!(text.parse::<PixelFilter>(), Ok(spec), "{text}");
    }
    let parse = |t: &str| t.parse::<PixelFilter>();
    assert_eq!(parse("box"), Ok(PixelFilter::default()));
    assert_eq!(
        parse("gaussian:stddev=0.3"),
        Ok(PixelFilter::Gaussian {
            stddev: 0.3,
            radius: 4.0 * 0.3
        })
    );
    assert_eq!(
        parse("Gaussian: radius=1.5"),
        Ok(PixelFilter::Gaussian {
            stddev: 0.5,
            radius: 1.5
        })
    );
    assert_eq!(parse("catmullrom"), Ok(PixelFilter::CatmullRom));
    assert_eq!(
        parse("lanczos:lobes=2"),
        Ok(PixelFilter::Lanczos { lobes: 2 })
    );
    for (bad, says) in [
        ("sinc", "unknown filter \"sinc\""),
        (
            "gaussian:sigma=1",
            "unknown parameter \"sigma\" (expected stddev, radius)",
        ),
        ("tent:radius=wide", "radius \"wide\" is not a number"),
        ("tent:radius=0", "the radius must be in (0, 8]"),
        ("tent:radius=20", "the radius must be in (0, 8]"),
        ("gaussian:stddev=-1,radius=1", "stddev must be > 0"),
        ("lanczos:lobes=2.5", "lobes 2.5 must be a whole number"),
        ("catmull-rom:b=1", "unknown parameter \"b\" (expected none)"),
        ("tent:1", "\"1\" is not key=value"),
    ] {
        let err = parse(bad).expect_err(bad);
        assert!(err.contains(says), "{bad}: {err}");
        assert!(!err.contains('\n'), "one line: {err}");
    }
}

#[test]
fn the_filters_match_mitsubas_values() {
    // Values of Mitsuba 3's filters (`eval` of its plugins, scalar_rgb) at
    // x = 0, 0.5, 1.5: its defaults and formulas are the same. Mitsuba
    // evaluates the Gaussian's exp by a fast approximation (4·10⁻⁴ off at
    // 0 against the exact formula), hence the tolerance.
    let cases = [
        (PixelFilter::Tent { radius: 1.0 }, [1.0, 0.5, 0.0]),
        (
            PixelFilter::MITSUBA_DEFAULT,
            [0.999_247, 0.606_423, 0.010_758],
        ),
        (
            PixelFilter::Mitchell {
                b: 1.0 / 3.0,
                c: 1.0 / 3.0,
            },
            [0.888_889, 0.534_722, -0.034_722],
        ),
        (PixelFilter::CatmullRom, [1.0, 0.5625, -0.0625]),
        (
            PixelFilter::Lanczos { lobes: 3 },
            [1.0, 0.607_927, -0.135_095],
        ),
    ];
    for (spec, values) in cases {
        for (x, v) in [0.0, 0.5, 1.5].into_iter().zip(values) {
            let got = spec.eval_1d(x);
            assert!((got - v).abs() < 5e-4, "{spec} at {x}: {got} vs {v}");
        }
    }
    assert!((PixelFilter::BlackmanHarris { width: 1.5 }.eval_1d(0.0) - 1.0).abs() < 1e-6);
}
