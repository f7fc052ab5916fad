//! Four triangles at once: the watertight test of [`super::triangle`] run
//! on SIMD lanes, for the leaves of the 4-wide BVH.
//!
//! Every lane performs exactly the scalar test's operations in the same
//! order, so results (and watertightness) are bit-identical to
//! [`super::intersect_triangle`]; the `t` error bound, needed only for lanes
//! that pass every other test, is computed for all lanes once any does, and
//! lanes whose positive `t` lies within it are decided by the same f64 test
//! ([`near_hit_t`]), one lane at a time (rare: origins within microns).

use super::surface::gamma;
use super::triangle::{near_hit_t, TriangleHit, TriangleRay};
use candela_bvh::simd::F32x4;
use glam::Vec3;

/// Up to four triangles in structure-of-arrays form: row `3 * v + axis`
/// holds coordinate `axis` of vertex `v` for each lane. 144 bytes.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(16))]
pub struct TrianglePacket {
    /// Vertex coordinates by row, one lane per triangle.
    pub rows: [[f32; 4]; 9],
}

impl TrianglePacket {
    /// Packs triangles into lanes; lanes past `tris.len()` (at most four are
    /// used) hold degenerate triangles, which never hit.
    pub fn new(tris: &[[Vec3; 3]]) -> Self {
        let mut rows = [[0.0f32; 4]; 9];
        for (lane, t) in tris.iter().take(4).enumerate() {
            for (v, p) in t.iter().enumerate() {
                for axis in 0..3 {
                    rows[3 * v + axis][lane] = p[axis];
                }
            }
        }
        Self { rows }
    }

    /// The triangle in `lane`.
    pub fn triangle(&self, lane: usize) -> [Vec3; 3] {
        let r = &self.rows;
        [0, 1, 2].map(|v| Vec3::new(r[3 * v][lane], r[3 * v + 1][lane], r[3 * v + 2][lane]))
    }
}

/// The per-ray set-up of [`TriangleRay`] broadcast to four lanes.
#[derive(Clone, Copy, Debug)]
pub struct TriangleRay4 {
    scalar: TriangleRay,
    axes: [usize; 3],
    origin: [F32x4; 3],
    shear: [F32x4; 3],
}

impl TriangleRay4 {
    /// Broadcasts a prepared ray.
    pub fn new(r: &TriangleRay) -> Self {
        let axes = match r.kz {
            0 => [1, 2, 0],
            1 => [2, 0, 1],
            _ => [0, 1, 2],
        };
        let o = r.origin;
        let s = r.shear;
        Self {
            scalar: *r,
            axes,
            origin: [F32x4::splat(o.x), F32x4::splat(o.y), F32x4::splat(o.z)],
            shear: [F32x4::splat(s.x), F32x4::splat(s.y), F32x4::splat(s.z)],
        }
    }
}

/// The lanes of `lanes` (a bit mask) hit with `t` in `(0, t_max)`, with
/// each lane's `t`, barycentric numerators and `1 / det`.
struct LaneHits {
    valid: u32,
    t: F32x4,
    e1: F32x4,
    e2: F32x4,
    inv_det: F32x4,
}

/// The scalar test's operations on four lanes; the `t` error bound is
/// computed for all lanes at once, only when some lane is still in range.
#[inline(always)]
fn hit_lanes(ray: &TriangleRay4, p: &TrianglePacket, lanes: u32, t_max: f32) -> Option<LaneHits> {
    let [kx, ky, kz] = ray.axes;
    let [sx, sy, sz] = ray.shear;
    let vertex = |v: usize| {
        let ax = F32x4::load(&p.rows[3 * v + kx]) - ray.origin[0];
        let ay = F32x4::load(&p.rows[3 * v + ky]) - ray.origin[1];
        let az = F32x4::load(&p.rows[3 * v + kz]) - ray.origin[2];
        (ax + sx * az, ay + sy * az, az)
    };
    let (x0, y0, z0) = vertex(0);
    let (x1, y1, z1) = vertex(1);
    let (x2, y2, z2) = vertex(2);
    let e0 = x1 * y2 - y1 * x2;
    let e1 = x2 * y0 - y2 * x0;
    let e2 = x0 * y1 - y0 * x1;
    let zero = F32x4::splat(0.0);
    let neg = e0.lt_mask(zero) | e1.lt_mask(zero) | e2.lt_mask(zero);
    let pos = zero.lt_mask(e0) | zero.lt_mask(e1) | zero.lt_mask(e2);
    let det = e0 + e1 + e2;
    let mut valid = lanes & !(neg & pos) & det.ne_mask(zero);
    if valid == 0 {
        return None;
    }
    let (z0, z1, z2) = (z0 * sz, z1 * sz, z2 * sz);
    let t_scaled = e0 * z0 + e1 * z1 + e2 * z2;
    let inv_det = F32x4::splat(1.0) / det;
    let t = t_scaled * inv_det;
    // Lanes behind the origin leave at once (most lanes of a shadow or
    // bounce ray's leaf): only t > 0 pays for the error bound below.
    valid &= t.lt_mask(F32x4::splat(t_max)) & zero.lt_mask(t);
    if valid == 0 {
        return None;
    }
    // `t_error_bound` lane-wise, operation for operation.
    let max3 = |a: F32x4, b: F32x4, c: F32x4| a.abs().max(b.abs()).max(c.abs());
    let max_z = max3(z0, z1, z2);
    let max_x = max3(x0, x1, x2);
    let max_y = max3(y0, y1, y2);
    let [g2, g3, g5] = [gamma(2), gamma(3), gamma(5)].map(F32x4::splat);
    let delta_x = g5 * (max_x + max_z);
    let delta_y = g5 * (max_y + max_z);
    let delta_z = g3 * max_z;
    let delta_e = F32x4::splat(2.0) * (g2 * max_x * max_y + delta_y * max_x + delta_x * max_y);
    let max_e = max3(e0, e1, e2);
    let bound = F32x4::splat(3.0)
        * (g3 * max_e * max_z + delta_e * max_z + delta_z * max_e)
        * inv_det.abs();
    let sure = valid & bound.lt_mask(t);
    let near = valid & !sure & inv_det.abs().lt_mask(F32x4::splat(f32::INFINITY));
    let (valid, t) = if near == 0 {
        (sure, t)
    } else {
        decide_near_lanes(ray, p, sure, near, t, t_max)
    };
    (valid != 0).then_some(LaneHits {
        valid,
        t,
        e1,
        e2,
        inv_det,
    })
}

