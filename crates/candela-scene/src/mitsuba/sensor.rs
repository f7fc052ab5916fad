//! The sensor (camera), its film and sampler, and the integrator. Film
//! size, reconstruction filter, sample count and depth become
//! [`crate::RenderHints`]: defaults that command-line flags override.
//!
//! # Reconstruction filter
//! The film's `<rfilter>` (box, tent, gaussian, mitchell, catmullrom,
//! lanczos, with Mitsuba 3's parameter names and defaults) becomes a
//! [`FilterHint`]; without one, Mitsuba's default, a Gaussian of σ = 0.5
//! (radius 2). Other filters are reported once by name and replaced by
//! that default. Mitsuba's film samples only inside the frame
//! (`sample_border` false), i.e. its edge pixels see a truncated filter;
//! Candela's camera samples the whole filter there, up to `radius − 0.5`
//! pixels outside the frame (the renderer's `camera/filter.rs`), so the
//! two differ slightly in the outermost pixels only.
//!
//! # Camera handedness
//! A Mitsuba camera looks down its local +Z with +Y up and +X to the *left*
//! of the image (its `lookat` builds x = up × dir). A Candela camera looks
//! down −Z with +X to the right. Turning the Mitsuba frame half a turn
//! about its Y axis (x → −x, z → −z) maps one onto the other, so
//! `world_from_camera = to_world · diag(−1, 1, −1)`: a rotation, the image
//! is not mirrored.
//!
//! # Clip planes
//! `near_clip` (default 0.01) and `far_clip` (default 10⁴) become the
//! camera's [`ClipRange`]: planes across the view axis, as Mitsuba's
//! perspective and thin-lens sensors apply them to camera rays only (a
//! ray at angle θ to the axis starts at `near / cos θ`, ends at
//! `far / cos θ`).
//!
//! # Depth
//! Mitsuba's `max_depth` counts path segments (1 = emitters seen directly);
//! Candela's counts bounces (0 = emitters seen directly), so Candela's
//! depth is `max_depth − 1`, and `−1` (unlimited) becomes
//! [`UNLIMITED_DEPTH`] (Russian roulette ends paths long before).

use super::doc::{describe, elements, Doc, XNode};
use super::media::IntegratorSeen;
use super::transform::to_world;
use super::values::{boolean, float, integer, string};
use super::Builder;
use crate::desc::{CameraDesc, ClipRange, Projection};
use crate::error::{ErrorKind, LoadError};
use crate::hints::FilterHint;
use glam::{Mat4, Vec3};

/// Candela's depth for Mitsuba's unlimited `max_depth = -1`.
pub(crate) const UNLIMITED_DEPTH: u32 = 1024;

/// Mitsuba's default film size.
const DEFAULT_FILM: (u32, u32) = (768, 576);

/// An `<integrator>`: `path` (and its relatives) give the depth; its type
/// decides whether media are traced (`media.rs`).
pub(super) fn integrator(b: &mut Builder, doc: &Doc, node: XNode) -> Result<(), LoadError> {
    let kind = doc.plugin_type(node)?;
    b.integrator = Some(IntegratorSeen {
        kind: kind.clone(),
        element: describe(node),
        loc: doc.loc(node),
    });
    let depth = match kind.as_str() {
        "path" | "volpath" | "volpathmis" | "prbvolpath" | "prb" | "prb_basic" => {
            integer(doc, node, "max_depth", -1)?
        }
        "direct" => 2,
        _ => {
            b.warn(
                doc,
                node,
                format!("integrator \"{kind}\" rendered by the path tracer"),
            )?;
            integer(doc, node, "max_depth", -1)?
        }
    };
    // Emitters seen directly are left out of the image (Mitsuba hides them
    // at its depth 0, the camera ray's first hit, and only there).
    b.hints.hide_emitters = boolean(doc, node, "hide_emitters", false)?;
    b.hints.max_depth = Some(match depth {
        -1 => UNLIMITED_DEPTH,
        d if d >= 1 => u32::try_from(d - 1)
            .unwrap_or(UNLIMITED_DEPTH)
            .min(UNLIMITED_DEPTH),
        d => {
            return Err(doc.err(
                node,
                ErrorKind::BadValue,
                format!("max_depth {d} (expected -1 or at least 1)"),
            ))
        }
    });
    Ok(())
}

