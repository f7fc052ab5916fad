//! BSDFs and textures.
//!
//! | Mitsuba | Candela description |
//! |---|---|
//! | `diffuse` | `Diffuse` (a `reflectance` texture fills the colour slot) |
//! | `twosided` | its BSDF with [`Sides::Both`]; with two BSDFs, the first with [`Sides::Back`] of the second |
//! | `dielectric` | `Glass`, ior = int_ior / ext_ior (numbers or names) |
//! | `thindielectric` | `ThinDielectric` |
//! | `roughdielectric` | `RoughDielectric` (alpha, or alpha_u/alpha_v; beckmann or ggx) |
//! | `conductor`, `roughconductor` | `Conductor` (alpha 0 when smooth, alpha_u/alpha_v anisotropic), `material` presets (the measured metals of [`crate::metals`]) or eta/k; a smooth `none` with `specular_reflectance` is a `Mirror` of that reflectance |
//! | `plastic`, `roughplastic` | `Plastic` (alpha 0 when smooth), with `nonlinear`; masking separable and F_int the mean of 64 even samples, as Mitsuba computes them |
//! | `bumpmap`, `normalmap` | the inner BSDF, its texture in the bump (height, times `scale`) or normal-map slot, with Mitsuba's [`PerturbationRules`] (`use_shadowing_function`; `flip_invalid_normals` false is reported) |
//! | `mask` | the inner BSDF, its opacity texture in the opacity slot, or a constant opacity (a colour's luminance) |
//! | `principled` | `Principled` (`principled.rs`: every parameter; textures on base_color, roughness, metallic) |
//! | `blendbsdf` | `Blend` of its two BSDFs (`blend.rs`), a weight texture in the blend weight slot |
//!
//! `null` is [`BsdfDesc::Null`]: rays pass through; an emitter on the shape
//! is still seen on its front side, as Mitsuba's `volpath` and `direct`
//! show it.
//!
//! Mitsuba BSDFs Candela lacks (`principledthin`, ...) are
//! replaced by the closest one and reported once.
//!
//! Sides: Mitsuba 3 evaluates every BSDF but the ones that transmit as
//! one-sided, black when `wo` or `wi` is behind the shading normal
//! (`flip_normals` turns that normal over); such BSDFs get
//! [`Sides::Front`] (and so does the diffuse 0.5 a shape gets when it
//! names no BSDF). `twosided` turns the frame over behind the surface and
//! evaluates its first BSDF there, or its second when it has two.

use super::blend::{blend_parts_two_sided, transmits};
use super::doc::{elements, Doc, XNode};
use super::textures::{for_slot, Texture};
use super::values::{boolean, constant_color, float, float_of, string};
use super::{tables, Builder};
use crate::desc::{
    Alpha, AwayFromViewer, BsdfDesc, InternalReflectance, Masking, MaterialDesc, MicrofacetModel,
    PerturbationRules, Sides, TextureRef, TextureSlot, TextureSlots,
};
use crate::error::{ErrorKind, LoadError};
use glam::Vec3;

/// A parameter that is a constant, maybe replaced by a texture.
type Param = (Vec3, Option<TextureRef>);

