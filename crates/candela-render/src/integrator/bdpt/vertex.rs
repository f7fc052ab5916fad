//! Path vertices of bidirectional methods and the densities between them,
//! all per unit *area* (solid-angle densities converted with the
//! geometry of the two ends), as Veach's MIS ratios need (Veach 1997
//! §10.2; pbrt-v4's `Vertex`).

use crate::bsdf::{shading_normal_correction, Bsdf, TransportMode};
use crate::geometry::Ray;
use crate::light::Light;
use crate::scene::Scene;
use crate::shading::ShadingFrame;
use crate::shape::SurfaceHit;
use glam::Vec3;

/// What a vertex is. Not `Copy` (a blend's BSDF boxes its parts), but
/// cloning one is a copy of bytes for every other BSDF.
// Vertices live in two small per-sample vectors; boxing the surface
// variant would allocate per vertex.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug)]
pub(crate) enum VertexKind {
    /// The lens point a camera subpath starts from.
    Camera,
    /// A point on a light (or, for lights at infinity, where its ray
    /// enters the scene), light `light` of the scene's set.
    Light {
        /// Index in the scene's light set.
        light: u32,
        /// Radiance (or intensity) emitted from here, before the angular
        /// factor of [`emitted_toward`].
        le: Vec3,
    },
    /// The lights at infinity, where a camera ray escaped (its position is
    /// meaningless; `ns` holds the direction light travels from there, the
    /// escaping ray's reversed, as for every vertex at infinity).
    Sky,
    /// A surface point, with its BSDF if it scatters (a pure emitter
    /// does not).
    Surface {
        /// The hit.
        hit: SurfaceHit,
        /// The shading frame, with its bump shadowing.
        frame: ShadingFrame,
        /// The BSDF, `None` for a pure emitter.
        bsdf: Option<Bsdf>,
    },
}

/// One vertex of a light or camera subpath.
#[derive(Clone, Debug)]
pub(crate) struct Vertex {
    /// What it is.
    pub kind: VertexKind,
    /// Position.
    pub p: Vec3,
    /// Geometric normal for area conversions (zero for points: camera,
    /// point and spot lights).
    pub ng: Vec3,
    /// Shading normal for cosines (the emitting normal of lights, the
    /// viewing direction of the camera, the direction light travels for
    /// vertices at infinity).
    pub ns: Vec3,
    /// Throughput of the subpath up to and including this vertex.
    pub beta: Vec3,
    /// Density of this vertex per unit area when sampled from its
    /// predecessor on its own subpath.
    pub pdf_fwd: f32,
    /// Density per unit area if it were sampled from the other side.
    pub pdf_rev: f32,
    /// Whether the scattering here was a delta lobe, so no connection can
    /// end here (delta *lights* are told by [`Vertex::is_delta_light`]).
    pub delta: bool,
    /// Whether the vertex lies at infinity (the sky, a light at infinity):
    /// densities toward it stay per unit solid angle.
    pub infinite: bool,
}

impl Vertex {
    /// A vertex of the given kind with no densities yet.
    pub fn new(kind: VertexKind, p: Vec3, ng: Vec3, ns: Vec3, beta: Vec3) -> Self {
        Self {
            infinite: matches!(kind, VertexKind::Sky),
            kind,
            p,
            ng,
            ns,
            beta,
            pdf_fwd: 0.0,
            pdf_rev: 0.0,
            delta: false,
        }
    }

    /// Whether this vertex lies on a surface (cosines at it count).
    pub fn on_surface(&self) -> bool {
        self.ng != Vec3::ZERO && !self.infinite
    }

    /// Whether a connection may end here (not a delta scatterer, not a
    /// pure emitter on a path's inside).
    pub fn connectible(&self, scene: &Scene) -> bool {
        match self.kind {
            VertexKind::Camera => true,
            VertexKind::Light { light, .. } => {
                !matches!(scene.lights.get(light), Light::Directional(_))
            }
            VertexKind::Sky => false,
            VertexKind::Surface { ref bsdf, .. } => bsdf.as_ref().is_some_and(|b| !b.is_specular()),
        }
    }

