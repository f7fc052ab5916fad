//! Materials as the renderer uses them: a BSDF (or none, for pure
//! emitters), an optional emitted radiance, and the textures of the
//! description's slots, looked up at each hit's `uv`.
//!
//! The description has a texture slot per parameter
//! ([`candela_scene::TextureSlot`]); every slot is read
//! ([`crate::shading::MaterialTextures`], whose docs say what each slot
//! drives on each BSDF). A slot the material's BSDF has no parameter for
//! is returned by name as [`Unsupported`] (the scene reports it once),
//! never dropped silently.

use crate::bsdf::{
    Blend, Bsdf, Masking, MetallicRoughness, MicrofacetDistribution, Plastic, Principled,
    RoughPlastic,
};
use crate::shading::MaterialTextures;
use crate::shape::SurfaceHit;
use crate::texture::{TextureCache, TexturePoint};
use candela_scene::{Alpha, BsdfDesc, MaterialDesc, MicrofacetModel, Sides};
use glam::Vec3;

/// A material ready for shading.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// The scattering model; `None` absorbs everything.
    pub bsdf: Option<Bsdf>,
    /// Radiance emitted on the side of the surface normal; with an
    /// emission texture, its mean (the light's power for light selection;
    /// [`Material::emission_at`] gives the value at a point).
    pub emission: Option<Vec3>,
    /// The textures of the description's slots.
    pub textures: MaterialTextures,
    /// What scatters behind the surface (see [`Material::facing`]).
    pub back: Back,
    /// Whether the BSDF's roughness differs along the two tangents, so its
    /// shading frame must follow the surface's dp/du.
    pub anisotropic: bool,
    /// An invisible surface ([`BsdfDesc::Null`]): every ray passes through
    /// it (`shading/opacity.rs`); one that emits is still met by the
    /// integrators' closest-hit queries, which add its emission and go on
    /// past it (`scene/visibility.rs`).
    pub invisible: bool,
    /// For a blend, its two parts as materials (their BSDFs, textures and
    /// sides), mixed per hit by [`Material::bsdf_at`]; `bsdf` then holds
    /// the blend of their untextured front BSDFs (its weight the
    /// constant, its flags the union).
    pub parts: Option<Box<[Material; 2]>>,
}

