//! MTL material libraries, read by our own pass (each statement is one
//! key and its values, and errors need their places), then mapped to
//! Candela materials as the table in the README's "Scene formats" section
//! says:
//!
//! - `illum` 3 or 5 (ray-traced reflection): a mirror of reflectance `Ks`.
//! - `illum` 4, 6, 7 or 9 (refraction): glass of index `Ni` (1.5 when `Ni`
//!   is missing or at most 1) and transmittance `Tf`.
//! - otherwise, `Ks` > 0 with `Kd` = 0: a rough conductor; Beckmann
//!   `alpha = sqrt(2 / (Ns + 2))` (the Phong-exponent equivalence of Walter
//!   et al. 2007, "Microfacet Models for Refraction", eq. 25 inverted) and a
//!   complex index `eta = 1, k = 2 sqrt(F0 / (1 - F0))` whose normal-incidence
//!   Fresnel reflectance is `F0 = Ks`.
//! - otherwise: Lambertian with albedo `Kd` (0.5 grey if absent); a `Ks`
//!   lobe beside a diffuse one is reported and dropped.
//! - `Ke` > 0 makes the material emissive (an area light, like COLLADA's
//!   CGL emission); `map_Kd` and `map_Ke` fill the colour and emission
//!   slots, `map_Bump`/`bump` the bump (height) slot, `norm` the
//!   normal-map slot and `map_d` the
//!   opacity slot. `Ka` is meaningless for a path tracer and skipped.
//! - every material shades both sides of its faces (`Sides::Both`), as
//!   path tracers reading OBJ do.

use super::statements::{error, number, statements, Statement};
use crate::desc::{BsdfDesc, ColorSpace, MaterialDesc, SourceLoc, TextureRef, TextureSlot};
use crate::error::{ErrorKind, LoadError};
use crate::report::Collector;
use glam::Vec3;
use std::path::{Path, PathBuf};

/// One `newmtl` block as written.
#[derive(Default)]
struct Raw {
    name: String,
    loc: SourceLoc,
    kd: Option<Vec3>,
    ks: Option<Vec3>,
    ke: Option<Vec3>,
    tf: Option<Vec3>,
    ns: Option<f32>,
    ni: Option<f32>,
    opacity: Option<(f32, SourceLoc)>,
    illum: Option<u32>,
    /// (slot, path as written, place)
    maps: Vec<(TextureSlot, String, SourceLoc)>,
}

/// Statements read but unsupported, with why.
const IGNORED: &[(&str, &str)] = &[
    ("map_Ka", "ambient maps have no meaning in a path tracer"),
    ("map_Ks", "specular colour maps are not supported"),
    ("map_Ns", "shininess maps are not supported"),
    ("map_ns", "shininess maps are not supported"),
    ("disp", "displacement maps are not supported"),
    ("decal", "decal maps are not supported"),
    ("refl", "reflection maps are not supported"),
    ("sharpness", "reflection sharpness is not supported"),
    ("Pr", "PBR roughness is not supported"),
    ("Pm", "PBR metallic is not supported"),
    ("map_Pr", "PBR roughness maps are not supported"),
    ("map_Pm", "PBR metallic maps are not supported"),
];

/// Reads the MTL text `text` of file `file` into Candela materials.
pub(crate) fn read_mtl(
    text: &str,
    file: &Path,
    strict: bool,
    warnings: &mut Collector,
) -> Result<Vec<MaterialDesc>, LoadError> {
    let mut raws: Vec<Raw> = Vec::new();
    for st in statements(text) {
        if st.keyword == "newmtl" {
            if st.rest.is_empty() {
                return Err(error(
                    file,
                    st.loc(),
                    "newmtl",
                    ErrorKind::MissingElement,
                    "expected a material name".into(),
                ));
            }
            raws.push(Raw {
                name: st.rest.to_string(),
                loc: st.loc(),
                ..Raw::default()
            });
            continue;
        }
        let Some(raw) = raws.last_mut() else {
            return Err(error(
                file,
                st.loc(),
                st.keyword,
                ErrorKind::MissingElement,
                "statement before any newmtl".into(),
            ));
        };
        statement(file, &st, raw, warnings)?;
    }
    let base = file.parent().unwrap_or(Path::new(""));
    raws.into_iter()
        .map(|raw| to_material(raw, file, base, strict, warnings))
        .collect()
}