    /// Whether the light of this vertex is a delta light (point, spot,
    /// directional): its position or direction cannot be hit.
    pub fn is_delta_light(&self, scene: &Scene) -> bool {
        match self.kind {
            VertexKind::Light { light, .. } => scene.lights.get(light).is_delta(),
            _ => false,
        }
    }

    /// The BSDF value (importance or radiance mode) for light coming from
    /// `next` and leaving toward `prev`'s side, i.e. `wo` toward the
    /// vertex's own predecessor (`wo_world`), `wi` toward `next`, with the
    /// shading-normal correction of the mode; the emitted radiance toward
    /// `next` for a light vertex. Zero for anything else or a direction
    /// that would leak through the true surface.
    pub fn f(&self, scene: &Scene, wo_world: Vec3, next: Vec3, mode: TransportMode) -> Vec3 {
        let wi = (next - self.p).normalize_or_zero();
        match self.kind {
            VertexKind::Surface {
                hit,
                frame,
                bsdf: Some(ref bsdf),
            } => {
                let (wo_l, wi_l) = (frame.to_local(wo_world), frame.to_local(wi));
                if !crate::shading::scatter_allowed(hit.ng, wi, wo_l, wi_l) {
                    return Vec3::ZERO;
                }
                bsdf.f_mode(wo_l, wi_l, mode)
                    * shading_normal_correction(mode, wo_world, wi, frame.z, hit.ng)
                    * frame.shadowing(toward_light(mode, wo_world, wi))
            }
            VertexKind::Light { light, le } => {
                emitted_toward(scene.lights.get(light), le, self.ns, wi)
            }
            _ => Vec3::ZERO,
        }
    }

    /// Converts a solid-angle density at this vertex toward `next` into a
    /// density per unit area at `next`.
    pub fn area_density(&self, pdf_dir: f32, next: &Vertex) -> f32 {
        if next.infinite {
            return pdf_dir;
        }
        let d = next.p - self.p;
        let dist2 = d.length_squared();
        if dist2 == 0.0 {
            return 0.0;
        }
        let mut pdf = pdf_dir / dist2;
        if next.on_surface() {
            pdf *= next.ng.dot(d / dist2.sqrt()).abs();
        }
        pdf
    }

    /// Density per unit area with which this vertex, reached from `prev`,
    /// samples `next` (Veach's p(x_i → x_{i+1} | x_{i−1})).
    pub fn pdf(&self, scene: &Scene, prev: Option<&Vertex>, next: &Vertex) -> f32 {
        let wn = if next.infinite {
            -next.ns
        } else {
            (next.p - self.p).normalize_or_zero()
        };
        let pdf_dir = match self.kind {
            VertexKind::Light { .. } | VertexKind::Sky => return self.pdf_light(scene, next),
            VertexKind::Camera => scene.camera.pdf_we(&Ray::new(self.p, wn)).1,
            VertexKind::Surface {
                frame, ref bsdf, ..
            } => {
                let (Some(bsdf), Some(prev)) = (bsdf, prev) else {
                    return 0.0;
                };
                let wp = (prev.p - self.p).normalize_or_zero();
                bsdf.pdf(frame.to_local(wp), frame.to_local(wn))
            }
        };
        self.area_density(pdf_dir, next)
    }

    /// The light (if any) this vertex is on: a light vertex's own, an
    /// emitting surface's.
    pub fn light_index(&self, scene: &Scene) -> Option<u32> {
        match self.kind {
            VertexKind::Light { light, .. } => Some(light),
            VertexKind::Surface { hit, .. } => scene.lights.light_of_prim(hit.prim),
            _ => None,
        }
    }

