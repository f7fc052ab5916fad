//! `candela bench scaling`: displaced spheres of growing triangle count.

use super::timing::cpu_seconds;
use super::{throughput, ScalingArgs};
use anyhow::Result;
use candela_render::accel::{Accel, TraversalStats};
use candela_render::geometry::{Frame, Ray};
use candela_render::shape::{spawn_ray, triangle_surface_point};
use glam::Vec3;
use std::f32::consts::TAU;

/// A cube sphere (each cube face a `k x k` grid pushed onto the sphere,
/// so triangles are evenly sized, unlike a latitude-longitude grid's polar
/// slivers) with about `target` triangles, its radius displaced by a few
/// sine waves so the BVH sees a bumpy, scanned-like surface.
fn displaced_sphere(target: usize) -> Vec<[Vec3; 3]> {
    let k = ((target as f32 / 12.0).sqrt().ceil() as usize).max(1);
    let displace = |p: Vec3| {
        let d = p.normalize();
        let (theta, phi) = (d.y.clamp(-1.0, 1.0).acos(), d.z.atan2(d.x));
        let r = 1.0
            + 0.05 * (7.0 * theta).sin() * (9.0 * phi).sin()
            + 0.02 * (31.0 * theta + 17.0 * phi).sin();
        r * d
    };
    let mut tris = Vec::with_capacity(12 * k * k);
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let point = |i: usize, j: usize| {
                let (u, v) = (
                    2.0 * i as f32 / k as f32 - 1.0,
                    2.0 * j as f32 / k as f32 - 1.0,
                );
                let mut p = [0.0f32; 3];
                p[axis] = sign;
                p[(axis + 1) % 3] = u;
                p[(axis + 2) % 3] = v * sign;
                displace(Vec3::from_array(p))
            };
            for i in 0..k {
                for j in 0..k {
                    let (a, b, c, d) = (
                        point(i, j),
                        point(i + 1, j),
                        point(i + 1, j + 1),
                        point(i, j + 1),
                    );
                    tris.push([a, b, c]);
                    tris.push([a, c, d]);
                }
            }
        }
    }
    tris
}

/// Tiny deterministic generator for ray sampling.
struct Rng(u64);
impl Rng {
    fn f32(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// Camera rays from (0, 0, 3) over a square field of view covering the sphere.
fn primary_rays(n: usize) -> Vec<Ray> {
    let side = (n as f32).sqrt().ceil() as usize;
    (0..side * side)
        .map(|k| {
            let (x, y) = (
                (k % side) as f32 / side as f32 - 0.5,
                (k / side) as f32 / side as f32 - 0.5,
            );
            Ray::new(
                Vec3::new(0.0, 0.0, 3.0),
                Vec3::new(0.9 * x, 0.9 * y, -1.0).normalize(),
            )
        })
        .collect()
}

/// Cosine-distributed rays leaving random points on random triangles.
fn diffuse_rays(tris: &[[Vec3; 3]], n: usize) -> Vec<Ray> {
    let mut rng = Rng(7);
    (0..n)
        .map(|_| {
            let t = &tris[(rng.f32() * tris.len() as f32) as usize % tris.len()];
            let (mut b1, mut b2) = (rng.f32(), rng.f32());
            if b1 + b2 > 1.0 {
                (b1, b2) = (1.0 - b1, 1.0 - b2);
            }
            let mut sp = triangle_surface_point(t, b1, b2);
            if sp.n.dot(sp.p) < 0.0 {
                sp.n = -sp.n;
            }
            let (r, phi) = (rng.f32().sqrt(), TAU * rng.f32());
            let local = Vec3::new(r * phi.cos(), r * phi.sin(), (1.0 - r * r).max(0.0).sqrt());
            let f = Frame::from_normal(sp.n);
            spawn_ray(&sp, f.x * local.x + f.y * local.y + f.z * local.z)
        })
        .collect()
}

/// Prints one row per size.
pub fn run(args: &ScalingArgs) -> Result<()> {
    println!("triangles | build 1 thread ms | build 2 threads ms (CPU ms) | BVH B/tri | total B/tri | depth | primary closest | primary any | diffuse closest | diffuse any (Mrays/s, 1 thread, per CPU-second) | nodes/tests per ray primary, diffuse");
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    let two = rayon::ThreadPoolBuilder::new().num_threads(2).build()?;
    for &size in &args.sizes {
        let tris = displaced_sphere(size);
        let b1 = one
            .install(|| Accel::build_with_layout(&tris, &[], args.bvh.into(), args.layout.into()))
            .info()
            .build_seconds;
        let cpu0 = cpu_seconds();
        let accel = two
            .install(|| Accel::build_with_layout(&tris, &[], args.bvh.into(), args.layout.into()));
        let build_cpu = cpu0.zip(cpu_seconds()).map_or(f64::NAN, |(a, b)| b - a);
        let info = accel.info();
        let n = tris.len() as f64;
        let mut rates = Vec::new();
        let mut per_ray = Vec::new();
        for rays in [primary_rays(args.rays), diffuse_rays(&tris, args.rays)] {
            let mut stats = TraversalStats::default();
            for r in &rays {
                accel.intersect_counted(r, &mut stats);
            }
            let n_rays = rays.len().max(1) as f64;
            per_ray.push(format!(
                "{:.0}/{:.0}",
                stats.nodes_visited as f64 / n_rays,
                stats.prims_tested as f64 / n_rays
            ));
            for any in [false, true] {
                let (m, _) = throughput(&accel, &rays, 1, any, 0.5)?;
                rates.push(m.cpu_rate().unwrap_or(m.wall_rate()));
            }
        }
        println!(
            "{} | {:.0} | {:.0} ({:.0}) | {:.1} | {:.1} | {} | {:.2} | {:.2} | {:.2} | {:.2} | {} {}",
            tris.len(),
            b1 * 1e3,
            info.build_seconds * 1e3,
            build_cpu * 1e3,
            info.bvh_bytes as f64 / n,
            info.total_bytes as f64 / n,
            info.depth,
            rates[0],
            rates[1],
            rates[2],
            rates[3],
            per_ray[0],
            per_ray[1]
        );
    }
    Ok(())
}
