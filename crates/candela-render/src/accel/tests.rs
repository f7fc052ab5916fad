//! The accelerated queries against brute force over every primitive, for
//! every build strategy, on seeded random scenes and degenerate inputs.

use super::*;
use crate::shape::intersect_sphere;

use candela_testkit::SplitMix64 as Rng;

/// Closest hit by testing every primitive: (t, primitive).
fn brute(tris: &[[Vec3; 3]], spheres: &[(Vec3, f32)], ray: &Ray) -> Option<(f32, PrimRef)> {
    let tr = TriangleRay::new(ray.origin, ray.dir);
    let mut best: Option<(f32, PrimRef)> = None;
    let mut t_max = ray.t_max;
    let ts = tris
        .iter()
        .map(|t| intersect_triangle(&tr, t, t_max).map(|h| h.t))
        .collect::<Vec<_>>();
    for (i, t) in ts.into_iter().enumerate() {
        if let Some(t) = t.filter(|&t| t < t_max) {
            t_max = t;
            best = Some((t, PrimRef::triangle(i as u32)));
        }
    }
    for (j, &(c, r)) in spheres.iter().enumerate() {
        if let Some(t) = intersect_sphere(ray.origin, ray.dir, c, r, t_max) {
            t_max = t;
            best = Some((t, PrimRef::sphere(j as u32)));
        }
    }
    best
}

/// Distance along `ray` to triangle `v` in f64 (Möller and Trumbore 1997),
/// the reference where f32 distances are only known to about 1e-2.
fn exact_triangle_t(ray: &Ray, v: &[Vec3; 3]) -> Option<f64> {
    let (o, d) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
    let [a, b, c] = v.map(|p| p.as_dvec3());
    let (e1, e2) = (b - a, c - a);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 {
        return None;
    }
    let s = o - a;
    let q = s.cross(e1);
    let (u, w) = (s.dot(p) / det, d.dot(q) / det);
    (u >= 0.0 && w >= 0.0 && u + w <= 1.0).then(|| e2.dot(q) / det)
}

/// `clip` also tests finite `t_max`; off for scenes whose primitives are so
/// large that their f32 hit distance is only known to about 1e-2 (then a hit
/// just before `t_max` may truly lie beyond it, and the BVH rightly prunes it).
fn check(tris: &[[Vec3; 3]], spheres: &[(Vec3, f32)], rng: &mut Rng, label: &str, clip: bool) {
    let layouts = [Layout::Binary, Layout::Wide4, Layout::Wide8];
    let strategies = [
        BuildStrategy::Sah,
        BuildStrategy::Median,
        BuildStrategy::None,
    ];
    for (strategy, layout) in strategies.into_iter().flat_map(|s| layouts.map(|l| (s, l))) {
        let accel = Accel::build_with_layout(tris, spheres, strategy, layout);
        let mut boxes: Vec<Aabb> = tris.iter().map(|t| Aabb::from_points(t)).collect();
        boxes.extend(
            spheres
                .iter()
                .map(|&(c, r)| Aabb::new(c - Vec3::splat(r), c + Vec3::splat(r))),
        );
        accel
            .validate(&boxes)
            .unwrap_or_else(|e| panic!("{label} {strategy:?} {layout:?}: {e}"));
        let mut stats = TraversalStats::default();
        let mut hits = 0;
        for k in 0..500 {
            let o = rng.vec(-12.0, 12.0);
            let target = rng.vec(-8.0, 8.0);
            let mut ray = Ray::new(o, (target - o).normalize());
            if clip && k % 4 == 0 {
                ray.t_max = rng.f32() * 15.0;
            }
            let want = brute(tris, spheres, &ray);
            let got = accel.intersect_counted(&ray, &mut stats);
            hits += got.is_some() as u64;
            // Equal distances; ids equal unless two primitives tie exactly.
            // Two triangles nearer each other than the f32 error of a huge
            // one's distance may be ordered either way by f32 tests: then
            // the accelerator's hit must be the nearer in f64.
            if got.map(|h| h.t) != want.map(|w| w.0) {
                let exact = |p: PrimRef| match p.kind() {
                    PrimKind::Triangle => exact_triangle_t(&ray, &tris[p.index() as usize]),
                    PrimKind::Sphere => None,
                };
                let (g, w) = (
                    got.and_then(|h| exact(h.prim)),
                    want.and_then(|w| exact(w.1)),
                );
                assert!(
                    matches!((g, w), (Some(g), Some(w)) if g <= w),
                    "{label} {strategy:?} {layout:?} ray {k}: {ray:?} {want:?}, got {got:?} \
                     (f64 distances {g:?} and {w:?})"
                );
            }
            if let (Some(g), Some(w)) = (got, want) {
                if g.prim != w.1 {
                    // A tie: the reported primitive alone gives the same distance.
                    let i = g.prim.index() as usize;
                    let alone = match g.prim.kind() {
                        PrimKind::Triangle => brute(&tris[i..=i], &[], &ray),
                        PrimKind::Sphere => brute(&[], &spheres[i..=i], &ray),
                    };
                    assert_eq!(
                        alone.map(|a| a.0),
                        Some(g.t),
                        "{label} {strategy:?} {layout:?} ray {k}: id"
                    );
                }
            }
            assert_eq!(
                accel.occluded(&ray),
                want.is_some(),
                "{label} {strategy:?} {layout:?} ray {k} occluded"
            );
        }
        assert!(stats.prims_tested >= hits && stats.nodes_visited >= hits.min(1));
    }
}

