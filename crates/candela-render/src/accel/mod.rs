//! The scene-level acceleration structure: one BVH over all triangles and
//! spheres, answering closest-hit and shadow queries.
//!
//! A hit names its primitive by [`PrimRef`] (triangle `i` or sphere `j`, in
//! input order), independent of the BVH's internal order. Primitive data is
//! stored in BVH leaf order, so a leaf's primitives are
//! adjacent in memory. The hit record is kept small; shading data (normals,
//! UVs, error bounds) is computed later from it by the caller with
//! [`crate::shape::triangle_surface_point`] or
//! [`crate::shape::sphere_surface_point`].

use crate::geometry::Ray;
use crate::shape::{
    intersect_sphere, intersect_triangle, sphere_uv, PrimKind, PrimRef, TriangleRay, TriangleRay4,
};
use candela_bvh::{Aabb, BuildOptions, BuildStrategy, Bvh, RayBoxQuery, StatsSink, WideBvh};
use glam::Vec3;
use rayon::prelude::*;
use std::time::Instant;

pub use candela_bvh::TraversalStats;

mod packets;
#[cfg(test)]
mod tests;

use packets::{LeafBlocks, LeafHit};

/// What a padding slot of the 4-wide leaves refers to; never reported, as
/// padding lanes are masked out of every test.
const PADDING_REF: PrimRef = PrimRef::triangle(PrimRef::MAX_INDEX);

/// A closest hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Ray parameter.
    pub t: f32,
    /// The primitive hit.
    pub prim: PrimRef,
    /// Triangle: barycentric weight of `v1`. Sphere: `u = phi / 2pi` around
    /// +Y, a texture coordinate (the normal is `(p - center) / radius`).
    pub b1: f32,
    /// Triangle: barycentric weight of `v2`. Sphere: `v = theta / pi` from +Y.
    pub b2: f32,
}

/// Why an acceleration structure could not be built.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum AccelError {
    /// A triangle refers to a vertex that does not exist.
    #[error("triangle {triangle} refers to vertex {index}, but there are {vertices} vertices")]
    IndexOutOfRange {
        /// Offending triangle.
        triangle: usize,
        /// Offending index.
        index: u32,
        /// Number of vertices.
        vertices: usize,
    },
}

/// Size and cost figures of a built structure, for reports.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AccelInfo {
    /// Wall-clock build time in seconds (BVH and primitive reordering).
    pub build_seconds: f64,
    /// Number of BVH nodes.
    pub nodes: usize,
    /// BVH depth.
    pub depth: u32,
    /// Bytes held by the BVH nodes and order.
    pub bvh_bytes: usize,
    /// Bytes held in total (BVH plus the reordered primitive data).
    pub total_bytes: usize,
}

/// Which node layout traversal uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layout {
    /// The binary BVH: 32-byte nodes, two scalar box tests per node.
    Binary,
    /// The binary BVH collapsed to 4-wide nodes tested with SSE, leaves
    /// tested four triangles at a time: about twice the binary layout's
    /// rate on incoherent rays (`candela bench rays --layout`).
    Wide4,
    /// 8-wide nodes tested with AVX2 (SSE halves on CPUs without it),
    /// the same 4-triangle leaves.
    Wide8,
}

impl Default for Layout {
    /// [`Layout::Wide8`] where the CPU has AVX2, [`Layout::Wide4`] elsewhere.
    fn default() -> Self {
        if candela_bvh::has_avx2() {
            Layout::Wide8
        } else {
            Layout::Wide4
        }
    }
}

/// The hierarchy in the chosen layout.
#[derive(Clone, Debug)]
enum Tree {
    /// Primitives one per slot.
    Binary(Bvh, Vec<Prim>),
    /// A 4-wide tree.
    Wide4(Wide<4>),
    /// An 8-wide tree.
    Wide8(Wide<8>),
}

