//! Light sampling of planar emitters (triangles, CGL parallelograms) by the
//! solid angle they subtend, with a fallback to sampling by area.
//!
//! Sampling by area converts to a solid-angle density `d² / (A cos θ_l)`
//! that grows toward the far, grazing parts of a lamp close to the
//! receiver, exactly where the receiver's cosine and the lamp's foreshortening
//! make them contribute least. Sampling the spherical polygon uniformly
//! (`sampling/warp/spherical_polygon.rs`) removes that variance: the
//! estimate then varies only with the BSDF, the receiver cosine and
//! visibility.
//!
//! The choice of method is a function of the viewpoint and the light only,
//! never of the sample, so that `pdf_li` reports the density `sample_li`
//! actually had (multiple importance sampling needs it):
//! - below [`MIN_SOLID_ANGLE`] the two densities barely differ across the
//!   lamp and sampling by area is cheaper (no trigonometry);
//! - above [`MAX_SOLID_ANGLE`] (a viewpoint almost on the lamp, which then
//!   fills nearly a hemisphere) the spherical polygon has angles near π
//!   and the warps lose accuracy; pbrt-v4 uses the same bounds;
//! - a true rectangle (orthogonal edges) uses Ureña et al.'s warp; another
//!   parallelogram is two triangles, chosen in proportion to their solid
//!   angles, so the density is uniform over the whole.

use glam::{Vec2, Vec3};

use super::AreaShape;
use crate::sampling::warp::{
    rectangle_solid_angle, square_to_spherical_rectangle, square_to_spherical_triangle,
    triangle_solid_angle, Parallelogram,
};

/// Below this solid angle (steradians) planar lamps are sampled by area
/// (see the module docs and BENCHMARKS.md, "Solid-angle sampling of lamps").
pub(crate) const MIN_SOLID_ANGLE: f32 = 3e-4;
/// Above this solid angle (steradians; a hemisphere is 2π ≈ 6.28) planar
/// lamps are sampled by area.
pub(crate) const MAX_SOLID_ANGLE: f32 = 6.22;
/// Below this estimate of the solid angle, `area / d²` with `d` the
/// distance to the lamp's centre, planar lamps are sampled by area without
/// computing the exact solid angle. The gain is large only close to a lamp
/// (the quadrature in BENCHMARKS.md: variance ratios of 0.006-0.06 within
/// about a lamp's width, where sampling by area has relative variances of
/// 0.25-42), while the spherical warps' trigonometry and the exact solid
/// angle cost a third more CPU per render on the CS184 boxes when every
/// shading point pays them (1.36-1.96x measured). Half a steradian is a
/// viewpoint within about 1.4 lamp widths of a square lamp.
pub(crate) const SOLID_ANGLE_GATE: f32 = 0.5;
/// A parallelogram whose edges' cosine is at most this is a rectangle for
/// Ureña et al.'s warp: the sliver it then misses or adds is a 10⁻⁶ fraction
/// of the lamp.
const RECTANGLE_COSINE: f32 = 1e-6;

/// How a planar lamp is sampled from a given viewpoint by solid angle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum SolidAngleSampling {
    /// One spherical triangle of this solid angle.
    Triangle(f32),
    /// A spherical rectangle of this solid angle.
    Rectangle(f32),
    /// A parallelogram as the triangles (origin, +edge0, +edge0+edge1) and
    /// (origin, +edge0+edge1, +edge1), of these solid angles.
    TwoTriangles(f32, f32),
}

impl SolidAngleSampling {
    /// The lamp's whole solid angle: the density is its inverse.
    pub(super) fn solid_angle(&self) -> f32 {
        match *self {
            SolidAngleSampling::Triangle(omega) | SolidAngleSampling::Rectangle(omega) => omega,
            SolidAngleSampling::TwoTriangles(a, b) => a + b,
        }
    }
}

/// The two triangles a parallelogram is split into, corners relative to `p`.
fn halves(shape: &Parallelogram, p: Vec3) -> [[Vec3; 3]; 2] {
    let o = shape.origin - p;
    let far = o + shape.edge0 + shape.edge1;
    [[o, o + shape.edge0, far], [o, far, o + shape.edge1]]
}

fn is_rectangle(shape: &Parallelogram) -> bool {
    let (e0, e1) = (shape.edge0, shape.edge1);
    e0.dot(e1).abs() <= RECTANGLE_COSINE * e0.length() * e1.length()
}

