//! The recorder that turns the path integrator's events into a
//! [`PathRecord`].

use super::records::{
    Contribution, EmissionRecord, EscapeRecord, HemisphereRecord, LightSampleRecord, PathRecord,
    RayRecord, RouletteRecord, ScatterRecord, Strategy, VertexRecord,
};
use crate::bsdf::BsdfFlags;
use crate::geometry::Ray;
use crate::integrator::record::{
    EmissionEvent, HemisphereEvent, LightSampleEvent, PathEnd, PathRecorder, ScatterEvent,
};
use crate::scene::Scene;
use crate::shape::SurfaceHit;
use glam::{Vec2, Vec3};

/// The lobe a BSDF sample chose, in words.
fn lobe_name(flags: BsdfFlags) -> String {
    let kind = if flags.is_specular() {
        "specular"
    } else if flags.intersects(BsdfFlags::GLOSSY) {
        "glossy"
    } else {
        "diffuse"
    };
    let side = if flags.is_transmission() {
        "transmission"
    } else {
        "reflection"
    };
    format!("{kind} {side}")
}

fn ray_record(ray: &Ray) -> RayRecord {
    RayRecord {
        origin: ray.origin.to_array(),
        direction: ray.dir.to_array(),
    }
}

/// The recorder that builds a [`PathRecord`].
pub(super) struct Recording<'a> {
    scene: &'a Scene,
    pub(super) record: PathRecord,
    /// Throughput of the current vertex (or of the escaping ray).
    beta: Vec3,
}

impl<'a> Recording<'a> {
    pub(super) fn new(scene: &'a Scene, pixel: (u32, u32), sample: u32) -> Self {
        Self {
            scene,
            record: PathRecord {
                pixel,
                sample,
                film: [0.0; 2],
                camera_ray: RayRecord::default(),
                vertices: Vec::new(),
                escape: None,
                contributions: Vec::new(),
                end: PathEnd::Escaped,
                radiance: [0.0; 3],
                value: [0.0; 3],
            },
            beta: Vec3::ONE,
        }
    }

    fn light_name(&self, index: u32) -> String {
        self.scene.names.light(index)
    }

    /// Adds a contribution if it is non-zero; `at_vertex` false for light
    /// seen by the escaping ray.
    fn contribute(
        &mut self,
        at_vertex: bool,
        bounces: u32,
        strategy: Strategy,
        light: Option<String>,
        value: Vec3,
    ) {
        if value == Vec3::ZERO {
            return;
        }
        let vertex = at_vertex.then(|| self.record.vertices.len() - 1);
        self.record.contributions.push(Contribution {
            vertex,
            bounces,
            strategy,
            light,
            value: value.to_array(),
        });
    }

    fn last_vertex(&mut self) -> Option<&mut VertexRecord> {
        self.record.vertices.last_mut()
    }
}

impl PathRecorder for Recording<'_> {
    fn camera(&mut self, film: Vec2, ray: &Ray) {
        self.record.film = film.to_array();
        self.record.camera_ray = ray_record(ray);
    }

    fn vertex(&mut self, scene: &Scene, depth: u32, _ray: &Ray, hit: &SurfaceHit, beta: Vec3) {
        self.beta = beta;
        let material = scene.material(hit.material);
        let surface = material
            .bsdf_at(hit)
            .map_or("emitter", |bsdf| bsdf.name())
            .to_string();
        self.record.vertices.push(VertexRecord {
            depth,
            position: hit.p.to_array(),
            distance: hit.t,
            geometric_normal: hit.ng.to_array(),
            shading_normal: hit.ns.to_array(),
            front_face: hit.front_face,
            shape: scene.names.shape(hit.prim),
            material: scene.names.material(hit.material),
            surface,
            throughput: beta.to_array(),
            emission: None,
            light_samples: Vec::new(),
            hemisphere_rays: Vec::new(),
            scatter: None,
            roulette: None,
        });
    }

    fn escape(&mut self, depth: u32, ray: &Ray, beta: Vec3) {
        self.beta = beta;
        self.record.escape = Some(EscapeRecord {
            depth,
            ray: ray_record(ray),
            throughput: beta.to_array(),
            environment: Vec::new(),
        });
    }

    fn emission(&mut self, e: &EmissionEvent) {
        let contribution = self.beta * e.value;
        let light = e.light.map(|i| self.light_name(i));
        let record = EmissionRecord {
            light: light.clone(),
            radiance: e.radiance.to_array(),
            mis_weight: e.mis_weight,
            contribution: contribution.to_array(),
        };
        if let Some(escape) = &mut self.record.escape {
            let bounces = escape.depth;
            escape.environment.push(record);
            self.contribute(false, bounces, Strategy::Environment, light, contribution);
        } else if let Some(vertex) = self.last_vertex() {
            let bounces = vertex.depth;
            vertex.emission = Some(record);
            self.contribute(true, bounces, Strategy::Emission, light, contribution);
        }
    }

    fn light_sample(&mut self, e: &LightSampleEvent) {
        let contribution = self.beta * e.value * e.scale;
        let light = self.light_name(e.light);
        let delta = self.scene.lights.get(e.light).is_delta();
        let Some(vertex) = self.last_vertex() else {
            return;
        };
        let origin = Vec3::from_array(vertex.position);
        let bounces = vertex.depth + 1;
        vertex.light_samples.push(LightSampleRecord {
            light: light.clone(),
            delta,
            direction: e.wi.to_array(),
            point: e
                .distance
                .is_finite()
                .then(|| (origin + e.wi * e.distance).to_array()),
            radiance: e.radiance.to_array(),
            pdf: e.pdf,
            bsdf: e.f.to_array(),
            bsdf_pdf: e.bsdf_pdf,
            mis_weight: e.mis_weight,
            visible: e.visible,
            contribution: contribution.to_array(),
        });
        let strategy = if delta {
            Strategy::DeltaLight
        } else {
            Strategy::LightSample
        };
        self.contribute(true, bounces, strategy, Some(light), contribution);
    }

    fn hemisphere_ray(&mut self, e: &HemisphereEvent) {
        let contribution = self.beta * e.value * e.scale;
        let Some(vertex) = self.last_vertex() else {
            return;
        };
        let bounces = vertex.depth + 1;
        vertex.hemisphere_rays.push(HemisphereRecord {
            direction: e.wi.to_array(),
            pdf: e.pdf,
            bsdf: e.f.to_array(),
            traced: e.traced,
            hit: e.hit.map(|p| p.to_array()),
            radiance: e.radiance.to_array(),
            contribution: contribution.to_array(),
        });
        self.contribute(true, bounces, Strategy::Hemisphere, None, contribution);
    }

    fn scatter(&mut self, e: &ScatterEvent) {
        if let Some(vertex) = self.last_vertex() {
            vertex.scatter = Some(ScatterRecord {
                lobe: lobe_name(e.sample.flags),
                direction: e.wi.to_array(),
                bsdf: e.sample.f.to_array(),
                pdf: e.sample.pdf,
                cos: e.sample.wi.z.abs(),
                throughput: e.beta.to_array(),
            });
        }
    }

    fn roulette(&mut self, survive: f32, survived: bool, beta: Vec3) {
        if let Some(vertex) = self.last_vertex() {
            vertex.roulette = Some(RouletteRecord {
                survival_probability: survive,
                survived,
                throughput: beta.to_array(),
            });
        }
    }

    fn end(&mut self, end: PathEnd, radiance: Vec3) {
        self.record.end = end;
        self.record.radiance = radiance.to_array();
    }
}
