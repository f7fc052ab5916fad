//! Repairs for defects that real course files (CS184, CMU 15-462) contain.
//!
//! A defect is repaired only when the repair invents nothing the file does
//! not imply: a matrix's missing affine row, a default the loader would use
//! anyway, a colour clamped into its physical range, a profile alias. Each
//! repair goes through [`Ctx::repair`]: a strict load gets the error it has
//! always given, a default load a warning naming the element, its place, the
//! defect and the fix. The rules are listed in README.md ("Lenient loading").
//! Count repairs live with the data they count (`sources`, `primitives`).

use super::numbers::{count_mismatch, floats};
use super::xml::{children, Ctx, XNode};
use crate::error::{ErrorKind, LoadError};
use glam::Vec3;

/// Profiles read as `CGL` outside strict mode: the CMU 15-462 files name the
/// same extension (spheres, BSDFs, area lights) after their course.
const CGL_ALIASES: [&str; 2] = ["CMU462", "CMU"];

/// The affine last row of a row-major 4x4 matrix.
const AFFINE_ROW: [f32; 4] = [0.0, 0.0, 0.0, 1.0];

/// The 16 numbers of a `<matrix>`, repaired when the file gives 12 to 15 of
/// them and those of the last row present agree with `0 0 0 1` (the rest is
/// that row), or more than 16 of which the first 16 end in `0 0 0 1` (the
/// rest is dropped). Anything else is a count mismatch.
pub(crate) fn matrix(ctx: &Ctx, el: XNode) -> Result<[f32; 16], LoadError> {
    let v = floats(ctx, el, None)?;
    let mut a = [0.0; 16];
    if v.len() == 16 {
        a.copy_from_slice(&v);
        return Ok(a);
    }
    let err = {
        let mut e = count_mismatch(ctx, el, 16, v.len());
        e.message = format!("expected 16 numbers (needs \"16\" but {} numbers)", v.len());
        e
    };
    let fix = match v.len() {
        n @ 12..=15 if v[12..] == AFFINE_ROW[..n - 12] => "the last row completed as 0 0 0 1",
        n if n > 16 && v[12..16] == AFFINE_ROW => "the numbers after the 16th dropped",
        _ => return Err(err),
    };
    ctx.repair(err, fix)?;
    let n = v.len().min(16);
    a[..n].copy_from_slice(&v[..n]);
    a[n..].copy_from_slice(&AFFINE_ROW[n - 12..]);
    Ok(a)
}

/// An optional number with a default: absent gives the default, and so
/// does an infinite or NaN value (repaired).
pub(crate) fn float_or(ctx: &Ctx, node: Option<XNode>, default: f32) -> Result<f32, LoadError> {
    let Some(node) = node else {
        return Ok(default);
    };
    match super::numbers::float(ctx, node) {
        Err(e) if e.kind == ErrorKind::NonFinite => {
            ctx.repair(e, &format!("the default {default} used"))?;
            Ok(default)
        }
        r => r,
    }
}

/// What a colour means, which decides its physical range.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Color {
    /// A fraction of light kept (albedo, reflectance, transmittance): [0, 1].
    Reflectance,
    /// Light given off (radiance, intensity): at least 0.
    Emitted,
}

/// A colour, clamped into its range (repaired; a `BadValue` when strict).
pub(crate) fn color(ctx: &Ctx, node: XNode, kind: Color) -> Result<Vec3, LoadError> {
    let c = super::numbers::vec3(ctx, node)?;
    let hi = match kind {
        Color::Reflectance => 1.0,
        Color::Emitted => f32::INFINITY,
    };
    let clamped = c.clamp(Vec3::ZERO, Vec3::splat(hi));
    if clamped != c {
        let (what, range) = match kind {
            Color::Reflectance => ("reflectance", "[0, 1]"),
            Color::Emitted => ("emitted colour", "[0, inf)"),
        };
        let err = ctx.err(
            node,
            ErrorKind::BadValue,
            format!("{what} ({}, {}, {}) is outside {range}", c.x, c.y, c.z),
        );
        ctx.repair(
            err,
            &format!("clamped to ({}, {}, {})", clamped.x, clamped.y, clamped.z),
        )?;
    }
    Ok(clamped)
}

/// An optional colour with a default: absent or non-finite gives the
/// default (repaired); otherwise as [`color`].
pub(crate) fn color_or(
    ctx: &Ctx,
    node: Option<XNode>,
    kind: Color,
    default: Vec3,
) -> Result<Vec3, LoadError> {
    let Some(node) = node else {
        return Ok(default);
    };
    match color(ctx, node, kind) {
        Err(e) if e.kind == ErrorKind::NonFinite => {
            let d = default;
            ctx.repair(e, &format!("the default ({}, {}, {}) used", d.x, d.y, d.z))?;
            Ok(default)
        }
        r => r,
    }
}

/// Whether a `<technique>` is the CGL extension: its profile is `CGL`, or,
/// outside strict mode, one of [`CGL_ALIASES`] (reported once per alias).
pub(crate) fn is_cgl(ctx: &Ctx, technique: XNode) -> Result<bool, LoadError> {
    let Some(profile) = technique.attribute("profile") else {
        return Ok(false);
    };
    if profile == "CGL" {
        return Ok(true);
    }
    if ctx.strict() || !CGL_ALIASES.contains(&profile) {
        return Ok(false);
    }
    ctx.warn(
        technique,
        format!("profile \"{profile}\" read as its alias \"CGL\""),
    )?;
    Ok(true)
}

/// The CGL `<technique>` under `node`, directly or inside `<extra>`.
pub(crate) fn cgl_technique<'a, 'i>(
    ctx: &Ctx,
    node: XNode<'a, 'i>,
) -> Result<Option<XNode<'a, 'i>>, LoadError> {
    let all = || {
        let extras = children(node, "extra").flat_map(|e| children(e, "technique"));
        children(node, "technique").chain(extras)
    };
    if let Some(t) = all().find(|t| t.attribute("profile") == Some("CGL")) {
        return Ok(Some(t));
    }
    for t in all() {
        if is_cgl(ctx, t)? {
            return Ok(Some(t));
        }
    }
    Ok(None)
}
