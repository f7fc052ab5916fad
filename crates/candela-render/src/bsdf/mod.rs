//! BSDFs in a local shading frame.
//!
//! # Conventions (fixed here, relied on everywhere)
//!
//! - **Frame**: directions are in the local shading frame of
//!   [`crate::geometry::Frame`], whose +Z is the shading normal. Build it
//!   from the surface's *outward* normal (the side the geometry defines).
//! - **Directions**: `wo` points toward the viewer (where the path came
//!   from), `wi` toward the light (where it continues); both point *away*
//!   from the surface and are unit vectors. (Mitsuba's `si.wi` is our `wo`.)
//! - **`f` excludes the cosine**: the integrator multiplies by |cos θi| =
//!   `wi.z.abs()`. [`BsdfSample::weight`] is `f·|cos θi|/pdf`.
//! - **Random numbers are arguments** (`u1` picks a lobe, `u2` the direction
//!   within it), never drawn inside, so sampling is deterministic and
//!   testable.
//! - **Two-sided shading**: every BSDF accepts `wo` on either side. Opaque
//!   BSDFs (diffuse, mirror, conductor) behave as if the frame were flipped
//!   so that `wo.z > 0`, so a caller *may* flip the frame for them, but need
//!   not. Dielectrics ([`Bsdf::Glass`], [`Bsdf::Refraction`],
//!   [`Bsdf::RoughGlass`], and the transmissive [`Bsdf::MetallicRoughness`]
//!   and [`Bsdf::Principled`]) read the side
//!   of `wo` to know whether the path is entering (`wo.z > 0`, relative IOR
//!   `ior`) or leaving (`wo.z < 0`, relative IOR `1 / ior`), so the caller
//!   **must not flip** the frame for them. The safe rule: never flip.
//!   One-sided materials (black from behind) and materials with another
//!   BSDF on the back are decided a level up, by which BSDF the material
//!   hands out at a hit (`Material::facing`), not here.
//! - **Radiance transport**: the path tracer carries radiance from lights to
//!   the camera, so refraction scales by `1/η²` with η the relative IOR
//!   (transmitted side over incident side of the light path as traced from
//!   the camera); the adjoint (importance) transport of light subpaths omits
//!   that factor ([`TransportMode`], `transport.rs`).
//!   Transmission then obeys the generalised reciprocity
//!   f(wo, wi)·η(wi)² = f(wi, wo)·η(wo)², η(w) the absolute IOR on the side
//!   of w; energy is conserved once refracted throughput is multiplied back
//!   by η² (what the furnace tests check).
//! - **Delta lobes** (flag [`BsdfFlags::SPECULAR`]): `f` and `pdf` return
//!   zero for every given pair; `sample` returns the one direction with
//!   `f = weight / |cos θi|` and `pdf` the discrete probability of choosing
//!   that lobe (1 for a single lobe), so `weight()` works uniformly.

mod beckmann;
mod blend;
#[cfg(test)]
mod blend_tests;
mod clear_coat;
#[cfg(test)]
mod clear_coat_tests;
mod coating;
mod diffuse;
#[cfg(test)]
mod diffuse_tests;
mod distribution;
#[cfg(test)]
mod distribution_tests;
mod flags;
mod fresnel;
#[cfg(test)]
mod furnace_tests;
mod ggx;
#[cfg(test)]
mod lobe_choice_tests;
#[cfg(test)]
mod masking_tests;
mod metallic_roughness;
#[cfg(test)]
mod metallic_roughness_tests;
mod microfacet;
#[cfg(test)]
mod microfacet_tests;
mod plastic;
#[cfg(test)]
mod plastic_tests;
mod principled;
mod rough_dielectric;
#[cfg(test)]
mod rough_dielectric_tests;
mod rough_plastic;
#[cfg(test)]
mod rough_plastic_tests;
mod sheen;
mod sheen_albedo;
#[cfg(test)]
mod sheen_tests;
mod special;
mod specular;
mod specular_albedo;
#[cfg(test)]
mod specular_tests;
#[cfg(test)]
mod test_support;
#[cfg(test)]
mod thin_dielectric_tests;
mod transport;
#[cfg(test)]
mod transport_tests;

pub use blend::Blend;
pub use coating::InternalReflectance;
pub use distribution::Masking;
pub use distribution::{MicrofacetDistribution, MIN_ALPHA};
pub use flags::BsdfFlags;
pub use metallic_roughness::MetallicRoughness;
pub use plastic::Plastic;
pub use principled::{Principled, PrincipledParameters};
pub use rough_plastic::RoughPlastic;
pub use transport::{shading_normal_correction, TransportMode};