/// Lanes in `near` re-decided in f64 by [`near_hit_t`], as the scalar test
/// does: the hit lanes (`sure` and the near lanes that hit) and their `t`.
#[cold]
#[inline(never)]
fn decide_near_lanes(
    ray: &TriangleRay4,
    p: &TrianglePacket,
    sure: u32,
    mut near: u32,
    t: F32x4,
    t_max: f32,
) -> (u32, F32x4) {
    let mut valid = sure;
    let mut ts = t.to_array();
    while near != 0 {
        let lane = near.trailing_zeros() as usize;
        near &= near - 1;
        if let Some(t) = near_hit_t(&ray.scalar, &p.triangle(lane), t_max) {
            ts[lane] = t;
            valid |= 1 << lane;
        }
    }
    (valid, F32x4::load(&ts))
}

/// Closest hit among the lanes in `lanes` (a bit mask) with `t` in
/// `(0, t_max)`: the lane and the hit.
#[inline(always)]
pub fn intersect_triangle4(
    ray: &TriangleRay4,
    p: &TrianglePacket,
    lanes: u32,
    t_max: f32,
) -> Option<(usize, TriangleHit)> {
    let h = hit_lanes(ray, p, lanes, t_max)?;
    let ta = h.t.to_array();
    let mut valid = h.valid;
    let mut lane = valid.trailing_zeros() as usize;
    valid &= valid - 1;
    while valid != 0 {
        let l = valid.trailing_zeros() as usize;
        valid &= valid - 1;
        if ta[l] < ta[lane] {
            lane = l;
        }
    }
    let inv = h.inv_det.to_array()[lane];
    Some((
        lane,
        TriangleHit {
            t: ta[lane],
            b1: h.e1.to_array()[lane] * inv,
            b2: h.e2.to_array()[lane] * inv,
        },
    ))
}

/// Whether any lane in `lanes` is hit with `t` in `(0, t_max)`: the
/// shadow-ray test, which needs no closest lane.
#[inline(always)]
pub fn occluded_triangle4(ray: &TriangleRay4, p: &TrianglePacket, lanes: u32, t_max: f32) -> bool {
    hit_lanes(ray, p, lanes, t_max).is_some()
}

#[cfg(test)]
mod tests {
    use super::super::intersect_triangle;
    use super::super::tests::Rng;
    use super::*;

    /// The packet agrees with the scalar test bit for bit: same lane chosen
    /// as the closest scalar hit, same t and barycentrics; the shadow test
    /// agrees with whether the scalar test hits at all.
    #[test]
    fn packet_matches_scalar() {
        let mut rng = Rng(41);
        let mut hits = 0;
        for _ in 0..100_000 {
            let n = 1 + (rng.f32() * 4.0) as usize % 4;
            let c = rng.vec(-50.0, 50.0);
            let s = rng.log(-2.0, 2.0);
            let tris: Vec<[Vec3; 3]> = (0..n)
                .map(|_| [0; 3].map(|_| c + s * rng.vec(-1.0, 1.0)))
                .collect();
            let o = c + 3.0 * s * rng.dir();
            let d = (c + s * rng.vec(-0.5, 0.5) - o).normalize();
            let t_max = if rng.f32() < 0.3 {
                rng.f32() * 4.0 * s
            } else {
                f32::INFINITY
            };
            let tr = TriangleRay::new(o, d);
            let mut want: Option<(usize, TriangleHit)> = None;
            let mut tm = t_max;
            for (i, t) in tris.iter().enumerate() {
                if let Some(h) = intersect_triangle(&tr, t, tm) {
                    tm = h.t;
                    want = Some((i, h));
                }
            }
            let packet = TrianglePacket::new(&tris);
            let got = intersect_triangle4(&TriangleRay4::new(&tr), &packet, (1 << n) - 1, t_max);
            let blocked = occluded_triangle4(&TriangleRay4::new(&tr), &packet, (1 << n) - 1, t_max);
            assert_eq!(blocked, want.is_some());
            assert_eq!(got.map(|g| g.1), want.map(|w| w.1));
            if let (Some(g), Some(w)) = (got, want) {
                assert!(g.0 == w.0 || tris[g.0] == tris[w.0] || g.1.t == w.1.t);
                hits += 1;
            }
            assert_eq!(packet.triangle(n - 1), tris[n - 1]);
        }
        assert!(hits > 20_000, "{hits}");
    }
}
