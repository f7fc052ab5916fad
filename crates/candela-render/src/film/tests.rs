use super::*;

#[test]
fn merging_sums_equals_adding_all_samples_to_one_pixel() {
    let samples = [
        Vec3::new(1.0, 2.0, 3.0),
        Vec3::new(0.5, 0.0, 0.25),
        Vec3::new(4.0, 4.0, 4.0),
    ];
    let mut all = PixelSums::default();
    samples.iter().for_each(|&s| all.add_sample(s));
    let mut a = PixelSums::default();
    a.add_sample(samples[0]);
    let mut b = PixelSums::default();
    b.add_sample(samples[1]);
    b.add_sample(samples[2]);
    a.merge(&b);
    assert_eq!(a.count, 3);
    assert!((a.radiance - all.radiance).length() < 1e-12);
    assert!((a.lum_sq - all.lum_sq).abs() < 1e-12);
    assert!((a.radiance_sq - all.radiance_sq).length() < 1e-12);
    let mean = a.mean();
    assert!((mean - Vec3::new(5.5, 6.0, 7.25) / 3.0).length() < 1e-6);
}

#[test]
fn empty_pixel_resolves_to_black() {
    assert_eq!(PixelSums::default().mean(), Vec3::ZERO);
    assert_eq!(PixelSums::default().mean_albedo(), Vec3::ZERO);
    assert_eq!(PixelSums::default().std_error(), Vec3::ZERO);
    assert!((luminance(Vec3::ONE) - 1.0).abs() < 1e-6);
}

#[test]
fn aovs_average_and_invalid_samples_count_as_black() {
    let mut p = PixelSums::default();
    let s = SampleValue {
        radiance: Vec3::new(2.0, 2.0, 2.0),
        albedo: Vec3::new(0.5, 0.25, 1.0),
        normal: Vec3::Y,
        ..SampleValue::default()
    };
    p.add(&s);
    p.add_invalid(&SampleValue {
        radiance: Vec3::NAN,
        ..s
    });
    assert_eq!(p.count, 2);
    assert_eq!(p.mean(), Vec3::ONE);
    assert_eq!(p.mean_albedo(), s.albedo);
    assert_eq!(p.mean_normal(), Vec3::Y);
}

#[test]
fn depth_averages_over_hits_and_cost_over_all_samples() {
    let work = |nodes, prims| candela_bvh::TraversalStats {
        nodes_visited: nodes,
        prims_tested: prims,
    };
    let mut p = PixelSums::default();
    assert_eq!(p.mean_depth(), f32::INFINITY);
    assert_eq!(p.mean_cost(CostMeasure::Total), 0.0);
    let hit = |depth, cost| SampleValue {
        depth,
        cost,
        ..SampleValue::default()
    };
    p.add(&hit(2.0, work(10, 4)));
    p.add(&hit(f32::INFINITY, work(3, 0))); // escaped: no depth, but work
    p.add_invalid(&hit(4.0, work(20, 8)));
    assert_eq!((p.count, p.depth_count), (3, 2));
    assert_eq!(p.mean_depth(), 3.0);
    assert_eq!(p.mean_cost(CostMeasure::Nodes), 11.0);
    assert_eq!(p.mean_cost(CostMeasure::PrimTests), 4.0);
    assert_eq!(p.mean_cost(CostMeasure::Total), 15.0);
    // Merging adds the sums: two copies have the same means.
    let mut twice = p;
    twice.merge(&p);
    assert_eq!(
        (twice.nodes, twice.prim_tests, twice.depth_count),
        (66, 24, 4)
    );
    assert_eq!(twice.mean_depth(), 3.0);
    let mut film = Film::new(2, 1);
    film.pixels[0] = p;
    assert_eq!(film.depth().values(), &[3.0, f32::INFINITY]);
    assert_eq!(film.cost(CostMeasure::Total).values(), &[15.0, 0.0]);
}

#[test]
fn std_error_matches_the_textbook_formula() {
    // Samples 1, 2, 3, 4 in every channel: variance 5/3, se = sqrt(5/12).
    let mut p = PixelSums::default();
    for v in [1.0, 2.0, 3.0, 4.0] {
        p.add_sample(Vec3::splat(v));
    }
    let expected = (5.0f32 / 12.0).sqrt();
    assert!((p.std_error() - Vec3::splat(expected)).abs().max_element() < 1e-6);
}

#[test]
fn films_of_different_sizes_do_not_merge() {
    let mut a = Film::new(4, 3);
    assert!(a.merge(&Film::new(3, 4)).is_err());
    let mut b = Film::new(4, 3);
    b.pixels[5].add_sample(Vec3::ONE);
    assert!(a.merge(&b).is_ok());
    assert_eq!(a.pixel(1, 1).count, 1);
}

#[test]
fn sample_spread_over_a_rect() {
    let mut f = Film::new(4, 4);
    for (i, p) in f.pixels.iter_mut().enumerate() {
        for _ in 0..i {
            p.add_sample(Vec3::ONE);
        }
    }
    let s = f.sample_spread(PixelRect::new(1, 1, 2, 2));
    assert_eq!((s.min, s.max), (5, 10));
    assert!((s.mean - 7.5).abs() < 1e-12);
    assert_eq!(
        f.sample_spread(PixelRect::new(9, 9, 2, 2)),
        SampleSpread::default()
    );
}
