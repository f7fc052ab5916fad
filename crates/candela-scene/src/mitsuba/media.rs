//! Participating media: Mitsuba's `homogeneous` medium with an `isotropic`
//! or `hg` phase function, read into [`MediumDesc`]s, the media on either
//! side of a shape ([`MediumInterface`], per material: a shape with media
//! gets a material of its own, see `shapes.rs`) and the sensor's medium.
//!
//! As Mitsuba 3.9 reads them (measured with its XML parser):
//! - `sigma_t` (default 1) and `albedo` (default 0.75) are a `<float>`,
//!   `<rgb>` or `<spectrum>`, or a `<volume type="constvolume">` (inline or
//!   a `<ref>` to a top-level one) whose `value` (default 1) is one of
//!   those; `scale` (default 1) multiplies `sigma_t`. Mitsuba refuses an
//!   `<rgb>` outside [0, 1] that is not inside a `<volume>`; Candela takes
//!   an `<rgb>` `sigma_t` above 1 as written. A `<spectrum>` `sigma_t`
//!   with wavelengths is clamped to [0, 1] as a reflectance, as Mitsuba
//!   clamps it (a note says so), unless it stands in a `<volume>`.
//! - Candela requires `sigma_t · scale ≥ 0` and `albedo` in [0, 1] (Mitsuba
//!   accepts a float albedo of 1.5; it is not an albedo).
//! - One phase function (`<phase>` or a `<ref>` to a top-level one):
//!   `isotropic` (the default) or `hg`, whose `g` defaults to 0.8 and must
//!   lie in (−1, 1).
//! - A shape's medium is a `<medium>` or `<ref>` child named `interior` or
//!   `exterior`; Mitsuba silently ignores one named otherwise (reported
//!   here). A sensor's medium is any `<medium>` or medium `<ref>` child,
//!   whatever its name.
//! - `sample_emitters` false only changes Mitsuba's noise: reported as
//!   unused.
//!
//! `heterogeneous` media, grid volumes, textures as `sigma_t`/`albedo` and
//! the phase functions `rayleigh`, `sggx`, `blendphase`, `tabphase` are
//! reported once by name and the medium is dropped: a shape naming it has
//! vacuum on that side.
//!
//! Only Mitsuba's volumetric integrators trace media; its `path` (the
//! default) ignores them entirely. A scene whose integrator is not one of
//! [`MEDIA_INTEGRATORS`] therefore loads without media, with a note
//! (Candela then renders what Mitsuba renders).

use super::doc::{describe, elements, Doc, XNode};
use super::spectrum::SpectrumReading;
use super::values::{boolean, constant_color, float, spectrum_read_as};
use super::Builder;
use crate::desc::{MediumDesc, MediumInterface, SourceLoc};
use crate::error::{ErrorKind, LoadError};
use glam::Vec3;

/// Mitsuba's integrators that trace participating media.
pub(super) const MEDIA_INTEGRATORS: [&str; 3] = ["volpath", "volpathmis", "prbvolpath"];

/// Mitsuba's default `sigma_t`, `albedo` and `hg` `g`.
const DEFAULT_SIGMA_T: f32 = 1.0;
const DEFAULT_ALBEDO: f32 = 0.75;
const DEFAULT_HG_G: f32 = 0.8;

/// The scene's `<integrator>`, kept to decide whether media are traced.
#[derive(Clone, Debug)]
pub(super) struct IntegratorSeen {
    pub kind: String,
    pub element: String,
    pub loc: SourceLoc,
}

/// A definition that is either read or was reported as unsupported
/// (`None`: whatever uses it goes without).
type Supported<T> = Option<T>;