    /// Density per unit area at `next` of the direction a light subpath
    /// starting at this (light) vertex takes toward `next`.
    pub fn pdf_light(&self, scene: &Scene, next: &Vertex) -> f32 {
        let bounds = scene.scene_sphere();
        let w = next.p - self.p;
        let dist2 = w.length_squared();
        let w = if self.infinite {
            self.ns
        } else {
            w / dist2.sqrt()
        };
        let cos_next = if next.on_surface() {
            next.ng.dot(w).abs()
        } else {
            1.0
        };
        if self.infinite {
            // The entry point is uniform on the scene's disk.
            let r = bounds.radius;
            return cos_next / (std::f32::consts::PI * r * r);
        }
        let Some(index) = self.light_index(scene) else {
            return 0.0;
        };
        let (_, pdf_dir) = scene.lights.get(index).pdf_le(self.p, self.ns, w, &bounds);
        pdf_dir * cos_next / dist2
    }

    /// Density per unit area (times the choice of the light) with which a
    /// light subpath starts at this vertex; for lights at infinity, the
    /// density of the direction toward `next` summed over them.
    pub fn pdf_light_origin(&self, scene: &Scene, next: &Vertex) -> f32 {
        let bounds = scene.scene_sphere();
        if self.infinite {
            return infinite_light_density(scene, self.ns);
        }
        let Some(index) = self.light_index(scene) else {
            return 0.0;
        };
        let w = (next.p - self.p).normalize_or_zero();
        let (pdf_pos, _) = scene.lights.get(index).pdf_le(self.p, self.ns, w, &bounds);
        scene.lights.emitter_pmf(index) * pdf_pos
    }

    /// Radiance emitted from this vertex toward `toward` (a point): an
    /// emitting surface's front side, or the sky along [`VertexKind::Sky`].
    pub fn le(&self, scene: &Scene, toward: Vec3) -> Vec3 {
        match self.kind {
            VertexKind::Sky => scene
                .lights
                .infinite_lights()
                .map(|i| scene.lights.get(i).le(-self.ns))
                .sum(),
            VertexKind::Surface { hit, .. }
                if hit.front_face && self.light_index(scene).is_some() =>
            {
                let _ = toward;
                scene
                    .material(hit.material)
                    .emission_at(hit.texture_point())
                    .unwrap_or(Vec3::ZERO)
            }
            _ => Vec3::ZERO,
        }
    }
}

/// Density of the lights at infinity emitting along `w` (a ray travelling
/// in direction `w`): Σ pmf · pdf_dir over them.
pub(crate) fn infinite_light_density(scene: &Scene, w: Vec3) -> f32 {
    let bounds = scene.scene_sphere();
    scene
        .lights
        .infinite_lights()
        .map(|i| {
            let light = scene.lights.get(i);
            if light.is_delta() {
                return 0.0;
            }
            scene.lights.emitter_pmf(i) * light.pdf_le(Vec3::ZERO, w, w, &bounds).1
        })
        .sum()
}

/// Radiance (intensity for point and spot lights) a light with emission
/// `le` at a point of normal `n` sends toward `w`: one-sided emitters only
/// on their normal's side, spots inside their cone with their falloff.
pub(crate) fn emitted_toward(light: &Light, le: Vec3, n: Vec3, w: Vec3) -> Vec3 {
    match light {
        Light::Area(_) => {
            if n.dot(w) > 0.0 {
                le
            } else {
                Vec3::ZERO
            }
        }
        Light::Point(p) => p.intensity,
        Light::Spot(s) => {
            let cos = w.dot(s.direction);
            if cos < s.cos_cutoff {
                Vec3::ZERO
            } else if s.exponent > 0.0 {
                s.intensity * cos.max(0.0).powf(s.exponent)
            } else {
                s.intensity
            }
        }
        Light::Directional(_) | Light::Ambient(_) | Light::Environment(_) => le,
    }
}

/// Of a surface vertex's two directions, `wo` toward its predecessor on
/// the subpath and `wi` toward its successor, the one toward the light:
/// a camera subpath (radiance) reaches the light after the vertex, a light
/// subpath (importance) came from it. The bump shadowing
/// (`ShadingFrame::shadowing`) is not reciprocal: it attenuates the light
/// side, as in the path tracer, so every strategy weighs a path alike.
pub fn toward_light(mode: TransportMode, wo: Vec3, wi: Vec3) -> Vec3 {
    match mode {
        TransportMode::Radiance => wi,
        TransportMode::Importance => wo,
    }
}