/// A wide tree with primitives in SIMD blocks per leaf, and the primitive
/// of each slot.
#[derive(Clone, Debug)]
struct Wide<const W: usize> {
    bvh: WideBvh<W>,
    leaves: LeafBlocks,
    slot_refs: Vec<PrimRef>,
}

impl<const W: usize> Wide<W> {
    /// Collapses `bvh` (built over `boxes`), splitting leaves of two blocks
    /// into free lanes, and packs the leaves; `refs` and `shape` give each
    /// input primitive.
    fn new(bvh: Bvh, boxes: &[Aabb], refs: &[PrimRef], shape: impl Fn(PrimRef) -> Shape) -> Self {
        let mut bvh = WideBvh::<W>::from_binary_filled(bvh, boxes, 4);
        bvh.pad_leaves(4);
        let slot_refs: Vec<PrimRef> = bvh
            .primitive_order()
            .iter()
            .map(|&id| refs.get(id as usize).copied().unwrap_or(PADDING_REF))
            .collect();
        let slot_refs = candela_bvh::on_huge_pages(slot_refs);
        let leaves = LeafBlocks::new(&slot_refs, shape);
        Self {
            bvh,
            leaves,
            slot_refs,
        }
    }

    /// Bytes of the leaf data (blocks and slot references).
    fn prim_bytes(&self) -> usize {
        self.leaves.bytes() + self.slot_refs.len() * std::mem::size_of::<PrimRef>()
    }

    #[inline(always)]
    fn closest<S: StatsSink>(
        &self,
        ray: &Ray,
        q: &RayBoxQuery,
        tri_ray: &TriangleRay,
        stats: &mut S,
    ) -> Option<Hit> {
        let tr4 = TriangleRay4::new(tri_ray);
        let prefetch = |first, count| self.leaves.prefetch(first, count);
        let mut hit = LeafHit::default();
        let test = |first, count, t_max| {
            self.leaves
                .closest(first, count, ray, &tr4, t_max, &mut hit)
        };
        let (slot, t) = self
            .bvh
            .closest_hit_leaves(q, ray.t_max, stats, prefetch, test)?;
        Some(Hit {
            t,
            prim: self.slot_refs[slot as usize],
            b1: hit.b1,
            b2: hit.b2,
        })
    }

    #[inline(always)]
    fn occluded<S: StatsSink>(&self, ray: &Ray, q: &RayBoxQuery, stats: &mut S) -> bool {
        // The triangle test's set-up (a permutation, two divisions and the
        // broadcasts) waits for the first leaf: most shadow rays toward a
        // lamp cross only empty nodes (on the CS184 render, 0.38M leaf
        // visits for 0.86M shadow rays) and never need it.
        let mut tr4: Option<TriangleRay4> = None;
        let prefetch = |first, count| self.leaves.prefetch(first, count);
        // Compiled into the traversal loop (see `WideBvh::any_hit_leaves`).
        let test = {
            #[inline(always)]
            |first, count, t_max| {
                let tr4 = tr4.get_or_insert_with(|| {
                    TriangleRay4::new(&TriangleRay::new(ray.origin, ray.dir))
                });
                self.leaves.any(first, count, ray, tr4, t_max)
            }
        };
        self.bvh.any_hit_leaves(q, ray.t_max, stats, prefetch, test)
    }
}

/// One primitive in leaf order: triangle vertices, or a sphere stored as
/// `[center, (radius, 0, 0), 0]`.
#[derive(Clone, Copy, Debug)]
struct Prim {
    v: [Vec3; 3],
    prim: PrimRef,
}

/// A primitive's geometry as the leaves store it.
#[derive(Clone, Copy, Debug)]
enum Shape {
    Triangle([Vec3; 3]),
    Sphere { center: Vec3, radius: f32 },
}

