//! Property values: numbers, lists of numbers, booleans, colours given as
//! `<rgb>`, `<spectrum>` or `<float>`.
//!
//! # Spectra
//! A `<spectrum value="400:0.343, 404:0.445, ...">` becomes the linear RGB
//! that Mitsuba 3's RGB variants make of it (see `spectrum.rs`): inside an
//! `<emitter>` as light (unbounded, white = equal energy), elsewhere as a
//! reflectance under D65 (clamped to [0, 1], except a conductor's `eta`
//! and `k`). A single number (`value="0.5"`) is a flat spectrum: that
//! number elsewhere, the equal-energy white of that power in an emitter.

use super::doc::{Doc, XNode};
use super::spectrum::SpectrumReading;
use crate::error::{ErrorKind, LoadError};
use glam::Vec3;

/// Parses one number of `node`'s attribute text (already substituted).
pub(super) fn number(doc: &Doc, node: XNode, token: &str) -> Result<f32, LoadError> {
    let v: f32 = token.trim().parse().map_err(|_| {
        doc.err(
            node,
            ErrorKind::BadNumber,
            format!("\"{}\" is not a number", token.trim()),
        )
    })?;
    if !v.is_finite() {
        return Err(doc.err(
            node,
            ErrorKind::NonFinite,
            format!("\"{}\" is not finite", token.trim()),
        ));
    }
    Ok(v)
}

/// Numbers separated by commas and/or white space.
pub(super) fn numbers(doc: &Doc, node: XNode, text: &str) -> Result<Vec<f32>, LoadError> {
    text.split(|c: char| c == ',' || c.is_whitespace())
        .filter(|t| !t.is_empty())
        .map(|t| number(doc, node, t))
        .collect()
}

/// Exactly `n` numbers, or a [`ErrorKind::CountMismatch`] error.
pub(super) fn exactly(doc: &Doc, node: XNode, text: &str, n: usize) -> Result<Vec<f32>, LoadError> {
    let v = numbers(doc, node, text)?;
    if v.len() != n {
        return Err(doc.err(
            node,
            ErrorKind::CountMismatch,
            format!("expected {n} numbers, found {}", v.len()),
        ));
    }
    Ok(v)
}

/// A 3-vector from `value="x, y, z"` or from `x`/`y`/`z` attributes
/// (each defaulting to `default`).
pub(super) fn xyz(doc: &Doc, node: XNode, default: f32) -> Result<Vec3, LoadError> {
    if let Some(v) = doc.attr(node, "value")? {
        let n = numbers(doc, node, &v)?;
        return match n.len() {
            1 => Ok(Vec3::splat(n[0])),
            3 => Ok(Vec3::new(n[0], n[1], n[2])),
            k => Err(doc.err(
                node,
                ErrorKind::CountMismatch,
                format!("expected 1 or 3 numbers, found {k}"),
            )),
        };
    }
    let mut out = [default; 3];
    for (o, key) in out.iter_mut().zip(["x", "y", "z"]) {
        if let Some(t) = doc.attr(node, key)? {
            *o = number(doc, node, &t)?;
        }
    }
    Ok(Vec3::from(out))
}

/// The `value` of a `<float>` or `<integer>` property.
pub(super) fn float_of(doc: &Doc, node: XNode) -> Result<f32, LoadError> {
    expect_tag(doc, node, &["float", "integer"])?;
    number(doc, node, &doc.required(node, "value")?)
}

/// Float property `name` of `node`, or `default`.
pub(super) fn float(doc: &Doc, node: XNode, name: &str, default: f32) -> Result<f32, LoadError> {
    match doc.prop(node, name)? {
        Some(p) => float_of(doc, p),
        None => Ok(default),
    }
}

/// Integer property `name`, or `default`.
pub(super) fn integer(doc: &Doc, node: XNode, name: &str, default: i64) -> Result<i64, LoadError> {
    let Some(p) = doc.prop(node, name)? else {
        return Ok(default);
    };
    expect_tag(doc, p, &["integer"])?;
    let v = doc.required(p, "value")?;
    v.trim().parse().map_err(|_| {
        doc.err(
            p,
            ErrorKind::BadNumber,
            format!("\"{}\" is not an integer", v.trim()),
        )
    })
}