fn statement(
    file: &Path,
    st: &Statement,
    raw: &mut Raw,
    warnings: &mut Collector,
) -> Result<(), LoadError> {
    match st.keyword {
        "Kd" => raw.kd = colour(file, st, warnings)?,
        "Ks" => raw.ks = colour(file, st, warnings)?,
        "Ke" => raw.ke = colour(file, st, warnings)?,
        "Tf" => raw.tf = colour(file, st, warnings)?,
        "Ka" => {}
        "Ns" => raw.ns = Some(non_negative(file, st)?),
        "Ni" => raw.ni = Some(non_negative(file, st)?),
        "d" => raw.opacity = Some((fraction(file, st)?, st.loc())),
        "Tr" => raw.opacity = Some((1.0 - fraction(file, st)?, st.loc())),
        "illum" => {
            let Some(&(token, col)) = st.args.first() else {
                return Err(error(
                    file,
                    st.loc(),
                    "illum",
                    ErrorKind::MissingElement,
                    "expected an illumination model 0 to 10".into(),
                ));
            };
            let model: u32 = token.parse().map_err(|_| {
                error(
                    file,
                    st.at(col),
                    "illum",
                    ErrorKind::BadNumber,
                    format!("\"{token}\" is not an illumination model"),
                )
            })?;
            raw.illum = Some(model);
        }
        "map_Kd" => map(file, st, raw, TextureSlot::Color, warnings)?,
        "map_Ke" => map(file, st, raw, TextureSlot::Emission, warnings)?,
        // The MTL specification's bump maps are heights; `norm` is a
        // tangent-space normal map.
        "map_Bump" | "map_bump" | "bump" => map(file, st, raw, TextureSlot::Bump, warnings)?,
        "norm" => map(file, st, raw, TextureSlot::Normal, warnings)?,
        "map_d" => map(file, st, raw, TextureSlot::Opacity, warnings)?,
        other => {
            let message = IGNORED
                .iter()
                .find(|(k, _)| *k == other)
                .map_or("unknown statement ignored", |(_, m)| m);
            warnings.warn(other.into(), message.into(), || st.loc())?;
        }
    }
    Ok(())
}

/// `r [g b]` (one value means grey); `spectral` and `xyz` forms are reported.
fn colour(
    file: &Path,
    st: &Statement,
    warnings: &mut Collector,
) -> Result<Option<Vec3>, LoadError> {
    if matches!(st.args.first(), Some(("spectral" | "xyz", _))) {
        warnings.warn(
            st.keyword.into(),
            "spectral and CIE XYZ colours are not supported; ignored".into(),
            || st.loc(),
        )?;
        return Ok(None);
    }
    let r = number(file, st, 0)?;
    let c = match st.args.len() {
        1 => Vec3::splat(r),
        _ => Vec3::new(r, number(file, st, 1)?, number(file, st, 2)?),
    };
    if c.min_element() < 0.0 {
        return Err(error(
            file,
            st.loc(),
            st.keyword,
            ErrorKind::BadValue,
            format!("negative colour {c}"),
        ));
    }
    Ok(Some(c))
}

fn non_negative(file: &Path, st: &Statement) -> Result<f32, LoadError> {
    let v = number(file, st, 0)?;
    if v < 0.0 {
        return Err(error(
            file,
            st.arg_loc(0),
            st.keyword,
            ErrorKind::BadValue,
            format!("{v} is negative"),
        ));
    }
    Ok(v)
}

fn fraction(file: &Path, st: &Statement) -> Result<f32, LoadError> {
    let v = number(file, st, 0)?;
    if !(0.0..=1.0).contains(&v) {
        return Err(error(
            file,
            st.arg_loc(0),
            st.keyword,
            ErrorKind::BadValue,
            format!("{v} is outside [0, 1]"),
        ));
    }
    Ok(v)
}