use rough_dielectric::RoughDielectric;

use glam::{Vec2, Vec3};

/// One sampled scattering direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BsdfSample {
    /// The sampled direction toward the light, in the local frame.
    pub wi: Vec3,
    /// The BSDF value for (wo, wi), cosine excluded.
    pub f: Vec3,
    /// The density of `wi` per unit solid angle, or for a delta lobe the
    /// discrete probability of having chosen it.
    pub pdf: f32,
    /// The kind of lobe that was sampled.
    pub flags: BsdfFlags,
}

impl BsdfSample {
    /// The sample of a mixture of lobes at `wi`, drawn from lobe `lobe`:
    /// valued and weighed by the whole mixture (`f`, `pdf`: every lobe's
    /// value and density there, as one-sample MIS needs), reflection or
    /// transmission by the side of `wi`; `None` where the density is zero
    /// or not finite.
    pub(super) fn of_mixture(
        wo: Vec3,
        wi: Vec3,
        lobe: BsdfFlags,
        pdf: f32,
        f: impl FnOnce() -> Vec3,
    ) -> Option<Self> {
        if !(pdf > 0.0 && pdf.is_finite()) {
            return None;
        }
        let side = if wi.z * wo.z < 0.0 {
            BsdfFlags::TRANSMISSION
        } else {
            BsdfFlags::REFLECTION
        };
        Some(Self {
            wi,
            f: f(),
            pdf,
            flags: side.union(lobe),
        })
    }

    /// The throughput multiplier `f·|cos θi| / pdf`.
    pub fn weight(&self) -> Vec3 {
        self.f * (self.wi.z.abs() / self.pdf)
    }

    /// Whether the sample came from a delta lobe.
    pub fn is_specular(&self) -> bool {
        self.flags.is_specular()
    }
}

/// The closed set of scattering models, as plain values: cheap to clone
/// (a copy of bytes but for a blend's boxed parts), `Sync`, and dispatched
/// by `match` without virtual calls.
#[derive(Clone, Debug, PartialEq)]
pub enum Bsdf {
    /// Lambertian reflection: f = albedo / π.
    Diffuse {
        /// Directional-hemispherical reflectance, per channel in [0, 1].
        albedo: Vec3,
    },
    /// Perfect specular reflection (delta), weight `reflectance`.
    Mirror {
        /// Reflected fraction per channel.
        reflectance: Vec3,
    },
    /// Smooth dielectric (delta): reflects with the exact Fresnel
    /// probability, refracts otherwise; total internal reflection reflects.
    /// Reflection weight `reflectance`, refraction weight
    /// `transmittance / η²` (radiance transport, see the module docs).
    Glass {
        /// Tint of the reflected light.
        reflectance: Vec3,
        /// Tint of the refracted light.
        transmittance: Vec3,
        /// Index of refraction of the inside (the −Z side) relative to the
        /// outside.
        ior: f32,
    },
    /// Refraction only (delta), no Fresnel reflection: CS184's
    /// `RefractionBSDF`. Under total internal reflection `sample` returns
    /// `None`, ending the path (the light is lost).
    Refraction {
        /// Tint of the refracted light.
        transmittance: Vec3,
        /// Index of refraction of the inside relative to the outside.
        ior: f32,
    },
    /// Smooth glass of zero thickness (a window pane, delta): reflects with
    /// the probability 2F/(1 + F) that sums the bounces inside the slab
    /// (F the Fresnel reflectance of one face), else passes straight
    /// through (`wi = −wo`) with no η² scaling, since it leaves into the
    /// medium it came from. Reflection weight `reflectance`, transmission
    /// weight `transmittance`. Either side.
    ThinGlass {
        /// Tint of the reflected light.
        reflectance: Vec3,
        /// Tint of the transmitted light.
        transmittance: Vec3,
        /// Index of refraction of the pane relative to its surroundings.
        ior: f32,
    },
    /// Rough dielectric (Walter et al. 2007): glossy reflection and
    /// refraction through microfacets with the exact dielectric Fresnel
    /// term, `transmittance / η²`-scaled refraction (radiance transport),
    /// total internal reflection; see `rough_dielectric.rs`.
    RoughGlass {
        /// The distribution of microfacet normals.
        distribution: MicrofacetDistribution,
        /// How its masking combines.
        masking: Masking,
        /// Tint of the reflected light.
        reflectance: Vec3,
        /// Tint of the refracted light.
        transmittance: Vec3,
        /// Index of refraction of the inside (the −Z side) relative to the
        /// outside.
        ior: f32,
    },
    /// Smooth plastic (Mitsuba's `plastic`): a diffuse base under a smooth
    /// dielectric coating, a delta specular lobe plus a diffuse one with
    /// the internal-scattering renormalisation (see `plastic.rs`).
    Plastic(Plastic),
    /// Rough plastic (Mitsuba's `roughplastic`): a diffuse base under a
    /// rough dielectric coating, a glossy microfacet lobe plus a diffuse one
    /// scaled by the coating's transmittance both ways (see
    /// `rough_plastic.rs`).
    RoughPlastic(RoughPlastic),
    /// Smooth conductor (delta): the mirror direction weighted by the exact
    /// conductor Fresnel reflectance, which rises to 1 at grazing angles.
    Conductor {
        /// Real part of the conductor's IOR, per channel.
        eta: Vec3,
        /// Imaginary part (extinction coefficient), per channel.
        k: Vec3,
    },
    /// Rough conductor: Beckmann or GGX microfacets, exact conductor
    /// Fresnel, Smith masking-shadowing (see `microfacet.rs`).
    Microfacet {
        /// The distribution of microfacet normals (CS184's `<microfacet>`:
        /// isotropic Beckmann).
        distribution: MicrofacetDistribution,
        /// How its masking combines.
        masking: Masking,
        /// Real part of the conductor's IOR, per channel.
        eta: Vec3,
        /// Imaginary part (extinction coefficient), per channel.
        k: Vec3,
    },
    /// The glTF 2.0 metallic-roughness model: Lambert base and GGX
    /// specular with Schlick Fresnel, mixed by metalness, with glass-like
    /// transmission (see `metallic_roughness/`).
    MetallicRoughness(MetallicRoughness),
    /// The principled BSDF of Burley 2012/2015 as Mitsuba 3 defines it:
    /// Burley diffuse with retro-reflection, sheen, anisotropic GGX
    /// specular (metallic and tinted), clearcoat and rough specular
    /// transmission (see `principled/mod.rs`).
    Principled(Principled),
    /// A mixture of two BSDFs (Mitsuba's `blendbsdf`), boxed so the enum
    /// stays as small as its largest single model (see `blend.rs`).
    Blend(Box<Blend>),
}