/// Expands an indexed mesh into one `[v0, v1, v2]` per triangle, checking
/// every index.
pub fn triangle_soup(
    positions: &[Vec3],
    indices: &[[u32; 3]],
) -> Result<Vec<[Vec3; 3]>, AccelError> {
    let vertex = |triangle: usize, i: u32| {
        positions
            .get(i as usize)
            .copied()
            .ok_or(AccelError::IndexOutOfRange {
                triangle,
                index: i,
                vertices: positions.len(),
            })
    };
    indices
        .iter()
        .enumerate()
        .map(|(t, idx)| Ok([vertex(t, idx[0])?, vertex(t, idx[1])?, vertex(t, idx[2])?]))
        .collect()
}

/// The bounding box of each primitive in input-id order: the triangles,
/// then the spheres.
pub fn primitive_boxes(triangles: &[[Vec3; 3]], spheres: &[(Vec3, f32)]) -> Vec<Aabb> {
    let mut boxes: Vec<Aabb> = triangles.par_iter().map(|t| Aabb::from_points(t)).collect();
    boxes.extend(spheres.iter().map(|&(c, r)| {
        let r = Vec3::splat(r.abs());
        Aabb::new(c - r, c + r)
    }));
    boxes
}

/// The binary hierarchy over the primitives (input ids: triangles, then
/// spheres), as [`Accel`] builds it before choosing a layout. With
/// [`Accel::default_options`] for [`Layout::Wide4`] it is the tree the
/// render's 4-wide tree is collapsed from: what a viewer shows node by node.
pub fn binary_tree(triangles: &[[Vec3; 3]], spheres: &[(Vec3, f32)], opts: BuildOptions) -> Bvh {
    tree_over(&primitive_boxes(triangles, spheres), opts)
}

/// The binary hierarchy over primitive boxes (centroids: the box centres).
fn tree_over(boxes: &[Aabb], opts: BuildOptions) -> Bvh {
    let centroids: Vec<Vec3> = boxes.par_iter().map(Aabb::center).collect();
    Bvh::build(boxes, &centroids, opts)
}

/// Triangles and spheres behind one BVH. Immutable and `Sync`: share it
/// between render threads by reference.
#[derive(Clone, Debug)]
pub struct Accel {
    tree: Tree,
    n_tri: u32,
    info: AccelInfo,
}

impl Accel {
    /// Builds over triangle soup and spheres `(center, radius)`.
    pub fn build(
        triangles: &[[Vec3; 3]],
        spheres: &[(Vec3, f32)],
        strategy: BuildStrategy,
    ) -> Self {
        Self::build_with_layout(triangles, spheres, strategy, Layout::default())
    }

    /// [`Accel::build`] with a chosen node layout (for benchmarks and tests).
    pub fn build_with_layout(
        triangles: &[[Vec3; 3]],
        spheres: &[(Vec3, f32)],
        strategy: BuildStrategy,
        layout: Layout,
    ) -> Self {
        Self::build_with_options(
            triangles,
            spheres,
            Self::default_options(strategy, layout),
            layout,
        )
    }

    /// The build options used for a strategy and layout: the wide layouts
    /// test leaves four primitives at a time, so the SAH counts blocks of 4.
    pub fn default_options(strategy: BuildStrategy, layout: Layout) -> BuildOptions {
        match layout {
            Layout::Binary => BuildOptions::with_strategy(strategy),
            // The collapse of least SAH cost with a node test at the cost of
            // a block test: on the CS184 boxes' renders 15% fewer render-loop
            // instructions than the greedy collapse (34% fewer in shadow
            // queries), fewer on the held-out sphere and terrain, 2-7% more
            // on the grass (BENCHMARKS.md, "The SAH collapse"). No leaf
            // cost: it saved no instructions anywhere, and at node cost 1
            // or more it flips flat patches into two-block leaves (terrain
            // any hit +17%; "A leaf cost for the SAH collapse").
            Layout::Wide4 | Layout::Wide8 => BuildOptions {
                leaf_block: 4,
                collapse: candela_bvh::Collapse::Sah,
                wide_node_cost: 1.0,
                wide_leaf_cost: 0.0,
                ..BuildOptions::with_strategy(strategy)
            },
        }
    }

