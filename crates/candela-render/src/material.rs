//! Materials as the renderer uses them: a BSDF (or none, for pure
//! emitters), an optional emitted radiance, and an optional image texture
//! for the diffuse colour, looked up at each hit's `uv`.
//!
//! The description has a texture slot per parameter
//! ([`candela_scene::TextureSlot`]); each slot is read here. Only the colour
//! of a diffuse BSDF is textured so far: every other filled slot is
//! returned by name as [`Unsupported`] (the scene reports it once), never
//! dropped silently.

use crate::bsdf::{Bsdf, MicrofacetDistribution, Plastic, RoughPlastic};
use crate::shape::SurfaceHit;
use crate::texture::{ImageTexture, TextureCache};
use candela_scene::{BsdfDesc, MaterialDesc, MicrofacetModel, TextureSlot};
use glam::Vec3;
use std::sync::Arc;

/// A material ready for shading.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// The scattering model; `None` absorbs everything.
    pub bsdf: Option<Bsdf>,
    /// Radiance emitted on the side of the surface normal.
    pub emission: Option<Vec3>,
    /// Diffuse colour by texture (replacing a diffuse BSDF's flat albedo),
    /// shared by every material that names the same file.
    pub diffuse_texture: Option<Arc<ImageTexture>>,
    /// Factor on the diffuse texture's (linear) values: the slot's scale.
    pub diffuse_scale: f32,
}

/// The subset of a description this renderer cannot honour yet, by name.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Unsupported(pub String);

impl Material {
    /// Converts a material description, reading its texture through
    /// `textures` (a texture that cannot be read leaves the flat colour and
    /// a message in the cache). Parameters the renderer cannot use are
    /// returned by name so the caller can report them once.
    pub fn from_desc(
        desc: &MaterialDesc,
        textures: &mut TextureCache,
    ) -> (Material, Vec<Unsupported>) {
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
            } => Some(glass(reflectance, transmittance, roughness, ior)),
            // Refraction alone has no rough counterpart: rough, it becomes
            // rough glass whose reflection is absorbed.
            BsdfDesc::Refraction {
                transmittance,
                roughness,
                ior,
            } if roughness > 0.0 => Some(glass(Vec3::ZERO, transmittance, roughness, ior)),
            BsdfDesc::Refraction {
                transmittance, ior, ..
            } => Some(Bsdf::Refraction { transmittance, ior }),
            BsdfDesc::Microfacet { alpha, eta, k } => Some(Bsdf::Microfacet {
                distribution: MicrofacetDistribution::beckmann(alpha),
                eta,
                k,
            }),
            BsdfDesc::RoughDielectric {
                distribution,
                alpha,
                ior,
                reflectance,
                transmittance,
            } => Some(Bsdf::RoughGlass {
                distribution: microfacets(distribution, alpha),
                reflectance,
                transmittance,
                ior,
            }),
            BsdfDesc::ThinDielectric {
                ior,
                reflectance,
                transmittance,
            } => Some(Bsdf::ThinGlass {
                reflectance,
                transmittance,
                ior,
            }),
            BsdfDesc::Plastic {
                diffuse,
                specular,
                ior,
                alpha,
                distribution,
                nonlinear,
            } => Some(if alpha > 0.0 {
                Bsdf::RoughPlastic(RoughPlastic::new(
                    microfacets(distribution, alpha),
                    diffuse,
                    specular,
                    ior,
                    nonlinear,
                ))
            } else {
                Bsdf::Plastic(Plastic::new(diffuse, specular, ior).with_nonlinear(nonlinear))
            }),
            BsdfDesc::Conductor {
                distribution,
                alpha,
                eta,
                k,
            } if alpha > 0.0 => Some(Bsdf::Microfacet {
                distribution: microfacets(distribution, alpha),
                eta,
                k,
            }),
            BsdfDesc::Conductor { eta, k, .. } => Some(Bsdf::Conductor { eta, k }),
            BsdfDesc::Black => None,
        };
        let (mut diffuse_texture, mut diffuse_scale) = (None, 1.0);
        for (slot, t) in desc.textures.iter() {
            match (slot, &bsdf) {
                (TextureSlot::Color, Some(Bsdf::Diffuse { .. })) => {
                    diffuse_texture = textures.get_in(&t.path, t.color_space);
                    diffuse_scale = t.scale;
                }
                (TextureSlot::Color, _) => unsupported.push(Unsupported(format!(
                    "material '{}': colour texture on a non-diffuse BSDF (ignored)",
                    desc.name
                ))),
                (other, _) => unsupported.push(Unsupported(format!(
                    "material '{}': {} texture not supported yet (ignored)",
                    desc.name,
                    other.name()
                ))),
            }
        }
        let emission = desc.emission.filter(|e| e.max_element() > 0.0);
        (
            Material {
                bsdf,
                emission,
                diffuse_texture,
                diffuse_scale,
            },
            unsupported,
        )
    }

    /// The BSDF at a hit point: a textured diffuse material takes its
    /// albedo from the texture at the hit's `uv`, times the slot's scale
    /// (clamped to [0, 1] so it never creates energy).
    pub fn bsdf_at(&self, hit: &SurfaceHit) -> Option<Bsdf> {
        match (&self.bsdf, &self.diffuse_texture) {
            (Some(Bsdf::Diffuse { .. }), Some(texture)) => Some(Bsdf::Diffuse {
                albedo: (texture.lookup(hit.uv) * self.diffuse_scale).clamp(Vec3::ZERO, Vec3::ONE),
            }),
            _ => self.bsdf,
        }
    }
}

/// CS184 glass: smooth, or with `roughness` r > 0 a Beckmann rough
/// dielectric of α = r (the convention of CS184's `<microfacet>` alpha).
fn glass(reflectance: Vec3, transmittance: Vec3, roughness: f32, ior: f32) -> Bsdf {
    if roughness > 0.0 {
        Bsdf::RoughGlass {
            distribution: MicrofacetDistribution::beckmann(roughness),
            reflectance,
            transmittance,
            ior,
        }
    } else {
        Bsdf::Glass {
            reflectance,
            transmittance,
            ior,
        }
    }
}

/// The distribution a description names, with roughness `alpha`.
fn microfacets(model: MicrofacetModel, alpha: f32) -> MicrofacetDistribution {
    match model {
        MicrofacetModel::Beckmann => MicrofacetDistribution::beckmann(alpha),
        MicrofacetModel::Ggx => MicrofacetDistribution::ggx(alpha),
    }
}