impl Builder {
    /// A `<bsdf>` element as a material without emission.
    pub(super) fn bsdf(&mut self, doc: &Doc, node: XNode) -> Result<MaterialDesc, LoadError> {
        let kind = doc.plugin_type(node)?;
        let name = doc.attr(node, "id")?.unwrap_or_else(|| kind.clone());
        let mut textures = TextureSlots::default();
        let bsdf = match kind.as_str() {
            "diffuse" => {
                let (albedo, tex) = self.color(doc, node, "reflectance", Vec3::splat(0.5))?;
                set(&mut textures, TextureSlot::Color, tex);
                BsdfDesc::Diffuse { albedo }
            }
            "twosided" | "bumpmap" | "normalmap" | "mask" => {
                return self.wrapper(doc, node, &kind, name)
            }
            "blendbsdf" => return self.blend(doc, node, name),
            "dielectric" => BsdfDesc::Glass {
                reflectance: self.constant(doc, node, "specular_reflectance", Vec3::ONE)?,
                transmittance: self.constant(doc, node, "specular_transmittance", Vec3::ONE)?,
                roughness: 0.0,
                ior: relative_ior(doc, node, tables::named_ior("bk7").unwrap_or(1.5))?,
            },
            "thindielectric" => BsdfDesc::ThinDielectric {
                reflectance: self.constant(doc, node, "specular_reflectance", Vec3::ONE)?,
                transmittance: self.constant(doc, node, "specular_transmittance", Vec3::ONE)?,
                ior: relative_ior(doc, node, tables::named_ior("bk7").unwrap_or(1.5))?,
            },
            "roughdielectric" => BsdfDesc::RoughDielectric {
                distribution: distribution(doc, node)?,
                masking: Masking::Separable,
                alpha: self.alpha(doc, node, &mut textures)?,
                reflectance: self.constant(doc, node, "specular_reflectance", Vec3::ONE)?,
                transmittance: self.constant(doc, node, "specular_transmittance", Vec3::ONE)?,
                ior: relative_ior(doc, node, tables::named_ior("bk7").unwrap_or(1.5))?,
            },
            "conductor" | "roughconductor" => {
                let (eta, k) = conductor_ior(self, doc, node)?;
                let rough = kind == "roughconductor";
                let scale = self.constant(doc, node, "specular_reflectance", Vec3::ONE)?;
                // Fresnel is 1 at every angle for "none", so the BSDF is
                // exactly a mirror of reflectance `scale`; Candela's
                // conductor has no such factor otherwise.
                let smooth_none = !rough && (eta, k) == (Vec3::ZERO, Vec3::ONE);
                if scale != Vec3::ONE && smooth_none {
                    return Ok(MaterialDesc {
                        name,
                        bsdf: BsdfDesc::Mirror { reflectance: scale },
                        emission: None,
                        textures,
                        sides: Sides::Front,
                        loc: doc.loc(node),
                    });
                }
                if scale != Vec3::ONE {
                    let p = doc.prop(node, "specular_reflectance")?.unwrap_or(node);
                    self.warn(
                        doc,
                        p,
                        "specular_reflectance is applied only to a smooth conductor of material \"none\" (ignored)",
                    )?;
                }
                BsdfDesc::Conductor {
                    distribution: if rough {
                        distribution(doc, node)?
                    } else {
                        MicrofacetModel::Beckmann
                    },
                    masking: Masking::Separable,
                    alpha: if rough {
                        self.alpha(doc, node, &mut textures)?
                    } else {
                        Alpha::isotropic(0.0)
                    },
                    eta,
                    k,
                }
            }
            "plastic" | "roughplastic" | "pplastic" => {
                if kind == "pplastic" {
                    self.warn(doc, node, "polarized plastic rendered as roughplastic")?;
                }
                let (diffuse, tex) =
                    self.color(doc, node, "diffuse_reflectance", Vec3::splat(0.5))?;
                set(&mut textures, TextureSlot::Color, tex);
                let rough = kind != "plastic";
                let int = ior(
                    doc,
                    node,
                    "int_ior",
                    tables::named_ior("polypropylene").unwrap_or(1.49),
                )?;
                let ext = ior(
                    doc,
                    node,
                    "ext_ior",
                    tables::named_ior("air").unwrap_or(1.0),
                )?;
                BsdfDesc::Plastic {
                    diffuse,
                    masking: Masking::Separable,
                    internal_reflectance: InternalReflectance::EvenSampleMean,
                    specular: self.constant(doc, node, "specular_reflectance", Vec3::ONE)?,
                    ior: int / ext,
                    alpha: if rough {
                        self.isotropic_alpha(doc, node, &mut textures)?
                    } else {
                        0.0
                    },
                    distribution: if rough {
                        distribution(doc, node)?
                    } else {
                        MicrofacetModel::Beckmann
                    },
                    nonlinear: boolean(doc, node, "nonlinear", false)?,
                }
            }
            "principled" => self.principled(doc, node, &mut textures)?,
            "principledthin" => {
                self.warn(
                    doc,
                    node,
                    format!("BSDF \"{kind}\" rendered as diffuse (its base_color)"),
                )?;
                let (albedo, tex) = self.color(doc, node, "base_color", Vec3::splat(0.5))?;
                set(&mut textures, TextureSlot::Color, tex);
                BsdfDesc::Diffuse { albedo }
            }
            "null" => BsdfDesc::Null,
            "measured" | "hair" | "polarizer" | "retarder" | "circular" => {
                self.warn(
                    doc,
                    node,
                    format!("BSDF \"{kind}\" rendered as grey diffuse"),
                )?;
                BsdfDesc::Diffuse {
                    albedo: Vec3::splat(0.5),
                }
            }
            other => {
                return Err(doc.err(
                    node,
                    ErrorKind::BadValue,
                    format!("unknown BSDF type \"{other}\""),
                ))
            }
        };
        Ok(MaterialDesc {
            name,
            bsdf,
            emission: None,
            textures,
            sides: sides_of(doc, node, &kind)?,
            loc: doc.loc(node),
        })
    }