    /// [`Accel::build`] with explicit BVH build options (for tuning).
    pub fn build_with_options(
        triangles: &[[Vec3; 3]],
        spheres: &[(Vec3, f32)],
        opts: BuildOptions,
        layout: Layout,
    ) -> Self {
        let start = Instant::now();
        let boxes = primitive_boxes(triangles, spheres);
        let bvh = tree_over(&boxes, opts);
        let n_tri = triangles.len() as u32;
        // Input (BVH) ids: triangles, then spheres.
        let refs: Vec<PrimRef> = (0..n_tri)
            .map(PrimRef::triangle)
            .chain((0..spheres.len() as u32).map(PrimRef::sphere))
            .collect();
        let shape = |p: PrimRef| match p.kind() {
            PrimKind::Triangle => Shape::Triangle(triangles[p.index() as usize]),
            PrimKind::Sphere => {
                let (center, r) = spheres[p.index() as usize];
                Shape::Sphere {
                    center,
                    radius: r.abs(),
                }
            }
        };
        let (nodes, depth, bvh_bytes, prim_bytes, tree) = match layout {
            Layout::Binary => {
                let prims: Vec<Prim> = bvh
                    .primitive_order()
                    .iter()
                    .map(|&id| {
                        let prim = refs[id as usize];
                        match shape(prim) {
                            Shape::Triangle(v) => Prim { v, prim },
                            Shape::Sphere { center, radius } => Prim {
                                v: [center, Vec3::new(radius, 0.0, 0.0), Vec3::ZERO],
                                prim,
                            },
                        }
                    })
                    .collect();
                let pb = prims.len() * std::mem::size_of::<Prim>();
                (
                    bvh.nodes().len(),
                    bvh.depth(),
                    bvh.bytes(),
                    pb,
                    Tree::Binary(bvh, prims),
                )
            }
            Layout::Wide4 => {
                let w = Wide::<4>::new(bvh, &boxes, &refs, shape);
                let (n, d, b, p) = (
                    w.bvh.nodes().len(),
                    w.bvh.depth(),
                    w.bvh.bytes(),
                    w.prim_bytes(),
                );
                (n, d, b, p, Tree::Wide4(w))
            }
            Layout::Wide8 => {
                let w = Wide::<8>::new(bvh, &boxes, &refs, shape);
                let (n, d, b, p) = (
                    w.bvh.nodes().len(),
                    w.bvh.depth(),
                    w.bvh.bytes(),
                    w.prim_bytes(),
                );
                (n, d, b, p, Tree::Wide8(w))
            }
        };
        let info = AccelInfo {
            build_seconds: start.elapsed().as_secs_f64(),
            nodes,
            depth,
            bvh_bytes,
            total_bytes: bvh_bytes + prim_bytes,
        };
        Self { tree, n_tri, info }
    }

    /// Builds over an indexed mesh (`indices` name three `positions` each).
    pub fn build_indexed(
        positions: &[Vec3],
        indices: &[[u32; 3]],
        spheres: &[(Vec3, f32)],
        strategy: BuildStrategy,
    ) -> Result<Self, AccelError> {
        Ok(Self::build(
            &triangle_soup(positions, indices)?,
            spheres,
            strategy,
        ))
    }

    /// Build time, node count, depth and memory.
    pub fn info(&self) -> AccelInfo {
        self.info
    }