/// A texture statement: options (`-bm 1`, `-o u v w`, ...) are skipped and
/// reported; the rest of the line is the file name.
fn map(
    file: &Path,
    st: &Statement,
    raw: &mut Raw,
    slot: TextureSlot,
    warnings: &mut Collector,
) -> Result<(), LoadError> {
    let mut first = 0;
    while let Some((token, _)) = st.args.get(first) {
        if !token.starts_with('-') || token.parse::<f32>().is_ok() {
            break;
        }
        warnings.warn(
            st.keyword.into(),
            format!("texture option {token} ignored"),
            || st.arg_loc(first),
        )?;
        first += 1;
        // The option's values: numbers and on/off.
        while let Some((value, _)) = st.args.get(first) {
            if value.parse::<f32>().is_err() && !matches!(*value, "on" | "off") {
                break;
            }
            first += 1;
        }
    }
    let Some(&(_, col)) = st.args.get(first) else {
        return Err(error(
            file,
            st.loc(),
            st.keyword,
            ErrorKind::MissingElement,
            "expected a texture file name".into(),
        ));
    };
    let name = st.rest[st.rest.len() - rest_len(st, first)..].to_string();
    raw.maps.push((slot, name, st.at(col)));
    Ok(())
}

/// Length of the text from argument `first` to the end of the statement.
fn rest_len(st: &Statement, first: usize) -> usize {
    let start = st.args[first].0.as_ptr() as usize;
    let end = st.rest.as_ptr() as usize + st.rest.len();
    end.saturating_sub(start).min(st.rest.len())
}

fn to_material(
    raw: Raw,
    file: &Path,
    base: &Path,
    strict: bool,
    warnings: &mut Collector,
) -> Result<MaterialDesc, LoadError> {
    let kd = raw.kd.unwrap_or(Vec3::splat(0.5));
    let ks = raw.ks.unwrap_or(Vec3::ZERO);
    let element = format!("newmtl {}", raw.name);
    let bsdf = match raw.illum.unwrap_or(2) {
        3 | 5 => BsdfDesc::Mirror {
            reflectance: raw.ks.unwrap_or(Vec3::ONE),
        },
        4 | 6 | 7 | 9 => BsdfDesc::Glass {
            reflectance: Vec3::ONE,
            transmittance: raw.tf.unwrap_or(Vec3::ONE),
            roughness: 0.0,
            ior: raw.ni.filter(|&n| n > 1.0).unwrap_or(1.5),
        },
        illum if illum >= 2 && ks.max_element() > 0.0 && kd.max_element() == 0.0 => {
            let f0 = ks.clamp(Vec3::ZERO, Vec3::splat(0.999));
            BsdfDesc::Microfacet {
                alpha: (2.0 / (raw.ns.unwrap_or(0.0) + 2.0)).sqrt(),
                eta: Vec3::ONE,
                k: 2.0 * (f0 / (Vec3::ONE - f0)).powf(0.5),
            }
        }
        illum => {
            if illum >= 2 && ks.max_element() > 0.0 {
                warnings.warn(
                    element.clone(),
                    "specular lobe (Ks) beside a diffuse one (Kd) dropped".into(),
                    || raw.loc,
                )?;
            }
            BsdfDesc::Diffuse { albedo: kd }
        }
    };
    let mut desc = MaterialDesc {
        name: raw.name.clone(),
        bsdf,
        emission: raw.ke.filter(|e| e.max_element() > 0.0),
        loc: raw.loc,
        ..MaterialDesc::default_grey()
    };
    if let Some((d, loc)) = raw.opacity.filter(|(d, _)| *d < 1.0) {
        warnings.warn(
            element.clone(),
            format!("constant opacity {d} not supported (only map_d); opaque"),
            || loc,
        )?;
    }
    for (slot, name, loc) in raw.maps {
        let path: PathBuf = base.join(name.replace('\\', "/"));
        if !path.is_file() {
            let message = format!("texture file {} not found", path.display());
            if strict {
                return Err(error(
                    file,
                    loc,
                    &element,
                    ErrorKind::MissingReference,
                    message,
                ));
            }
            warnings.warn(element.clone(), format!("{message}; ignored"), || loc)?;
            continue;
        }
        let space = match slot {
            TextureSlot::Color | TextureSlot::Emission => ColorSpace::of_image_file(&path),
            _ => ColorSpace::Linear,
        };
        desc.textures.set(slot, TextureRef::new(path, space));
    }
    Ok(desc)
}