impl Builder {
    /// A `<medium>`: its index in [`crate::SceneDesc::media`], or `None`
    /// when it is of a kind Candela lacks (reported).
    pub(super) fn medium(&mut self, doc: &Doc, node: XNode) -> Result<Supported<usize>, LoadError> {
        let kind = doc.plugin_type(node)?;
        match kind.as_str() {
            "homogeneous" => {}
            "heterogeneous" => {
                self.warn(
                    doc,
                    node,
                    "medium type \"heterogeneous\" is not supported (dropped: vacuum instead)",
                )?;
                return Ok(None);
            }
            other => {
                return Err(doc.err(
                    node,
                    ErrorKind::BadValue,
                    format!("unknown medium type \"{other}\""),
                ))
            }
        }
        let Some(sigma_t) = self.medium_value(doc, node, "sigma_t", DEFAULT_SIGMA_T)? else {
            return Ok(None);
        };
        let Some(albedo) = self.medium_value(doc, node, "albedo", DEFAULT_ALBEDO)? else {
            return Ok(None);
        };
        let Some(phase_g) = self.medium_phase(doc, node)? else {
            return Ok(None);
        };
        let scale = float(doc, node, "scale", 1.0)?;
        if scale < 0.0 {
            let p = doc.prop(node, "scale")?.unwrap_or(node);
            return Err(doc.err(p, ErrorKind::BadValue, format!("scale {scale} is negative")));
        }
        if !boolean(doc, node, "sample_emitters", true)? {
            let p = doc.prop(node, "sample_emitters")?.unwrap_or(node);
            self.warn(
                doc,
                p,
                "\"sample_emitters\" false is not used (it changes Mitsuba's noise, not the image)",
            )?;
        }
        self.scene.media.push(MediumDesc {
            name: doc.attr(node, "id")?.unwrap_or(kind),
            sigma_t: sigma_t * scale,
            albedo,
            phase_g,
            loc: doc.loc(node),
        });
        Ok(Some(self.scene.media.len() - 1))
    }

    /// A top-level `<medium>`, `<phase>` or `<volume>`, kept by its id.
    pub(super) fn named_medium_part(&mut self, doc: &Doc, node: XNode) -> Result<(), LoadError> {
        let tag = node.tag_name().name();
        let Some(id) = doc.attr(node, "id")? else {
            return self.warn(
                doc,
                node,
                format!("a top-level <{tag}> without an id is never used"),
            );
        };
        match tag {
            "medium" => {
                let m = self.medium(doc, node)?;
                self.media_by_id.insert(id, m);
            }
            "phase" => {
                let g = self.phase(doc, node)?;
                self.phases.insert(id, g);
            }
            _ => {
                let v = self.volume(doc, node)?;
                self.volumes.insert(id, v);
            }
        }
        Ok(())
    }

    /// The media a shape names for its two sides.
    pub(super) fn shape_media(
        &mut self,
        doc: &Doc,
        shape: XNode,
    ) -> Result<MediumInterface, LoadError> {
        let mut sides = MediumInterface::default();
        for c in elements(shape) {
            let is_medium = match c.tag_name().name() {
                "medium" => true,
                "ref" => self.media_by_id.contains_key(&doc.required(c, "id")?),
                _ => false,
            };
            if !is_medium {
                continue;
            }
            let side = match doc.attr(c, "name")?.as_deref() {
                Some("interior") => &mut sides.interior,
                Some("exterior") => &mut sides.exterior,
                _ => {
                    self.warn(
                        doc,
                        c,
                        "a shape's medium needs name=\"interior\" or \"exterior\" \
                         (ignored, as Mitsuba ignores it)",
                    )?;
                    continue;
                }
            };
            *side = self.medium_of(doc, c)?;
        }
        Ok(sides)
    }

    /// The sensor's medium: its `<medium>` or medium `<ref>` child.
    pub(super) fn sensor_medium(
        &mut self,
        doc: &Doc,
        sensor: XNode,
    ) -> Result<Supported<usize>, LoadError> {
        let mut medium = None;
        for c in elements(sensor) {
            let is_medium = match c.tag_name().name() {
                "medium" => true,
                "ref" => self.media_by_id.contains_key(&doc.required(c, "id")?),
                _ => false,
            };
            if is_medium {
                medium = self.medium_of(doc, c)?;
            }
        }
        Ok(medium)
    }