    /// Checks the hierarchy's invariants against the primitives' boxes
    /// (in input id order, as built).
    pub fn validate(&self, boxes: &[Aabb]) -> Result<(), String> {
        match &self.tree {
            Tree::Binary(b, _) => b.validate(boxes),
            Tree::Wide4(w) => w.bvh.validate(boxes),
            Tree::Wide8(w) => w.bvh.validate(boxes),
        }
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> u32 {
        self.n_tri
    }

    /// Turns the AVX2 traversal of an 8-wide tree on or off (on only where
    /// the CPU has it), so tests can compare it with the portable path.
    #[cfg(test)]
    fn set_avx2(&mut self, on: bool) {
        if let Tree::Wide8(w) = &mut self.tree {
            w.bvh.set_avx2(on);
        }
    }

    /// Whether queries take the AVX2 traversal (an 8-wide tree on a CPU
    /// with it, unless a test turned it off).
    #[cfg(test)]
    fn uses_avx2(&self) -> bool {
        matches!(&self.tree, Tree::Wide8(w) if w.bvh.uses_avx2())
    }

    /// Closest hit with `t` in `(0, ray.t_max)`.
    pub fn intersect(&self, ray: &Ray) -> Option<Hit> {
        self.intersect_counted(ray, &mut ())
    }

    /// True if anything lies on the ray with `t` in `(0, ray.t_max)`.
    pub fn occluded(&self, ray: &Ray) -> bool {
        self.occluded_counted(ray, &mut ())
    }

    /// [`Accel::intersect`], adding node visits and primitive tests to `stats`
    /// (pass a per-thread [`TraversalStats`]; `&mut ()` counts nothing).
    #[inline]
    pub fn intersect_counted<S: StatsSink>(&self, ray: &Ray, stats: &mut S) -> Option<Hit> {
        let q = RayBoxQuery::new(ray.origin, ray.dir);
        let tri_ray = TriangleRay::new(ray.origin, ray.dir);
        match &self.tree {
            Tree::Binary(bvh, prims) => {
                let mut bary = (0.0, 0.0);
                let test = |slot: u32, t_max: f32| {
                    self.test(&prims[slot as usize], ray, &tri_ray, t_max, &mut bary)
                };
                let (slot, t) = bvh.closest_hit(&q, ray.t_max, stats, test)?;
                let p = &prims[slot as usize];
                if p.prim.kind() == PrimKind::Sphere {
                    bary = sphere_uv(p.v[0], ray.at(t));
                }
                Some(Hit {
                    t,
                    prim: p.prim,
                    b1: bary.0,
                    b2: bary.1,
                })
            }
            Tree::Wide4(w) => w.closest(ray, &q, &tri_ray, stats),
            Tree::Wide8(w) => w.closest(ray, &q, &tri_ray, stats),
        }
    }

    /// [`Accel::occluded`] with statistics.
    #[inline]
    pub fn occluded_counted<S: StatsSink>(&self, ray: &Ray, stats: &mut S) -> bool {
        let q = RayBoxQuery::new(ray.origin, ray.dir);
        match &self.tree {
            Tree::Binary(bvh, prims) => {
                let tri_ray = TriangleRay::new(ray.origin, ray.dir);
                let mut bary = (0.0, 0.0);
                let test = |slot: u32, t_max: f32| {
                    self.test(&prims[slot as usize], ray, &tri_ray, t_max, &mut bary)
                };
                bvh.any_hit(&q, ray.t_max, stats, test)
            }
            Tree::Wide4(w) => w.occluded(ray, &q, stats),
            Tree::Wide8(w) => w.occluded(ray, &q, stats),
        }
    }

    /// Intersects one primitive; triangle barycentrics go to `bary`.
    #[inline(always)]
    fn test(
        &self,
        p: &Prim,
        ray: &Ray,
        tri_ray: &TriangleRay,
        t_max: f32,
        bary: &mut (f32, f32),
    ) -> Option<f32> {
        match p.prim.kind() {
            PrimKind::Triangle => {
                let h = intersect_triangle(tri_ray, &p.v, t_max)?;
                *bary = (h.b1, h.b2);
                Some(h.t)
            }
            PrimKind::Sphere => intersect_sphere(ray.origin, ray.dir, p.v[0], p.v[1].x, t_max),
        }
    }
}