fn random_triangles(rng: &mut Rng, n: usize, size: f32) -> Vec<[Vec3; 3]> {
    (0..n)
        .map(|_| {
            let c = rng.vec(-8.0, 8.0);
            [
                c + rng.vec(-size, size),
                c + rng.vec(-size, size),
                c + rng.vec(-size, size),
            ]
        })
        .collect()
}

#[test]
fn random_scenes_match_brute_force() {
    let mut rng = Rng(31);
    for (nt, ns) in [(1, 0), (0, 1), (5, 3), (100, 10), (2000, 20), (6000, 0)] {
        let tris = random_triangles(&mut rng, nt, 1.0);
        let spheres: Vec<(Vec3, f32)> = (0..ns)
            .map(|_| (rng.vec(-8.0, 8.0), rng.f32() * 2.0))
            .collect();
        check(
            &tris,
            &spheres,
            &mut rng,
            &format!("{nt} tris, {ns} spheres"),
            true,
        );
    }
}

#[test]
fn degenerate_scenes_match_brute_force() {
    let mut rng = Rng(32);
    check(&[], &[], &mut rng, "empty", true);
    let same = vec![[Vec3::ZERO, Vec3::X * 3.0, Vec3::Y * 3.0]; 50];
    check(&same, &[], &mut rng, "identical triangles", true);
    // Axis-aligned flat triangles (zero-thickness boxes) and a huge one.
    let mut flat: Vec<[Vec3; 3]> = (0..200)
        .map(|_| {
            let c = rng.vec(-8.0, 8.0);
            [
                c,
                c + Vec3::new(rng.f32(), 0.0, 0.0),
                c + Vec3::new(0.0, rng.f32(), 0.0),
            ]
        })
        .collect();
    check(&flat, &[], &mut rng, "flat", true);
    flat.push([
        Vec3::new(-1e6, -1e6, 0.5),
        Vec3::new(1e6, -1e6, 0.5),
        Vec3::new(0.0, 1e6, 0.5),
    ]);
    check(
        &flat,
        &[(Vec3::ZERO, 1e4)],
        &mut rng,
        "flat and huge",
        false,
    );
    let nested: Vec<(Vec3, f32)> = (1..30).map(|i| (Vec3::ONE, i as f32 * 0.3)).collect();
    check(&[], &nested, &mut rng, "concentric spheres", true);
}