    /// Whether `id` names a medium (a `<ref>` to it is no BSDF).
    pub(super) fn is_medium_id(&self, id: &str) -> bool {
        self.media_by_id.contains_key(id)
    }

    /// Mitsuba's `path` integrator (its default) and the others but
    /// [`MEDIA_INTEGRATORS`] ignore media: so does the scene then, with a
    /// note.
    pub(super) fn drop_media_the_integrator_ignores(&mut self) {
        if self.scene.media.is_empty() {
            return;
        }
        let (kind, element, loc) = match &self.integrator {
            Some(i) => (i.kind.clone(), i.element.clone(), i.loc),
            None => (
                "path".to_string(),
                "<scene>".to_string(),
                SourceLoc::default(),
            ),
        };
        if MEDIA_INTEGRATORS.contains(&kind.as_str()) {
            return;
        }
        self.scene.media.clear();
        self.scene.medium_interfaces.clear();
        self.scene.camera_medium = None;
        let whose = if self.integrator.is_some() {
            "the file's integrator"
        } else {
            "Mitsuba's default integrator"
        };
        self.warnings.note(
            element,
            format!(
                "participating media are ignored: {whose} \"{kind}\" does not trace them \
                 (Mitsuba's volpath does)"
            ),
            loc,
        );
    }

    /// The medium of a `<medium>` or `<ref>` element.
    fn medium_of(&mut self, doc: &Doc, node: XNode) -> Result<Supported<usize>, LoadError> {
        if node.tag_name().name() == "medium" {
            return self.medium(doc, node);
        }
        let id = doc.required(node, "id")?;
        Ok(self.media_by_id.get(&id).copied().flatten())
    }

    /// `sigma_t` or `albedo` of a medium (see the module docs), checked:
    /// `None` when it is a kind of volume Candela lacks (reported).
    fn medium_value(
        &mut self,
        doc: &Doc,
        medium: XNode,
        name: &str,
        default: f32,
    ) -> Result<Supported<Vec3>, LoadError> {
        let Some(p) = doc.prop(medium, name)? else {
            return Ok(Some(Vec3::splat(default)));
        };
        let value = match p.tag_name().name() {
            "volume" => self.volume(doc, p)?,
            "ref" => {
                let id = doc.required(p, "id")?;
                *self.volumes.get(&id).ok_or_else(|| {
                    doc.err(
                        p,
                        ErrorKind::MissingReference,
                        format!("no <volume> with id \"{id}\""),
                    )
                })?
            }
            "texture" => {
                self.warn(
                    doc,
                    p,
                    format!("a texture as a medium's \"{name}\" is not supported (the medium is dropped: vacuum instead)"),
                )?;
                None
            }
            "spectrum" if name == "sigma_t" => Some(self.clamped_spectrum(doc, p)?),
            _ => Some(constant_value(doc, p)?),
        };
        if let Some(v) = value {
            let ok = match name {
                "albedo" => v.cmpge(Vec3::ZERO).all() && v.cmple(Vec3::ONE).all(),
                _ => v.cmpge(Vec3::ZERO).all(),
            };
            if !ok {
                let range = if name == "albedo" {
                    "in [0, 1]"
                } else {
                    "≥ 0"
                };
                return Err(doc.err(
                    p,
                    ErrorKind::BadValue,
                    format!("medium {name} ({}, {}, {}) is not {range}", v.x, v.y, v.z),
                ));
            }
        }
        Ok(value)
    }

    /// A `<spectrum>` `sigma_t`, clamped to [0, 1] as Mitsuba clamps it,
    /// with a note when that changed it.
    fn clamped_spectrum(&mut self, doc: &Doc, node: XNode) -> Result<Vec3, LoadError> {
        let reading = SpectrumReading::of(doc, node)?;
        let clamped = spectrum_read_as(doc, node, reading)?;
        let written = spectrum_read_as(doc, node, reading.unclamped())?;
        if clamped != written {
            self.warnings.note(
                describe(node),
                format!(
                    "sigma_t ({}, {}, {}) clamped to ({}, {}, {}), as Mitsuba clamps a \
                     spectrum outside a <volume> (a constvolume keeps it)",
                    written.x, written.y, written.z, clamped.x, clamped.y, clamped.z
                ),
                doc.loc(node),
            );
        }
        Ok(clamped)
    }