/// A BSDF value is at most 72 bytes, the rough plastic's size: the enum's
/// tag lives in a niche of the plastic's and every other model fits beside
/// it (the glTF model within 60 bytes, `sheen.rs`). The render loop moves
/// and matches these at every vertex, and 8 bytes more cost it 0.15% of
/// its instructions (callgrind, CS184's CBbunny) whatever the scene's
/// BSDFs.
const _: () = assert!(std::mem::size_of::<Bsdf>() <= 72);

impl Bsdf {
    /// The model's name, as the path inspector shows it.
    pub fn name(&self) -> &'static str {
        match self {
            Bsdf::Diffuse { .. } => "diffuse",
            Bsdf::Mirror { .. } => "mirror",
            Bsdf::Glass { .. } => "glass",
            Bsdf::Refraction { .. } => "refraction",
            Bsdf::ThinGlass { .. } => "thin glass",
            Bsdf::RoughGlass { .. } => "rough glass",
            Bsdf::Plastic(_) => "plastic",
            Bsdf::RoughPlastic(_) => "rough plastic",
            Bsdf::Conductor { .. } => "conductor",
            Bsdf::Microfacet { .. } => "rough conductor",
            Bsdf::MetallicRoughness(_) => "glTF metallic-roughness",
            Bsdf::Principled(_) => "principled",
            Bsdf::Blend(_) => "blend",
        }
    }

    /// The union of the flags of its lobes.
    pub fn flags(&self) -> BsdfFlags {
        match self {
            Bsdf::Diffuse { .. } => diffuse::FLAGS,
            Bsdf::Mirror { .. } => specular::MIRROR_FLAGS,
            Bsdf::Glass { .. } => specular::GLASS_FLAGS,
            Bsdf::Refraction { .. } => specular::REFRACTION_FLAGS,
            Bsdf::ThinGlass { .. } => specular::GLASS_FLAGS,
            Bsdf::RoughGlass { .. } => rough_dielectric::FLAGS,
            Bsdf::Plastic(_) => plastic::FLAGS,
            Bsdf::RoughPlastic(_) => rough_plastic::FLAGS,
            Bsdf::Conductor { .. } => specular::MIRROR_FLAGS,
            Bsdf::Microfacet { .. } => microfacet::FLAGS,
            Bsdf::MetallicRoughness(m) => m.flags(),
            Bsdf::Principled(p) => p.flags(),
            Bsdf::Blend(b) => b.flags(),
        }
    }

    /// Whether its microfacet roughness differs along the shading frame's
    /// x and y, so the frame's tangent must follow the surface (dp/du).
    pub fn is_anisotropic(&self) -> bool {
        match self {
            Bsdf::RoughGlass { distribution, .. } | Bsdf::Microfacet { distribution, .. } => {
                let (ax, ay) = distribution.alphas();
                ax != ay
            }
            Bsdf::Principled(p) => p.is_anisotropic(),
            Bsdf::Blend(b) => b.is_anisotropic(),
            _ => false,
        }
    }

    /// Whether every lobe is a delta, so `f` and `pdf` are always zero and
    /// light sampling is useless here.
    pub fn is_specular(&self) -> bool {
        !self.flags().is_non_specular()
    }

    /// The BSDF value for the pair (cosine excluded); zero for delta lobes.
    /// The diffuse case is inlined into the caller (next-event estimation
    /// calls this once per light sample); the others go through
    /// [`Bsdf::f_any`].
    #[inline]
    pub fn f(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        match *self {
            Bsdf::Diffuse { albedo } => diffuse::f(albedo, wo, wi),
            _ => self.f_any(wo, wi),
        }
    }

    /// [`Bsdf::f`] for any model, dispatched out of line.
    #[inline(never)]
    fn f_any(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        match self {
            Bsdf::Diffuse { albedo } => diffuse::f(*albedo, wo, wi),
            Bsdf::Mirror { .. }
            | Bsdf::Glass { .. }
            | Bsdf::Refraction { .. }
            | Bsdf::ThinGlass { .. }
            | Bsdf::Conductor { .. } => Vec3::ZERO,
            Bsdf::RoughGlass { .. } => self.rough_dielectric().map_or(Vec3::ZERO, |b| b.f(wo, wi)),
            Bsdf::Plastic(plastic) => plastic.f(wo, wi),
            Bsdf::RoughPlastic(plastic) => plastic.f(wo, wi),
            Bsdf::Microfacet {
                distribution,
                masking,
                eta,
                k,
            } => microfacet::f(*distribution, *masking, *eta, *k, wo, wi),
            Bsdf::MetallicRoughness(m) => m.f(wo, wi),
            Bsdf::Principled(p) => p.f(wo, wi),
            Bsdf::Blend(b) => b.f_mode(wo, wi, TransportMode::Radiance),
        }
    }

    /// Whether [`Bsdf::sample`] reads its `u1` (chooses between lobes);
    /// when not, a caller may skip drawing it.
    pub fn samples_a_lobe(&self) -> bool {
        match self {
            Bsdf::Diffuse { .. }
            | Bsdf::Mirror { .. }
            | Bsdf::Refraction { .. }
            | Bsdf::Conductor { .. }
            | Bsdf::Microfacet { .. } => false,
            Bsdf::Glass { .. }
            | Bsdf::ThinGlass { .. }
            | Bsdf::RoughGlass { .. }
            | Bsdf::Plastic(_)
            | Bsdf::RoughPlastic(_)
            | Bsdf::MetallicRoughness(_)
            | Bsdf::Principled(_)
            | Bsdf::Blend(_) => true,
        }
    }

    /// Samples `wi` given `wo`: `u1` selects a lobe (where there are
    /// several), `u2` the direction. `None` when the sample carries no
    /// energy (e.g. a direction below the surface), which ends the path.
    /// Inlined for the diffuse case like [`Bsdf::f`].
    #[inline]
    pub fn sample(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        match *self {
            Bsdf::Diffuse { albedo } => diffuse::sample(albedo, wo, u2),
            _ => self.sample_any(wo, u1, u2),
        }
    }

    /// [`Bsdf::sample`] for any model, dispatched out of line.
    #[inline(never)]
    fn sample_any(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        match *self {
            Bsdf::Blend(ref b) => b.sample_mode(wo, u1, u2, TransportMode::Radiance),
            Bsdf::Diffuse { albedo } => diffuse::sample(albedo, wo, u2),
            Bsdf::Mirror { reflectance } => specular::sample_mirror(reflectance, wo),
            Bsdf::Glass {
                reflectance,
                transmittance,
                ior,
            } => specular::sample_glass(reflectance, transmittance, ior, wo, u1),
            Bsdf::Refraction { transmittance, ior } => {
                specular::sample_refraction(transmittance, ior, wo)
            }
            Bsdf::ThinGlass {
                reflectance,
                transmittance,
                ior,
            } => specular::sample_thin_glass(reflectance, transmittance, ior, wo, u1),
            Bsdf::RoughGlass { .. } => self.rough_dielectric()?.sample(wo, u1, u2),
            Bsdf::Plastic(plastic) => plastic.sample(wo, u1, u2),
            Bsdf::RoughPlastic(plastic) => plastic.sample(wo, u1, u2),
            Bsdf::Conductor { eta, k } => specular::sample_conductor(eta, k, wo),
            Bsdf::Microfacet {
                distribution,
                masking,
                eta,
                k,
            } => microfacet::sample(distribution, masking, eta, k, wo, u2),
            Bsdf::MetallicRoughness(m) => m.sample(wo, u1, u2),
            Bsdf::Principled(p) => p.sample(wo, u1, u2),
        }
    }

    /// The density per unit solid angle with which `sample` returns `wi`
    /// (zero for delta lobes), for multiple importance sampling. Inlined for
    /// the diffuse case like [`Bsdf::f`].
    #[inline]
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        match *self {
            Bsdf::Diffuse { .. } => diffuse::pdf(wo, wi),
            _ => self.pdf_any(wo, wi),
        }
    }

    /// [`Bsdf::pdf`] for any model, dispatched out of line.
    #[inline(never)]
    fn pdf_any(&self, wo: Vec3, wi: Vec3) -> f32 {
        match *self {
            Bsdf::Diffuse { .. } => diffuse::pdf(wo, wi),
            Bsdf::Mirror { .. }
            | Bsdf::Glass { .. }
            | Bsdf::Refraction { .. }
            | Bsdf::ThinGlass { .. }
            | Bsdf::Conductor { .. } => 0.0,
            Bsdf::RoughGlass { .. } => self.rough_dielectric().map_or(0.0, |b| b.pdf(wo, wi)),
            Bsdf::Plastic(plastic) => plastic.pdf(wo, wi),
            Bsdf::RoughPlastic(plastic) => plastic.pdf(wo, wi),
            Bsdf::Microfacet { distribution, .. } => microfacet::pdf(distribution, wo, wi),
            Bsdf::MetallicRoughness(m) => m.pdf(wo, wi),
            Bsdf::Principled(p) => p.pdf(wo, wi),
            Bsdf::Blend(ref b) => b.pdf(wo, wi),
        }
    }

    /// A representative colour for albedo AOVs and denoisers: the albedo,
    /// the mirror's reflectance, the glass's transmittance (what one mostly
    /// sees through it), the conductor's reflectance at normal incidence.
    pub fn albedo(&self) -> Vec3 {
        match *self {
            Bsdf::Diffuse { albedo } => albedo,
            Bsdf::Mirror { reflectance } => reflectance,
            Bsdf::Glass { transmittance, .. }
            | Bsdf::Refraction { transmittance, .. }
            | Bsdf::ThinGlass { transmittance, .. }
            | Bsdf::RoughGlass { transmittance, .. } => transmittance,
            Bsdf::Plastic(plastic) => plastic.diffuse(),
            Bsdf::RoughPlastic(plastic) => plastic.diffuse(),
            Bsdf::Microfacet { eta, k, .. } | Bsdf::Conductor { eta, k } => {
                fresnel::fresnel_conductor(1.0, eta, k)
            }
            Bsdf::MetallicRoughness(m) => m.albedo(),
            Bsdf::Principled(p) => p.albedo(),
            Bsdf::Blend(ref b) => b.albedo(),
        }
    }
}

impl Bsdf {
    /// The rough dielectric's parameters, if this is one.
    fn rough_dielectric(&self) -> Option<RoughDielectric> {
        match *self {
            Bsdf::RoughGlass {
                distribution,
                masking,
                reflectance,
                transmittance,
                ior,
            } => Some(RoughDielectric {
                dist: distribution,
                reflectance,
                transmittance,
                ior,
                masking,
            }),
            _ => None,
        }
    }
}

/// Whether two directions lie on the same side of the surface.
fn same_hemisphere(a: Vec3, b: Vec3) -> bool {
    a.z * b.z > 0.0
}