/// Boolean property `name`, or `default`.
pub(super) fn boolean(
    doc: &Doc,
    node: XNode,
    name: &str,
    default: bool,
) -> Result<bool, LoadError> {
    let Some(p) = doc.prop(node, name)? else {
        return Ok(default);
    };
    expect_tag(doc, p, &["boolean"])?;
    match doc.required(p, "value")?.trim() {
        "true" | "1" => Ok(true),
        "false" | "0" => Ok(false),
        other => Err(doc.err(
            p,
            ErrorKind::BadValue,
            format!("\"{other}\" is not true or false"),
        )),
    }
}

/// String property `name`, if present.
pub(super) fn string(doc: &Doc, node: XNode, name: &str) -> Result<Option<String>, LoadError> {
    match doc.prop(node, name)? {
        Some(p) => {
            expect_tag(doc, p, &["string"])?;
            doc.required(p, "value").map(Some)
        }
        None => Ok(None),
    }
}

/// A point or vector property `name` (`<point>`/`<vector>`), if present.
pub(super) fn point(doc: &Doc, node: XNode, name: &str) -> Result<Option<Vec3>, LoadError> {
    match doc.prop(node, name)? {
        Some(p) => {
            expect_tag(doc, p, &["point", "vector"])?;
            xyz(doc, p, 0.0).map(Some)
        }
        None => Ok(None),
    }
}

/// A constant colour from an `<rgb>`, `<spectrum>` or `<float>` element
/// (linear RGB), or `None` for other elements (textures, references).
pub(super) fn constant_color(doc: &Doc, node: XNode) -> Result<Option<Vec3>, LoadError> {
    match node.tag_name().name() {
        "rgb" => {
            let v = numbers(doc, node, &doc.required(node, "value")?)?;
            match v.len() {
                1 => Ok(Some(Vec3::splat(v[0]))),
                3 => Ok(Some(Vec3::new(v[0], v[1], v[2]))),
                k => Err(doc.err(
                    node,
                    ErrorKind::CountMismatch,
                    format!("expected 3 numbers (or 1), found {k}"),
                )),
            }
        }
        "spectrum" => spectrum(doc, node).map(Some),
        "float" | "integer" => float_of(doc, node).map(|v| Some(Vec3::splat(v))),
        _ => Ok(None),
    }
}

/// A `<spectrum>`: one number (flat) or `wavelength:value` pairs in
/// increasing wavelength, as linear RGB (see the module docs).
pub(super) fn spectrum(doc: &Doc, node: XNode) -> Result<Vec3, LoadError> {
    spectrum_read_as(doc, node, SpectrumReading::of(doc, node)?)
}

/// A `<spectrum>` read as `reading` says (see [`spectrum`]).
pub(super) fn spectrum_read_as(
    doc: &Doc,
    node: XNode,
    reading: SpectrumReading,
) -> Result<Vec3, LoadError> {
    let Some(text) = doc.attr(node, "value")? else {
        return Err(doc.err(
            node,
            ErrorKind::MissingElement,
            "only inline spectra (value=\"...\") are supported",
        ));
    };
    if !text.contains(':') {
        let v = numbers(doc, node, &text)?;
        if v.len() != 1 {
            return Err(doc.err(
                node,
                ErrorKind::CountMismatch,
                format!("a flat spectrum has 1 number, found {}", v.len()),
            ));
        }
        return Ok(reading.flat(v[0]));
    }
    let mut samples: Vec<(f32, f32)> = Vec::new();
    for pair in text.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        let (l, v) = pair.split_once(':').ok_or_else(|| {
            doc.err(
                node,
                ErrorKind::BadValue,
                format!("\"{pair}\" is not wavelength:value"),
            )
        })?;
        let (l, v) = (number(doc, node, l)?, number(doc, node, v)?);
        if samples.last().is_some_and(|&(prev, _)| l <= prev) {
            return Err(doc.err(node, ErrorKind::BadValue, "wavelengths must increase"));
        }
        samples.push((l, v));
    }
    Ok(reading.rgb(&samples))
}

/// An error unless `node` is one of the element kinds `tags`.
pub(super) fn expect_tag(doc: &Doc, node: XNode, tags: &[&str]) -> Result<(), LoadError> {
    if tags.contains(&node.tag_name().name()) {
        return Ok(());
    }
    Err(doc.err(
        node,
        ErrorKind::BadValue,
        format!(
            "property has the wrong type: expected <{}>",
            tags.join("> or <")
        ),
    ))
}