    /// BSDFs that wrap another one (`twosided`, `bumpmap`, ...).
    fn wrapper(
        &mut self,
        doc: &Doc,
        node: XNode,
        kind: &str,
        name: String,
    ) -> Result<MaterialDesc, LoadError> {
        let mut inner: Option<MaterialDesc> = None;
        let mut back: Option<MaterialDesc> = None;
        let mut extra = 0;
        for c in elements(node) {
            let m = match c.tag_name().name() {
                "bsdf" => self.bsdf(doc, c)?,
                "ref" => {
                    let id = doc.required(c, "id")?;
                    if self.textures.contains_key(&id) {
                        continue; // a bump or normal map given by reference
                    }
                    self.named_bsdf(doc, c, &id)?
                }
                _ => continue,
            };
            if inner.is_none() {
                inner = Some(m);
            } else if back.is_none() {
                back = Some(m);
            } else {
                extra += 1;
            }
        }
        let Some(mut m) = inner else {
            return Err(doc.err(
                node,
                ErrorKind::MissingElement,
                format!("\"{kind}\" has no inner <bsdf>"),
            ));
        };
        if kind == "twosided" {
            if extra > 0 {
                self.warn(doc, node, "twosided: BSDFs after the second are ignored")?;
            }
            self.two_sides(doc, node, &mut m, back)?;
        } else if back.is_some() {
            self.warn(
                doc,
                node,
                format!("\"{kind}\": only the first inner BSDF is used"),
            )?;
        }
        match kind {
            "bumpmap" | "normalmap" => {
                if let Some(mut tex) = self.map_texture(doc, node)? {
                    let slot = if kind == "bumpmap" {
                        // The height gradient's factor.
                        tex.scale = float(doc, node, "scale", 1.0)?;
                        TextureSlot::Bump
                    } else {
                        TextureSlot::Normal
                    };
                    set(&mut m.textures, slot, Some(tex));
                }
                m.textures.perturbation = self.perturbation_rules(doc, node)?;
            }
            "mask" => {
                let (opacity, tex) = self.color(doc, node, "opacity", Vec3::ONE)?;
                if tex.is_none() && opacity.min_element() < 1.0 {
                    // Mitsuba reads a colour as one value by its luminance.
                    m.textures.opacity_constant = Some(luminance(opacity).clamp(0.0, 1.0));
                }
                set(&mut m.textures, TextureSlot::Opacity, tex);
            }
            _ => {}
        }
        m.name = name;
        m.loc = doc.loc(node);
        Ok(m)
    }

    /// Makes `front` (a `twosided`'s first BSDF) scatter on both sides:
    /// with itself turned over on the back, or with `back`. Mitsuba
    /// refuses to nest a BSDF that transmits; such a one is kept as it is
    /// (a dielectric is two-sided already) and reported.
    fn two_sides(
        &mut self,
        doc: &Doc,
        node: XNode,
        front: &mut MaterialDesc,
        back: Option<MaterialDesc>,
    ) -> Result<(), LoadError> {
        if transmits(front) || back.as_ref().is_some_and(transmits) {
            return self.warn(
                doc,
                node,
                "twosided around a BSDF that transmits (Mitsuba refuses it): the inner BSDF is used as it is",
            );
        }
        blend_parts_two_sided(front);
        front.sides = match back {
            Some(mut b) => {
                b.sides = Sides::Both;
                blend_parts_two_sided(&mut b);
                Sides::Back(Box::new(b))
            }
            None => Sides::Both,
        };
        Ok(())
    }

    /// Mitsuba's rules for the shading frame of a `normalmap` or
    /// `bumpmap` (its `flip_invalid_normals` and `use_shadowing_function`).
    fn perturbation_rules(
        &mut self,
        doc: &Doc,
        node: XNode,
    ) -> Result<PerturbationRules, LoadError> {
        let mut rules = PerturbationRules::MITSUBA;
        rules.shadow_terminator = boolean(doc, node, "use_shadowing_function", true)?;
        if !boolean(doc, node, "flip_invalid_normals", true)? {
            let p = doc.prop(node, "flip_invalid_normals")?.unwrap_or(node);
            self.warn(
                doc,
                p,
                "flip_invalid_normals false is not supported (a normal facing away from the viewer is bent toward it)",
            )?;
            rules.away_from_viewer = AwayFromViewer::BendTowardViewer;
        }
        Ok(rules)
    }