    /// A `<volume>`: a `constvolume`'s value, or `None` for a grid
    /// (reported).
    fn volume(&mut self, doc: &Doc, node: XNode) -> Result<Supported<Vec3>, LoadError> {
        match doc.plugin_type(node)?.as_str() {
            "constvolume" => match doc.prop(node, "value")? {
                None => Ok(Some(Vec3::ONE)),
                Some(p) if p.tag_name().name() == "texture" || p.tag_name().name() == "ref" => {
                    self.warn(
                        doc,
                        p,
                        "a texture in a constvolume is not supported (a medium using it is dropped: vacuum instead)",
                    )?;
                    Ok(None)
                }
                Some(p) => constant_value(doc, p).map(Some),
            },
            "gridvolume" => {
                self.warn(
                    doc,
                    node,
                    "volume type \"gridvolume\" is not supported (a medium using it is dropped: vacuum instead)",
                )?;
                Ok(None)
            }
            other => Err(doc.err(
                node,
                ErrorKind::BadValue,
                format!("unknown volume type \"{other}\""),
            )),
        }
    }

    /// The medium's phase function as a Henyey–Greenstein g: `None` when it
    /// is one Candela lacks (reported).
    fn medium_phase(&mut self, doc: &Doc, medium: XNode) -> Result<Supported<f32>, LoadError> {
        let mut phase = None;
        for c in elements(medium) {
            let g = match c.tag_name().name() {
                "phase" => self.phase(doc, c)?,
                "ref" => {
                    let id = doc.required(c, "id")?;
                    match self.phases.get(&id) {
                        Some(&g) => g,
                        // A `sigma_t` or `albedo` volume: read above.
                        None if self.volumes.contains_key(&id) => continue,
                        None => {
                            return Err(doc.err(
                                c,
                                ErrorKind::MissingReference,
                                format!("no <phase> or <volume> with id \"{id}\""),
                            ))
                        }
                    }
                }
                _ => continue,
            };
            if phase.is_some() {
                return Err(doc.err(
                    c,
                    ErrorKind::BadValue,
                    "a medium has one phase function (this is its second)",
                ));
            }
            phase = Some(g);
        }
        Ok(phase.unwrap_or(Some(0.0)))
    }

    /// A `<phase>` as a Henyey–Greenstein g (isotropic: 0), or `None` for
    /// one Candela lacks (reported).
    fn phase(&mut self, doc: &Doc, node: XNode) -> Result<Supported<f32>, LoadError> {
        match doc.plugin_type(node)?.as_str() {
            "isotropic" => Ok(Some(0.0)),
            "hg" => {
                let g = float(doc, node, "g", DEFAULT_HG_G)?;
                if g.abs() >= 1.0 {
                    let p = doc.prop(node, "g")?.unwrap_or(node);
                    return Err(doc.err(
                        p,
                        ErrorKind::BadValue,
                        format!("hg asymmetry g {g} is not in (-1, 1)"),
                    ));
                }
                Ok(Some(g))
            }
            kind @ ("rayleigh" | "sggx" | "blendphase" | "tabphase") => {
                self.warn(
                    doc,
                    node,
                    format!("phase function \"{kind}\" is not supported (its medium is dropped: vacuum instead)"),
                )?;
                Ok(None)
            }
            other => Err(doc.err(
                node,
                ErrorKind::BadValue,
                format!("unknown phase function type \"{other}\""),
            )),
        }
    }
}

/// A constant `<float>`, `<rgb>` or `<spectrum>` value.
fn constant_value(doc: &Doc, node: XNode) -> Result<Vec3, LoadError> {
    constant_color(doc, node)?.ok_or_else(|| {
        doc.err(
            node,
            ErrorKind::BadValue,
            "expected <float>, <rgb>, <spectrum> or <volume type=\"constvolume\">",
        )
    })
}