/// The 8-wide tree's AVX2 path (the AVX2 node test, leaves of two blocks
/// on eight lanes) and its portable path (SSE halves, one block at a time)
/// give the same hits bit for bit, and the same statistics, on the same
/// rays: clustered triangles (leaves of 5-8, several leaves entered per
/// node), spheres, rays leaving a triangle's surface (the near-hit test)
/// and finite `t_max`.
#[test]
fn avx2_path_matches_portable_path() {
    let avx2_cpu = if candela_bvh::has_avx2() {
        Ok(())
    } else {
        Err("this CPU has no AVX2 and FMA")
    };
    if candela_testkit::optional_dependency(avx2_cpu, "CANDELA_REQUIRE_AVX2").is_none() {
        return;
    }
    let mut rng = Rng(33);
    let mut tris = Vec::new();
    for _ in 0..60 {
        let c = rng.vec(-6.0, 6.0);
        for _ in 0..40 {
            tris.push([0; 3].map(|_| c + rng.vec(-0.5, 0.5)));
        }
    }
    let spheres: Vec<(Vec3, f32)> = (0..8)
        .map(|_| (rng.vec(-6.0, 6.0), 0.2 + rng.f32()))
        .collect();
    let avx2 = Accel::build_with_layout(&tris, &spheres, BuildStrategy::Sah, Layout::Wide8);
    let mut portable = avx2.clone();
    portable.set_avx2(false);
    assert!(
        avx2.uses_avx2() && !portable.uses_avx2(),
        "the two paths differ"
    );
    let (mut hits, mut from_surface) = (0, 0);
    for k in 0..20_000 {
        let mut ray = if k % 4 == 0 {
            let [a, b, c] = tris[(rng.f32() * tris.len() as f32) as usize % tris.len()];
            let (u, v) = (rng.f32() * 0.5, rng.f32() * 0.5);
            Ray::new(a + u * (b - a) + v * (c - a), rng.dir())
        } else {
            let o = rng.vec(-12.0, 12.0);
            Ray::new(o, (rng.vec(-3.0, 3.0) - o).normalize())
        };
        if k % 3 == 0 {
            ray.t_max = rng.f32() * 20.0;
        }
        let (mut s_avx2, mut s_portable) = (TraversalStats::default(), TraversalStats::default());
        let got = avx2.intersect_counted(&ray, &mut s_avx2);
        let want = portable.intersect_counted(&ray, &mut s_portable);
        let bits =
            |h: Option<Hit>| h.map(|h| (h.t.to_bits(), h.prim, h.b1.to_bits(), h.b2.to_bits()));
        assert_eq!(bits(got), bits(want), "ray {k}: {ray:?}");
        assert_eq!(s_avx2, s_portable, "ray {k}: statistics");
        assert_eq!(
            avx2.occluded(&ray),
            portable.occluded(&ray),
            "ray {k}: occluded"
        );
        hits += usize::from(got.is_some());
        from_surface += usize::from(k % 4 == 0 && got.is_some_and(|h| h.t < 1e-3));
    }
    assert!(hits > 5_000 && from_surface > 50, "{hits} {from_surface}");
}

#[test]
fn indexed_build_reports_bad_indices() {
    let p = [Vec3::ZERO, Vec3::X, Vec3::Y];
    let err =
        Accel::build_indexed(&p, &[[0, 1, 2], [0, 1, 7]], &[], BuildStrategy::Sah).unwrap_err();
    assert_eq!(
        err,
        AccelError::IndexOutOfRange {
            triangle: 1,
            index: 7,
            vertices: 3
        }
    );
    let ok = Accel::build_indexed(&p, &[[0, 1, 2]], &[], BuildStrategy::Sah).unwrap();
    let hit = ok
        .intersect(&Ray::new(Vec3::new(0.25, 0.25, 1.0), -Vec3::Z))
        .unwrap();
    assert_eq!(
        (hit.t, hit.prim, hit.b1, hit.b2),
        (1.0, PrimRef::triangle(0), 0.25, 0.25)
    );
}