/// What the gate needs of a lamp besides its shape: its surface area and
/// its centre, computed once per light (the set keeps one per light) rather
/// than per light sample.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct LampSize {
    /// Surface area.
    pub(crate) area: f32,
    /// The centre of a planar lamp (unused for spheres).
    centre: Vec3,
}

impl LampSize {
    /// The size of `shape`.
    pub(crate) fn of(shape: &AreaShape) -> Self {
        let centre = match shape {
            AreaShape::Triangle { v, .. } => (v[0] + v[1] + v[2]) * (1.0 / 3.0),
            AreaShape::Rect { shape, .. } => shape.origin + 0.5 * (shape.edge0 + shape.edge1),
            AreaShape::Sphere { center, .. } => *center,
        };
        Self {
            area: shape.area(),
            centre,
        }
    }
}

/// How to sample the planar `shape` of size `size` seen from `p` by
/// solid angle, or `None`
/// to sample it by area (spheres; a viewpoint behind or in the lamp's plane,
/// which sees nothing; a lamp far enough for [`SOLID_ANGLE_GATE`]; solid
/// angles outside the bounds above).
#[inline(always)]
pub(super) fn choose(shape: &AreaShape, p: Vec3, size: &LampSize) -> Option<SolidAngleSampling> {
    // The gate first: most shading points are far from the lamp, and this
    // test is a handful of multiplications (the lamp's area and centre are
    // precomputed).
    let (corner, normal) = match shape {
        AreaShape::Triangle { v, normal } => (v[0], *normal),
        AreaShape::Rect { shape, normal } => (shape.origin, *normal),
        AreaShape::Sphere { .. } => return None,
    };
    if size.area < SOLID_ANGLE_GATE * (size.centre - p).length_squared() {
        return None;
    }
    choose_near(shape, p, corner, normal)
}

/// [`choose`] for a viewpoint the gate let through (kept out of line: the
/// gate alone is inlined into every light sample).
#[inline(never)]
fn choose_near(
    shape: &AreaShape,
    p: Vec3,
    corner: Vec3,
    normal: Vec3,
) -> Option<SolidAngleSampling> {
    if (p - corner).dot(normal) <= 0.0 {
        return None;
    }
    let sampling = match shape {
        AreaShape::Triangle { v, .. } => {
            SolidAngleSampling::Triangle(triangle_solid_angle(v[0] - p, v[1] - p, v[2] - p))
        }
        AreaShape::Rect { shape, .. } if is_rectangle(shape) => SolidAngleSampling::Rectangle(
            rectangle_solid_angle(shape.origin - p, shape.edge0, shape.edge1),
        ),
        AreaShape::Rect { shape, .. } => {
            let [a, b] = halves(shape, p);
            SolidAngleSampling::TwoTriangles(
                triangle_solid_angle(a[0], a[1], a[2]),
                triangle_solid_angle(b[0], b[1], b[2]),
            )
        }
        AreaShape::Sphere { .. } => return None,
    };
    let omega = sampling.solid_angle();
    (omega.is_finite() && (MIN_SOLID_ANGLE..=MAX_SOLID_ANGLE).contains(&omega)).then_some(sampling)
}

/// A direction from `p` uniform in the solid angle of `shape` (as
/// [`choose`] decided), and for rectangles the sampled point relative to
/// `p` (triangles leave the intersection to the caller).
pub(super) fn sample(
    shape: &AreaShape,
    sampling: SolidAngleSampling,
    p: Vec3,
    u: Vec2,
) -> Option<(Vec3, Option<Vec3>)> {
    match (shape, sampling) {
        (AreaShape::Triangle { v, .. }, SolidAngleSampling::Triangle(_)) => {
            square_to_spherical_triangle([v[0] - p, v[1] - p, v[2] - p], u).map(|w| (w, None))
        }
        (AreaShape::Rect { shape, .. }, SolidAngleSampling::Rectangle(_)) => {
            let q = square_to_spherical_rectangle(shape.origin - p, shape.edge0, shape.edge1, u)?;
            Some((q.try_normalize()?, Some(q)))
        }
        (AreaShape::Rect { shape, .. }, SolidAngleSampling::TwoTriangles(a, b)) => {
            // Reuse u0 both to choose the half and within it.
            let first = a / (a + b);
            let [ta, tb] = halves(shape, p);
            let (tri, u0) = if u.x < first {
                (ta, u.x / first)
            } else {
                (tb, ((u.x - first) / (1.0 - first)).min(1.0))
            };
            square_to_spherical_triangle(tri, Vec2::new(u0, u.y)).map(|w| (w, None))
        }
        _ => None,
    }
}
