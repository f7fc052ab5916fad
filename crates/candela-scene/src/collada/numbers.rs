//! Numbers in element text and attributes.
//!
//! Arrays are split on ASCII whitespace and parsed with `str::parse`, without
//! allocating per number. A declared `count` is checked against a hard limit
//! *before* anything is allocated, and the allocation is also bounded by the
//! length of the text, so a hostile count cannot exhaust memory.

use super::xml::{text, Ctx, XNode};
use crate::error::{clip, ErrorKind, LoadError};
use glam::Vec3;

/// Largest array the loader accepts. A number takes at least two bytes of text
/// (digit and separator), so no file under the 512 MiB limit can hold more.
pub(crate) const MAX_ARRAY_LEN: usize = 256 << 20;

/// Parses every number in `node`'s text as `f32`; with `count`, exactly that
/// many must be present. Infinite and NaN values are errors.
pub(crate) fn floats(ctx: &Ctx, node: XNode, count: Option<usize>) -> Result<Vec<f32>, LoadError> {
    let s = text(node);
    let mut out = Vec::with_capacity(capacity(ctx, node, count, s)?);
    for token in s.split_ascii_whitespace() {
        let v: f32 = token.parse().map_err(|_| {
            ctx.err_token(
                node,
                token,
                ErrorKind::BadNumber,
                format!("\"{}\" is not a number", clip(token)),
            )
        })?;
        if !v.is_finite() {
            return Err(ctx.err_token(
                node,
                token,
                ErrorKind::NonFinite,
                format!("\"{}\" is not finite", clip(token)),
            ));
        }
        out.push(v);
    }
    check_count(ctx, node, count, out.len())?;
    Ok(out)
}

/// Parses every number in `node`'s text as a non-negative integer index.
pub(crate) fn indices(ctx: &Ctx, node: XNode, count: Option<usize>) -> Result<Vec<u32>, LoadError> {
    let s = text(node);
    let mut out = Vec::with_capacity(capacity(ctx, node, count, s)?);
    for token in s.split_ascii_whitespace() {
        let v: u32 = token.parse().map_err(|_| {
            ctx.err_token(
                node,
                token,
                ErrorKind::BadNumber,
                format!("\"{}\" is not a non-negative integer", clip(token)),
            )
        })?;
        out.push(v);
    }
    check_count(ctx, node, count, out.len())?;
    Ok(out)
}

/// Byte offset of the `n`-th (0-based) number in `node`'s text, for pointing
/// at one bad index after the fact.
pub(crate) fn nth_token<'a>(node: XNode<'a, '_>, n: usize) -> Option<&'a str> {
    text(node).split_ascii_whitespace().nth(n)
}

/// One number.
pub(crate) fn float(ctx: &Ctx, node: XNode) -> Result<f32, LoadError> {
    match floats(ctx, node, None)?.as_slice() {
        [x] => Ok(*x),
        v => Err(ctx.err(
            node,
            ErrorKind::CountMismatch,
            format!("expected 1 number but found {}", v.len()),
        )),
    }
}

/// A colour or vector: three numbers, or four (RGBA, alpha dropped).
pub(crate) fn vec3(ctx: &Ctx, node: XNode) -> Result<Vec3, LoadError> {
    let v = floats(ctx, node, None)?;
    match v.len() {
        3 | 4 => Ok(Vec3::new(v[0], v[1], v[2])),
        n => Err(ctx.err(
            node,
            ErrorKind::CountMismatch,
            format!("expected 3 numbers but found {n}"),
        )),
    }
}

/// An optional unsigned integer attribute.
pub(crate) fn attr_usize(ctx: &Ctx, node: XNode, name: &str) -> Result<Option<usize>, LoadError> {
    let Some(v) = node.attribute(name) else {
        return Ok(None);
    };
    let byte = node
        .attribute_node(name)
        .map_or(node.range().start, |a| a.range_value().start);
    let n: u64 = v.trim().parse().map_err(|_| {
        ctx.err_at(
            byte,
            node,
            ErrorKind::BadNumber,
            format!("{name}=\"{}\" is not a non-negative integer", clip(v)),
        )
    })?;
    match usize::try_from(n) {
        Ok(n) if n <= MAX_ARRAY_LEN => Ok(Some(n)),
        _ => Err(ctx.err_at(
            byte,
            node,
            ErrorKind::TooLarge,
            format!("{name}=\"{n}\" exceeds the limit of {MAX_ARRAY_LEN}"),
        )),
    }
}

fn capacity(ctx: &Ctx, node: XNode, count: Option<usize>, s: &str) -> Result<usize, LoadError> {
    let most = s.len() / 2 + 1;
    match count {
        Some(c) if c > MAX_ARRAY_LEN => Err(ctx.err(
            node,
            ErrorKind::TooLarge,
            format!("count=\"{c}\" exceeds the limit of {MAX_ARRAY_LEN}"),
        )),
        Some(c) => Ok(c.min(most)),
        None => Ok(most.min(1024)),
    }
}

fn check_count(
    ctx: &Ctx,
    node: XNode,
    count: Option<usize>,
    found: usize,
) -> Result<(), LoadError> {
    match count {
        Some(c) if c != found => Err(count_mismatch(ctx, node, c, found)),
        _ => Ok(()),
    }
}

/// The error for an element whose `count` (declared or implied) is `c` but
/// whose text holds `found` numbers.
pub(crate) fn count_mismatch(ctx: &Ctx, node: XNode, c: usize, found: usize) -> LoadError {
    ctx.err(
        node,
        ErrorKind::CountMismatch,
        format!("count=\"{c}\" but {found} numbers"),
    )
}
