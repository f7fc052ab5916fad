//! Materials as the renderer uses them: a BSDF (or none, for pure
//! emitters), an optional emitted radiance.

use crate::bsdf::Bsdf;
use crate::scene::SurfaceHit;
use candela_scene::{BsdfDesc, MaterialDesc};
use glam::Vec3;

/// A material ready for shading.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// The scattering model; `None` absorbs everything.
    pub bsdf: Option<Bsdf>,
    /// Radiance emitted on the side of the surface normal.
    pub emission: Option<Vec3>,
}

/// The subset of a description this renderer cannot honour yet, by name.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Unsupported(pub String);

impl Material {
    /// Converts a material description. Parameters the renderer cannot use
    /// are returned by name so the caller can report them once.
    pub fn from_desc(desc: &MaterialDesc) -> (Material, Vec<Unsupported>) {
        let mut unsupported = Vec::new();
        let bsdf = match desc.bsdf {
            BsdfDesc::Diffuse { albedo } => Some(Bsdf::Diffuse {
                albedo: albedo.clamp(Vec3::ZERO, Vec3::ONE),
            }),
            BsdfDesc::Mirror { reflectance } => Some(Bsdf::Mirror { reflectance }),
            BsdfDesc::Glass {
                reflectance,
                transmittance,
                roughness,
                ior,
            } => {
                if roughness > 0.0 {
                    unsupported.push(Unsupported(format!(
                        "material '{}': rough glass (roughness {roughness}; rendered smooth)",
                        desc.name
                    )));
                }
                Some(Bsdf::Glass {
                    reflectance,
                    transmittance,
                    ior,
                })
            }
            BsdfDesc::Refraction {
                transmittance,
                roughness,
                ior,
            } => {
                if roughness > 0.0 {
                    unsupported.push(Unsupported(format!(
                        "material '{}': rough refraction (roughness {roughness}; rendered smooth)",
                        desc.name
                    )));
                }
                Some(Bsdf::Refraction { transmittance, ior })
            }
            BsdfDesc::Microfacet { alpha, eta, k } => Some(Bsdf::Microfacet { alpha, eta, k }),
            BsdfDesc::Black => None,
        };
        if desc.diffuse_texture.is_some() {
            unsupported.push(Unsupported(format!(
                "material '{}': diffuse texture (using the flat colour)",
                desc.name
            )));
        }
        let emission = desc.emission.filter(|e| e.max_element() > 0.0);
        (Material { bsdf, emission }, unsupported)
    }

    /// The BSDF at a hit point (where textures will be looked up).
    pub fn bsdf_at(&self, _hit: &SurfaceHit) -> Option<Bsdf> {
        self.bsdf
    }
}