/// What a surface does seen from behind its shading normal.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum Back {
    /// The same BSDF, as if the surface faced the viewer (two-sided).
    #[default]
    Same,
    /// Nothing: black, like a BSDF with no value (one-sided).
    Black,
    /// Another material's BSDF and textures, turned to face the viewer.
    Other(Box<Material>),
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
        textures_cache: &mut TextureCache,
    ) -> (Material, Vec<Unsupported>) {
        let mut unsupported = Vec::new();
        let mut parts = None;
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
                masking: Masking::HeightCorrelated,
                eta,
                k,
            }),
            BsdfDesc::RoughDielectric {
                distribution,
                masking,
                alpha,
                ior,
                reflectance,
                transmittance,
            } => Some(Bsdf::RoughGlass {
                distribution: microfacets(distribution, alpha),
                masking,
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
                masking,
                internal_reflectance,
                nonlinear,
            } => Some(if alpha > 0.0 {
                Bsdf::RoughPlastic(RoughPlastic::with_conventions(
                    microfacets(distribution, Alpha::isotropic(alpha)),
                    masking,
                    internal_reflectance,
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
                masking,
                alpha,
                eta,
                k,
            } if alpha.is_rough() => Some(Bsdf::Microfacet {
                distribution: microfacets(distribution, alpha),
                masking,
                eta,
                k,
            }),
            BsdfDesc::Conductor { eta, k, .. } => Some(Bsdf::Conductor { eta, k }),
            BsdfDesc::Black | BsdfDesc::Null => None,
            BsdfDesc::MetallicRoughness {
                base_color,
                metallic,
                roughness,
                transmission,
                ior,
                specular,
                specular_color,
                clearcoat,
                clearcoat_roughness,
                sheen_color,
                sheen_roughness,
            } => Some(Bsdf::MetallicRoughness(
                MetallicRoughness::new(base_color, metallic, roughness, transmission, ior)
                    .with_specular(specular, specular_color)
                    .with_sheen(sheen_color, sheen_roughness)
                    .with_clearcoat(clearcoat, clearcoat_roughness),
            )),
            BsdfDesc::Principled(p) => Some(Bsdf::Principled(Principled::new(p))),
            BsdfDesc::Blend(ref blend) => {
                let [a, b] = blend.parts.each_ref().map(|part| {
                    let (mut m, more) = Material::from_desc(part, textures_cache);
                    unsupported.extend(more);
                    m.emission = None;
                    m
                });
                let template = Blend::new(blend.weight, a.bsdf.clone(), b.bsdf.clone());
                parts = Some(Box::new([a, b]));
                Some(Bsdf::Blend(Box::new(template)))
            }
        };
        let (textures, unusable) =
            MaterialTextures::from_slots(&desc.textures, bsdf.as_ref(), textures_cache);
        for slot in unusable {
            unsupported.push(Unsupported(format!(
                "material '{}': {} texture has no parameter to drive on this BSDF (ignored)",
                desc.name,
                slot.name()
            )));
        }
        let emission = match &textures.emission {
            Some(t) => Some(t.mean_color()),
            None => desc.emission,
        }
        .filter(|e| e.max_element() > 0.0);
        let back = match &desc.sides {
            Sides::Both => Back::Same,
            Sides::Front => Back::Black,
            Sides::Back(back) => {
                let (mut back, more) = Material::from_desc(back, textures_cache);
                unsupported.extend(more);
                back.emission = None;
                back.back = Back::Same;
                Back::Other(Box::new(back))
            }
        };
        let anisotropic = bsdf.as_ref().is_some_and(Bsdf::is_anisotropic)
            || parts
                .as_ref()
                .is_some_and(|p| p.iter().any(Material::any_side_anisotropic));
        (
            Material {
                bsdf,
                emission,
                textures,
                back,
                anisotropic,
                invisible: desc.bsdf == BsdfDesc::Null,
                parts,
            },
            unsupported,
        )
    }

    /// The material that scatters at `hit`: this one when the viewer (`wo`)
    /// is in front of the shading normal, else what [`Material::back`] says
    /// (`None` for a one-sided material seen from behind). Everything a hit
    /// is shaded with (its BSDF, its shading frame) comes through here, so
    /// light samples, BSDF samples and their MIS weights all see the same
    /// side.
    #[inline]
    pub fn facing(&self, hit: &SurfaceHit) -> Option<&Material> {
        if hit.front_face {
            return Some(self);
        }
        match &self.back {
            Back::Same => Some(self),
            Back::Black => None,
            Back::Other(back) => Some(back),
        }
    }

    /// The BSDF at a hit point, on the side the hit sees
    /// ([`Material::facing`]), with every textured parameter read at the
    /// hit's `uv`; `None` where nothing scatters. A copy: see
    /// [`Material::bsdf_in`] for the borrow the render loop takes.
    pub fn bsdf_at(&self, hit: &SurfaceHit) -> Option<Bsdf> {
        self.bsdf_in(hit, &mut None).cloned()
    }

    /// [`Material::bsdf_at`] without a copy: the material's own BSDF,
    /// borrowed, where nothing changes it at the hit; else the BSDF made
    /// for the hit (textured, or a blend's), stored in `made` and
    /// borrowed from there. `Bsdf` is not `Copy` (a blend boxes its
    /// parts), so a copy per vertex would be a clone through a `match` on
    /// the model; the borrow costs nothing.
    #[inline]
    pub fn bsdf_in<'a>(&'a self, hit: &SurfaceHit, made: &'a mut Option<Bsdf>) -> Option<&'a Bsdf> {
        let side = self.facing(hit)?;
        if side.parts.is_some() {
            return Some(made.insert(side.blend_at(hit)?));
        }
        let bsdf = side.bsdf.as_ref()?;
        if !side.textures.textures_bsdf() {
            return Some(bsdf); // untextured: no call, no copy
        }
        Some(made.insert(side.textures.apply(bsdf.clone(), hit.texture_point())))
    }

    /// A blend's BSDF at `hit`: each part's own BSDF there (on the side the
    /// hit sees, textured; none where that part is black), mixed by the
    /// weight there. `None` when both parts are black (or this is no
    /// blend). Out of line: it recurses through [`Material::bsdf_at`],
    /// which must stay small enough to inline into the render loop.
    #[inline(never)]
    fn blend_at(&self, hit: &SurfaceHit) -> Option<Bsdf> {
        let parts = self.parts.as_ref()?;
        let [a, b] = parts.each_ref().map(|p| p.bsdf_at(hit));
        if a.is_none() && b.is_none() {
            return None;
        }
        let weight = match (&self.textures.weight, &self.bsdf) {
            (Some(t), _) => t.color(hit.texture_point()).dot(LUMINANCE),
            (None, Some(Bsdf::Blend(template))) => template.weight,
            (None, _) => 0.0,
        };
        Some(Bsdf::Blend(Box::new(Blend::new(weight, a, b))))
    }

    /// Whether the BSDF on either side is anisotropic.
    fn any_side_anisotropic(&self) -> bool {
        self.anisotropic || matches!(&self.back, Back::Other(b) if b.any_side_anisotropic())
    }

    /// The radiance emitted at a point (on the emitting side): the
    /// emission texture's value there, else the constant.
    pub fn emission_at(&self, at: impl Into<TexturePoint>) -> Option<Vec3> {
        self.emission?;
        self.textures.emission(at).or(self.emission)
    }
}

/// Rec. 709 luminance weights: how Mitsuba reads a colour texture as one
/// value (a blend's weight).
const LUMINANCE: Vec3 = Vec3::new(0.2126, 0.7152, 0.0722);

/// CS184 glass: smooth, or with `roughness` r > 0 a Beckmann rough
/// dielectric of α = r (the convention of CS184's `<microfacet>` alpha).
fn glass(reflectance: Vec3, transmittance: Vec3, roughness: f32, ior: f32) -> Bsdf {
    if roughness > 0.0 {
        Bsdf::RoughGlass {
            distribution: MicrofacetDistribution::beckmann(roughness),
            masking: Masking::HeightCorrelated,
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

/// The distribution a description names, with roughness `alpha` (its `u`
/// along the shading frame's x, which follows dp/du when they differ).
fn microfacets(model: MicrofacetModel, alpha: Alpha) -> MicrofacetDistribution {
    let (alpha_x, alpha_y) = (alpha.u, alpha.v);
    match model {
        MicrofacetModel::Beckmann => MicrofacetDistribution::Beckmann { alpha_x, alpha_y },
        MicrofacetModel::Ggx => MicrofacetDistribution::Ggx { alpha_x, alpha_y },
    }
}