/// A `<sensor>`: `perspective`, `thinlens` or `orthographic`.
pub(super) fn sensor(b: &mut Builder, doc: &Doc, node: XNode) -> Result<(), LoadError> {
    let kind = doc.plugin_type(node)?;
    if !matches!(kind.as_str(), "perspective" | "thinlens" | "orthographic") {
        if matches!(kind.as_str(), "radiancemeter" | "irradiancemeter" | "batch") {
            return b.warn(
                doc,
                node,
                format!("sensor \"{kind}\" is not supported (skipped)"),
            );
        }
        return Err(doc.err(
            node,
            ErrorKind::BadValue,
            format!("unknown sensor type \"{kind}\""),
        ));
    }
    let (film, filter) = film(b, doc, node)?;
    sampler(b, doc, node)?;
    let projection = if kind == "orthographic" {
        orthographic(b, doc, node)?
    } else if kind == "thinlens" {
        let (xfov_deg, yfov_deg) = fields_of_view(doc, node, film)?;
        let aperture_radius = float(doc, node, "aperture_radius", f32::NAN)?;
        let focus_distance = float(doc, node, "focus_distance", f32::NAN)?;
        if !(aperture_radius >= 0.0 && focus_distance > 0.0) {
            return Err(doc.err(
                node,
                ErrorKind::DegenerateCamera,
                "a thinlens needs aperture_radius >= 0 and focus_distance > 0",
            ));
        }
        Projection::ThinLens {
            xfov_deg,
            yfov_deg,
            aperture_radius,
            focus_distance,
        }
    } else {
        let (xfov_deg, yfov_deg) = fields_of_view(doc, node, film)?;
        Projection::Perspective { xfov_deg, yfov_deg }
    };
    let world_from_camera = to_world(doc, node)? * Mat4::from_scale(Vec3::new(-1.0, 1.0, -1.0));
    if world_from_camera.determinant().abs().partial_cmp(&1e-12)
        != Some(std::cmp::Ordering::Greater)
    {
        return Err(doc.err(
            node,
            ErrorKind::DegenerateCamera,
            "to_world is not invertible",
        ));
    }
    let near = float(doc, node, "near_clip", 0.01)?;
    let far = float(doc, node, "far_clip", 10_000.0)?;
    if !(near > 0.0 && far > near) {
        return Err(doc.err(
            node,
            ErrorKind::DegenerateCamera,
            format!("clip range [{near}, {far}] is empty"),
        ));
    }
    let medium = b.sensor_medium(doc, node)?;
    if b.scene.cameras.is_empty() {
        b.scene.camera_medium = medium;
    } else if medium != b.scene.camera_medium {
        b.warn(
            doc,
            node,
            "a sensor medium unlike the first sensor's is not supported (every camera is in the first sensor's medium)",
        )?;
    }
    if b.scene.cameras.is_empty() {
        b.hints.file_camera = true;
        b.hints.resolution = Some(film);
        b.hints.filter = Some(filter);
    }
    b.scene.cameras.push(CameraDesc {
        name: doc.attr(node, "id")?.unwrap_or(kind),
        world_from_camera,
        projection,
        znear: Some(near),
        zfar: Some(far),
        clip: Some(ClipRange { near, far }),
        loc: doc.loc(node),
    });
    Ok(())
}

/// An `orthographic` sensor's extent: Mitsuba's film spans camera x in
/// [−1, 1] and y in [−1, 1] over the aspect, both scaled by `to_world`, so
/// the view is 2·|to_world x| wide and its height follows the image's
/// aspect, as Candela's orthographic camera makes it. A y scale unlike the
/// x scale (a squashed view) is reported and the x scale used.
fn orthographic(b: &mut Builder, doc: &Doc, node: XNode) -> Result<Projection, LoadError> {
    let m = to_world(doc, node)?;
    let (sx, sy) = (m.x_axis.truncate().length(), m.y_axis.truncate().length());
    if !(sx > 0.0 && sx.is_finite()) {
        return Err(doc.err(
            node,
            ErrorKind::DegenerateCamera,
            "to_world is not invertible",
        ));
    }
    if (sx - sy).abs() > 1e-4 * sx.max(sy) {
        b.warn(
            doc,
            node,
            format!("an orthographic view scaled unevenly (x {sx}, y {sy}) keeps the image's aspect; x's scale is used"),
        )?;
    }
    Ok(Projection::Orthographic { width: 2.0 * sx })
}

/// Horizontal and vertical fields of view (degrees) from `fov` along
/// `fov_axis` (x, y, diagonal, smaller, larger) for a `w` × `h` film; a
/// `focal_length` ("50mm", 35 mm film, 36 mm wide) when there is no `fov`.
fn fields_of_view(doc: &Doc, node: XNode, (w, h): (u32, u32)) -> Result<(f32, f32), LoadError> {
    let (w, h) = (w as f32, h as f32);
    let (fov, axis) = match doc.prop(node, "fov")? {
        Some(_) => (
            float(doc, node, "fov", 0.0)?,
            string(doc, node, "fov_axis")?.unwrap_or_else(|| "x".into()),
        ),
        None => {
            let f = string(doc, node, "focal_length")?.unwrap_or_else(|| "50mm".into());
            let mm: f32 = f.trim().trim_end_matches("mm").parse().map_err(|_| {
                doc.err(
                    node,
                    ErrorKind::BadNumber,
                    format!("focal_length \"{f}\" is not like \"50mm\""),
                )
            })?;
            (2.0 * (18.0 / mm).atan().to_degrees(), "x".into())
        }
    };
    if !(fov > 0.0 && fov < 180.0) {
        return Err(doc.err(
            node,
            ErrorKind::DegenerateCamera,
            format!("field of view {fov} is not in (0, 180)"),
        ));
    }
    let t = (0.5 * fov.to_radians()).tan();
    let (tx, ty) = match axis.as_str() {
        "x" => (t, t * h / w),
        "y" => (t * w / h, t),
        "diagonal" => {
            let d = (w * w + h * h).sqrt();
            (t * w / d, t * h / d)
        }
        "smaller" if w <= h => (t, t * h / w),
        "smaller" => (t * w / h, t),
        "larger" if w >= h => (t, t * h / w),
        "larger" => (t * w / h, t),
        other => {
            return Err(doc.err(
                node,
                ErrorKind::BadValue,
                format!(
                    "unknown fov_axis \"{other}\" (expected x, y, diagonal, smaller or larger)"
                ),
            ))
        }
    };
    Ok((2.0 * tx.atan().to_degrees(), 2.0 * ty.atan().to_degrees()))
}

