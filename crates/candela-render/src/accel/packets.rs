//! Leaf primitives of the wide BVHs packed four to a block, so a leaf is
//! tested with SIMD (the layout of Embree's `Triangle4`).

use super::{Shape, PADDING_REF};
use crate::geometry::Ray;
use crate::shape::PrimRef;
use crate::shape::{
    intersect_sphere, intersect_triangle4, occluded_triangle4, sphere_uv, TrianglePacket,
    TriangleRay4,
};
use candela_bvh::simd::prefetch;
use glam::Vec3;

/// Up to four primitives. A sphere lane keeps its centre in the `v0` rows
/// and its radius in the `v1.x` row. 160 bytes, 32-byte aligned so that a
/// block spans three cache lines, not four. Primitive references are
/// not stored here: the accelerator maps the winning slot to its
/// [`PrimRef`]. Each kind of shape has its own lane mask.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
pub(super) struct Block {
    tri: TrianglePacket,
    tri_lanes: u32,
    sphere_lanes: u32,
}

const _: () = assert!(std::mem::size_of::<Block>() == 160);

/// The blocks of every leaf: block `k` holds slots `4k .. 4k + 4` of a
/// tree whose leaves were padded to multiples of four
/// ([`candela_bvh::WideBvh::pad_leaves`]), so a leaf starting at slot `first` starts at
/// block `first / 4`.
#[derive(Clone, Debug)]
pub(super) struct LeafBlocks {
    blocks: Vec<Block>,
}

/// The winning primitive's barycentrics (or sphere coordinates).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct LeafHit {
    pub b1: f32,
    pub b2: f32,
}

impl LeafBlocks {
    /// Packs the primitives of `slots` (a BVH's leaf order, padded to
    /// multiples of four with `PADDING_REF`); `shape` gives each one's geometry.
    pub(super) fn new(slots: &[PrimRef], shape: impl Fn(PrimRef) -> Shape) -> Self {
        let blocks = slots
            .chunks(4)
            .map(|chunk| {
                let mut tris = [[Vec3::ZERO; 3]; 4];
                let (mut tri_lanes, mut sphere_lanes) = (0, 0);
                for (lane, &prim) in chunk.iter().enumerate() {
                    if prim == PADDING_REF {
                        continue;
                    }
                    match shape(prim) {
                        Shape::Triangle(t) => {
                            tris[lane] = t;
                            tri_lanes |= 1 << lane;
                        }
                        Shape::Sphere { center, radius } => {
                            tris[lane] = [center, Vec3::new(radius, 0.0, 0.0), Vec3::ZERO];
                            sphere_lanes |= 1 << lane;
                        }
                    }
                }
                Block {
                    tri: TrianglePacket::new(&tris),
                    tri_lanes,
                    sphere_lanes,
                }
            })
            .collect();
        Self {
            blocks: candela_bvh::on_huge_pages(blocks),
        }
    }

    /// Starts loading the blocks of slots `first .. first + count` (a leaf
    /// the traversal will visit later) into cache.
    #[inline(always)]
    pub fn prefetch(&self, first: u32, count: u32) {
        let start = (first / 4) as usize;
        for b in &self.blocks[start..start + count.div_ceil(4) as usize] {
            prefetch(&b.tri.rows[0]);
            prefetch(&b.tri.rows[4]);
            prefetch(&b.tri_lanes);
        }
    }

    /// Bytes held.
    pub fn bytes(&self) -> usize {
        self.blocks.len() * std::mem::size_of::<Block>()
    }

    /// Closest hit among slots `first .. first + count` before `t_max`.
    #[inline(always)]
    pub fn closest(
        &self,
        first: u32,
        count: u32,
        ray: &Ray,
        tr4: &TriangleRay4,
        t_max: f32,
        out: &mut LeafHit,
    ) -> Option<(u32, f32)> {
        let start = (first / 4) as usize;
        let mut best: Option<(u32, f32)> = None;
        let mut t_best = t_max;
        for (k, b) in self.blocks[start..start + count.div_ceil(4) as usize]
            .iter()
            .enumerate()
        {
            let slot0 = first + 4 * k as u32;
            if b.tri_lanes != 0 {
                if let Some((lane, h)) = intersect_triangle4(tr4, &b.tri, b.tri_lanes, t_best) {
                    t_best = h.t;
                    best = Some((slot0 + lane as u32, h.t));
                    *out = LeafHit { b1: h.b1, b2: h.b2 };
                }
            }
            let mut s = b.sphere_lanes;
            while s != 0 {
                let lane = s.trailing_zeros() as usize;
                s &= s - 1;
                let [c, r, _] = b.tri.triangle(lane);
                if let Some(t) = intersect_sphere(ray.origin, ray.dir, c, r.x, t_best) {
                    t_best = t;
                    best = Some((slot0 + lane as u32, t));
                    let (u, v) = sphere_uv(c, ray.at(t));
                    *out = LeafHit { b1: u, b2: v };
                }
            }
        }
        best
    }

    /// True if any primitive in slots `first .. first + count` is hit before `t_max`.
    #[inline(always)]
    pub fn any(&self, first: u32, count: u32, ray: &Ray, tr4: &TriangleRay4, t_max: f32) -> bool {
        let start = (first / 4) as usize;
        // A loop, not `Iterator::any`, which the compiler kept out of line
        // (a call per leaf, and SSE encoding outside the AVX2 traversal).
        for b in &self.blocks[start..start + count.div_ceil(4) as usize] {
            if (b.tri_lanes != 0 && occluded_triangle4(tr4, &b.tri, b.tri_lanes, t_max))
                || (b.sphere_lanes != 0 && any_sphere(b, ray, t_max))
            {
                return true;
            }
        }
        false
    }
}

/// Whether a sphere lane of `b` is hit before `t_max` (kept out of line:
/// most scenes have no spheres).
#[inline(never)]
fn any_sphere(b: &Block, ray: &Ray, t_max: f32) -> bool {
    (0..4)
        .filter(|l| b.sphere_lanes & (1 << l) != 0)
        .any(|lane| {
            let [c, r, _] = b.tri.triangle(lane);
            intersect_sphere(ray.origin, ray.dir, c, r.x, t_max).is_some()
        })
}