    /// The texture of a bump or normal map (a `<texture>` or `<ref>` child).
    fn map_texture(&mut self, doc: &Doc, node: XNode) -> Result<Option<TextureRef>, LoadError> {
        for c in elements(node) {
            let t = match c.tag_name().name() {
                "texture" => self.texture(doc, c)?,
                "ref" => match self.textures.get(&doc.required(c, "id")?) {
                    Some(t) => t.clone(),
                    None => continue,
                },
                _ => continue,
            };
            // Read as the texture says, as Mitsuba does: a map wants
            // `raw` (else its PNG is decoded from sRGB first).
            if let Texture::Varying(t) = t {
                return Ok(Some(t));
            }
        }
        Ok(None)
    }

    /// Mitsuba's BSDF of a shape that names none: diffuse 0.5, one-sided.
    pub(super) fn default_diffuse() -> MaterialDesc {
        MaterialDesc {
            sides: Sides::Front,
            ..MaterialDesc::default_grey()
        }
    }

    /// The material of the BSDF named `id`.
    pub(super) fn named_bsdf(
        &self,
        doc: &Doc,
        node: XNode,
        id: &str,
    ) -> Result<MaterialDesc, LoadError> {
        self.bsdfs.get(id).cloned().ok_or_else(|| {
            doc.err(
                node,
                ErrorKind::MissingReference,
                format!("no <bsdf> with id \"{id}\""),
            )
        })
    }

    /// Colour property `name`: a constant, or a texture (its constant
    /// `default`).
    pub(super) fn color(
        &mut self,
        doc: &Doc,
        node: XNode,
        name: &str,
        default: Vec3,
    ) -> Result<Param, LoadError> {
        let Some(p) = doc.prop(node, name)? else {
            return Ok((default, None));
        };
        let texture = match p.tag_name().name() {
            "texture" => self.texture(doc, p)?,
            "ref" => {
                let id = doc.required(p, "id")?;
                self.textures.get(&id).cloned().ok_or_else(|| {
                    doc.err(
                        p,
                        ErrorKind::MissingReference,
                        format!("no <texture> with id \"{id}\""),
                    )
                })?
            }
            _ => {
                return match constant_color(doc, p)? {
                    Some(c) => Ok((c, None)),
                    None => Err(doc.err(
                        p,
                        ErrorKind::BadValue,
                        "expected a colour (<rgb>, <spectrum>, <float>) or a texture",
                    )),
                }
            }
        };
        Ok(match texture {
            Texture::Varying(t) => (default, Some(t)),
            Texture::Constant(c) => (c, None),
        })
    }

    /// A colour property that Candela cannot texture: a texture is
    /// reported and replaced by `default`.
    pub(super) fn constant(
        &mut self,
        doc: &Doc,
        node: XNode,
        name: &str,
        default: Vec3,
    ) -> Result<Vec3, LoadError> {
        let (c, tex) = self.color(doc, node, name, default)?;
        if tex.is_some() {
            let p = doc.prop(node, name)?.unwrap_or(node);
            self.warn(
                doc,
                p,
                format!("a texture for \"{name}\" is not supported (constant used)"),
            )?;
        }
        Ok(c)
    }

    /// Roughness `alpha` (default 0.1), or `alpha_u` and `alpha_v` (along
    /// the shading frame's dp/du and across it); a texture for `alpha` goes
    /// to the roughness slot, textures for `alpha_u`/`alpha_v` are reported
    /// (their constants used).
    fn alpha(
        &mut self,
        doc: &Doc,
        node: XNode,
        textures: &mut TextureSlots,
    ) -> Result<Alpha, LoadError> {
        if doc.prop(node, "alpha_u")?.is_some() || doc.prop(node, "alpha_v")?.is_some() {
            let u = self.constant(doc, node, "alpha_u", Vec3::splat(0.1))?.x;
            let v = self.constant(doc, node, "alpha_v", Vec3::splat(0.1))?.x;
            return Ok(Alpha {
                u: check_alpha(doc, node, u)?,
                v: check_alpha(doc, node, v)?,
            });
        }
        let (a, tex) = self.color(doc, node, "alpha", Vec3::splat(0.1))?;
        set(textures, TextureSlot::Roughness, tex);
        check_alpha(doc, node, a.x).map(Alpha::isotropic)
    }

    /// [`Self::alpha`] for a model with one roughness (`roughplastic`):
    /// anisotropic values are averaged and reported.
    fn isotropic_alpha(
        &mut self,
        doc: &Doc,
        node: XNode,
        textures: &mut TextureSlots,
    ) -> Result<f32, LoadError> {
        let alpha = self.alpha(doc, node, textures)?;
        if alpha.is_anisotropic() {
            self.warn(
                doc,
                node,
                "anisotropic roughness on a plastic rendered isotropic (the mean alpha)",
            )?;
        }
        Ok(0.5 * (alpha.u + alpha.v))
    }
}