/// The sensor's `<film>` size and reconstruction filter (Mitsuba's
/// defaults without one).
fn film(b: &mut Builder, doc: &Doc, sensor: XNode) -> Result<((u32, u32), FilterHint), LoadError> {
    let Some(film) = elements(sensor).find(|c| c.tag_name().name() == "film") else {
        return Ok((DEFAULT_FILM, FilterHint::MITSUBA_DEFAULT));
    };
    let w = integer(doc, film, "width", DEFAULT_FILM.0 as i64)?;
    let h = integer(doc, film, "height", DEFAULT_FILM.1 as i64)?;
    let ok = |v: i64| (1..=1 << 16).contains(&v);
    if !(ok(w) && ok(h)) {
        return Err(doc.err(
            film,
            ErrorKind::BadValue,
            format!("film size {w}x{h} is not in 1..=65536"),
        ));
    }
    if doc.prop(film, "crop_width")?.is_some() || doc.prop(film, "crop_offset_x")?.is_some() {
        b.warn(
            doc,
            film,
            "film cropping is not supported (the whole film is rendered)",
        )?;
    }
    let filter = match elements(film).find(|c| c.tag_name().name() == "rfilter") {
        Some(node) => rfilter(b, doc, node)?,
        None => FilterHint::MITSUBA_DEFAULT,
    };
    Ok(((w as u32, h as u32), filter))
}

/// An `<rfilter>`, with Mitsuba 3's parameter names and defaults; an
/// unsupported one is reported and replaced by Mitsuba's default.
fn rfilter(b: &mut Builder, doc: &Doc, node: XNode) -> Result<FilterHint, LoadError> {
    let kind = doc.plugin_type(node)?;
    let positive = |name: &str, default: f32| -> Result<f32, LoadError> {
        let v = float(doc, node, name, default)?;
        if v > 0.0 {
            Ok(v)
        } else {
            Err(doc.err(
                node,
                ErrorKind::BadValue,
                format!("rfilter {kind}: {name} {v} must be > 0"),
            ))
        }
    };
    Ok(match kind.as_str() {
        "box" => FilterHint::Box,
        "tent" => FilterHint::Tent {
            radius: positive("radius", 1.0)?,
        },
        "gaussian" => FilterHint::Gaussian {
            stddev: positive("stddev", 0.5)?,
        },
        "mitchell" => FilterHint::Mitchell {
            b: float(doc, node, "B", 1.0 / 3.0)?,
            c: float(doc, node, "C", 1.0 / 3.0)?,
        },
        "catmullrom" => FilterHint::CatmullRom,
        "lanczos" => {
            let lobes = integer(doc, node, "lobes", 3)?;
            if !(1..=8).contains(&lobes) {
                return Err(doc.err(
                    node,
                    ErrorKind::BadValue,
                    format!("rfilter lanczos: lobes {lobes} is not in 1..=8"),
                ));
            }
            FilterHint::Lanczos {
                lobes: lobes as u32,
            }
        }
        _ => {
            b.warn(
                doc,
                node,
                format!(
                    "rfilter \"{kind}\" is not supported (Mitsuba's default gaussian, \
                     stddev 0.5, is used)"
                ),
            )?;
            FilterHint::MITSUBA_DEFAULT
        }
    })
}

/// The sensor's `<sampler>` sample count.
fn sampler(b: &mut Builder, doc: &Doc, sensor: XNode) -> Result<(), LoadError> {
    let Some(s) = elements(sensor).find(|c| c.tag_name().name() == "sampler") else {
        return Ok(());
    };
    let n = integer(doc, s, "sample_count", 4)?;
    if !(1..=1 << 24).contains(&n) {
        return Err(doc.err(
            s,
            ErrorKind::BadValue,
            format!("sample_count {n} is not in 1..=16777216"),
        ));
    }
    if b.scene.cameras.is_empty() {
        b.hints.spp = Some(n as u32);
    }
    Ok(())
}