/// The sides a Mitsuba BSDF of type `kind` scatters on: both for those
/// that transmit (the dielectrics, hair, `principledthin`, a `principled`
/// with `spec_trans` > 0), the front only for every other one (black from
/// behind, as Mitsuba 3 evaluates them).
fn sides_of(doc: &Doc, node: XNode, kind: &str) -> Result<Sides, LoadError> {
    let transmits = match kind {
        "dielectric" | "thindielectric" | "roughdielectric" | "hair" | "null" => true,
        // principledthin is two-sided whatever its parameters.
        "principledthin" => true,
        "principled" => match doc.prop(node, "spec_trans")? {
            None => false,
            Some(p) if p.tag_name().name() == "float" => float_of(doc, p)? > 0.0,
            Some(_) => true, // a texture: transmits somewhere
        },
        _ => false,
    };
    Ok(if transmits { Sides::Both } else { Sides::Front })
}

/// Rec. 709 luminance, as Mitsuba reads a colour where it needs one value.
fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

fn check_alpha(doc: &Doc, node: XNode, alpha: f32) -> Result<f32, LoadError> {
    if alpha > 0.0 {
        Ok(alpha)
    } else {
        Err(doc.err(
            node,
            ErrorKind::BadValue,
            format!("roughness alpha {alpha} is not positive"),
        ))
    }
}

/// Puts `texture` (if any) into `slot`, read as Mitsuba reads a texture
/// there ([`for_slot`]).
pub(super) fn set(textures: &mut TextureSlots, slot: TextureSlot, texture: Option<TextureRef>) {
    if let Some(t) = texture {
        textures.set(slot, for_slot(slot, t));
    }
}

/// `distribution`: beckmann (the default) or ggx.
fn distribution(doc: &Doc, node: XNode) -> Result<MicrofacetModel, LoadError> {
    match string(doc, node, "distribution")?.as_deref() {
        None | Some("beckmann") => Ok(MicrofacetModel::Beckmann),
        Some("ggx") => Ok(MicrofacetModel::Ggx),
        Some(other) => Err(doc.err(
            node,
            ErrorKind::BadValue,
            format!("unknown microfacet distribution \"{other}\" (expected beckmann or ggx)"),
        )),
    }
}

/// int_ior / ext_ior, with `int_default` inside and air outside.
fn relative_ior(doc: &Doc, node: XNode, int_default: f32) -> Result<f32, LoadError> {
    let int = ior(doc, node, "int_ior", int_default)?;
    let ext = ior(
        doc,
        node,
        "ext_ior",
        tables::named_ior("air").unwrap_or(1.0),
    )?;
    Ok(int / ext)
}

/// An IOR property: a number or a name from Mitsuba's table.
fn ior(doc: &Doc, node: XNode, name: &str, default: f32) -> Result<f32, LoadError> {
    let Some(p) = doc.prop(node, name)? else {
        return Ok(default);
    };
    let v = if p.tag_name().name() == "string" {
        let n = doc.required(p, "value")?;
        tables::named_ior(&n).ok_or_else(|| {
            doc.err(
                p,
                ErrorKind::BadValue,
                format!("unknown IOR name \"{n}\" (known: {})", tables::ior_names()),
            )
        })?
    } else {
        float_of(doc, p)?
    };
    if v > 0.0 {
        Ok(v)
    } else {
        Err(doc.err(p, ErrorKind::BadValue, format!("IOR {v} is not positive")))
    }
}

/// A conductor's (eta, k): explicit `eta`/`k`, or the `material` preset
/// (default "none", a perfect mirror, as in Mitsuba 3).
fn conductor_ior(b: &mut Builder, doc: &Doc, node: XNode) -> Result<(Vec3, Vec3), LoadError> {
    if doc.prop(node, "eta")?.is_some() || doc.prop(node, "k")?.is_some() {
        let eta = b.constant(doc, node, "eta", Vec3::ZERO)?;
        let k = b.constant(doc, node, "k", Vec3::ONE)?;
        return Ok((eta, k));
    }
    let name = string(doc, node, "material")?.unwrap_or_else(|| "none".into());
    tables::conductor(&name).ok_or_else(|| {
        let p = doc.prop(node, "material").ok().flatten().unwrap_or(node);
        doc.err(
            p,
            ErrorKind::BadValue,
            format!(
                "unknown conductor \"{name}\" (known: {})",
                tables::conductor_names()
            ),
        )
    })
}
