//! Primitive elements (`<polylist>`, `<triangles>`, `<polygons>`): their
//! inputs, polygon sizes and index lists, checked for consistency.

use super::numbers::{attr_usize, count_mismatch, indices, nth_token};
use super::xml::{child, children, elements, Ctx, XNode};
use crate::error::{ErrorKind, LoadError};

/// One attribute stream of a primitive: which `<source>`, at which offset.
#[derive(Clone, Copy)]
pub(crate) struct Stream<'a, 'i> {
    pub source: XNode<'a, 'i>,
    pub offset: usize,
}

/// A primitive element, read and checked, not yet resolved against sources.
pub(crate) struct Primitive<'a, 'i> {
    /// The element itself.
    pub node: XNode<'a, 'i>,
    /// Positions (always present).
    pub pos: Stream<'a, 'i>,
    /// Normals, if any.
    pub normal: Option<Stream<'a, 'i>>,
    /// Texture coordinates (the first set), if any.
    pub uv: Option<Stream<'a, 'i>>,
    /// Indices per corner (max input offset + 1).
    pub stride: usize,
    /// Vertex count of each polygon (each >= 3).
    pub vcounts: Vec<u32>,
    /// All corner indices, `stride` per corner.
    pub p: Vec<u32>,
    /// The `<p>` elements and where each starts in `p`, to locate a bad index.
    pub p_nodes: Vec<(XNode<'a, 'i>, usize)>,
}

impl<'a, 'i> Primitive<'a, 'i> {
    /// Locates the `k`-th entry of `p` in the text, for an error.
    pub fn index_error(&self, ctx: &Ctx, k: usize, message: String) -> LoadError {
        let (node, start) = self
            .p_nodes
            .iter()
            .rev()
            .find(|(_, s)| *s <= k)
            .copied()
            .unwrap_or((self.node, 0));
        match nth_token(node, k - start) {
            Some(tok) => ctx.err_token(node, tok, ErrorKind::IndexOutOfRange, message),
            None => ctx.err(node, ErrorKind::IndexOutOfRange, message),
        }
    }
}

/// Fan triangulation of a convex polygon with `n` corners: (0, i, i + 1).
pub(crate) fn fan(n: usize) -> impl Iterator<Item = [usize; 3]> {
    (1..n.saturating_sub(1)).map(|i| [0, i, i + 1])
}

/// Reads one primitive element.
pub(crate) fn read<'a, 'i>(
    ctx: &Ctx<'a, 'i>,
    prim: XNode<'a, 'i>,
) -> Result<Primitive<'a, 'i>, LoadError> {
    let (pos, normal, uv, stride) = inputs(ctx, prim)?;
    let count = attr_usize(ctx, prim, "count")?;
    let mut out = Primitive {
        node: prim,
        pos,
        normal,
        uv,
        stride,
        vcounts: Vec::new(),
        p: Vec::new(),
        p_nodes: Vec::new(),
    };
    match prim.tag_name().name() {
        "polygons" => read_polygons(ctx, &mut out, count)?,
        kind => {
            let Some(p) = child(prim, "p") else {
                if count.unwrap_or(0) == 0 {
                    return Ok(out);
                }
                return Err(ctx.err(prim, ErrorKind::MissingElement, "missing <p>"));
            };
            out.p = indices(ctx, p, None)?;
            out.p_nodes.push((p, 0));
            if kind == "triangles" {
                triangle_counts(ctx, &mut out, p, count)?;
            } else {
                polylist_counts(ctx, &mut out, p, count)?;
            }
        }
    }
    Ok(out)
}

type Inputs<'a, 'i> = (
    Stream<'a, 'i>,
    Option<Stream<'a, 'i>>,
    Option<Stream<'a, 'i>>,
    usize,
);

/// The primitive's inputs (following VERTEX into `<vertices>`) and its stride.
fn inputs<'a, 'i>(ctx: &Ctx<'a, 'i>, prim: XNode<'a, 'i>) -> Result<Inputs<'a, 'i>, LoadError> {
    let (mut pos, mut normal, mut uv) = (None, None, None);
    let mut stride = 0;
    for input in children(prim, "input") {
        let offset = attr_usize(ctx, input, "offset")?
            .ok_or_else(|| ctx.err(input, ErrorKind::MissingElement, "missing attribute offset"))?;
        stride = stride.max(offset + 1);
        let semantic = input.attribute("semantic").unwrap_or("");
        if semantic == "VERTEX" {
            let Some(vertices) = ctx.resolve(input, "source", &["vertices"])? else {
                continue;
            };
            for vin in children(vertices, "input") {
                let sem = vin.attribute("semantic").unwrap_or("");
                assign(ctx, vin, sem, offset, &mut pos, &mut normal, &mut uv)?;
            }
        } else {
            assign(ctx, input, semantic, offset, &mut pos, &mut normal, &mut uv)?;
        }
    }
    let pos = pos.ok_or_else(|| {
        ctx.err(
            prim,
            ErrorKind::MissingElement,
            "no POSITION input (through VERTEX)",
        )
    })?;
    Ok((pos, normal, uv, stride))
}

fn assign<'a, 'i>(
    ctx: &Ctx<'a, 'i>,
    input: XNode<'a, 'i>,
    semantic: &str,
    offset: usize,
    pos: &mut Option<Stream<'a, 'i>>,
    normal: &mut Option<Stream<'a, 'i>>,
    uv: &mut Option<Stream<'a, 'i>>,
) -> Result<(), LoadError> {
    let slot = match semantic {
        "POSITION" => pos,
        "NORMAL" => normal,
        "TEXCOORD" => uv,
        other => {
            return ctx.warn(
                input,
                format!("input semantic {other} not supported; ignored"),
            )
        }
    };
    if slot.is_some() {
        return ctx.warn(input, format!("additional {semantic} input ignored"));
    }
    if let Some(source) = ctx.resolve(input, "source", &["source"])? {
        *slot = Some(Stream { source, offset });
    }
    Ok(())
}

fn triangle_counts(
    ctx: &Ctx,
    out: &mut Primitive,
    p: XNode,
    count: Option<usize>,
) -> Result<(), LoadError> {
    let per = (3 * out.stride).max(1);
    let (n, rest) = (out.p.len() / per, out.p.len() % per);
    let msg = match count {
        Some(c) if c.saturating_mul(per) != out.p.len() => {
            format!(
                "count=\"{c}\" needs {} indices but <p> has {}",
                c.saturating_mul(per),
                out.p.len()
            )
        }
        _ if rest != 0 => format!("<p> has {} indices, not a multiple of {per}", out.p.len()),
        _ => String::new(),
    };
    if !msg.is_empty() {
        let err = ctx.err(p, ErrorKind::CountMismatch, msg);
        let fix = match count {
            // The indices are whole triangles: the count is only a wrong summary.
            Some(_) if rest == 0 => format!("the {n} triangles in <p> used"),
            // The last triangle is cut short (and the count, if any, agrees).
            Some(c) if c != n + 1 => return Err(err),
            _ => format!("the incomplete last triangle dropped ({n} kept)"),
        };
        ctx.repair(err, &fix)?;
        out.p.truncate(n * per);
    }
    out.vcounts = vec![3; n];
    Ok(())
}

fn polylist_counts(
    ctx: &Ctx,
    out: &mut Primitive,
    p: XNode,
    count: Option<usize>,
) -> Result<(), LoadError> {
    let vc = child(out.node, "vcount")
        .ok_or_else(|| ctx.err(out.node, ErrorKind::MissingElement, "missing <vcount>"))?;
    out.vcounts = indices(ctx, vc, None)?;
    let stride = out.stride as u64;
    let corners: u64 = out.vcounts.iter().map(|&n| u64::from(n)).sum();
    let needed = corners.saturating_mul(stride);
    let found = out.p.len() as u64;
    if let Some(c) = count.filter(|&c| c != out.vcounts.len()) {
        // `<vcount>` and `<p>` agreeing outvote the count attribute.
        let err = count_mismatch(ctx, vc, c, out.vcounts.len());
        if needed != found {
            return Err(err);
        }
        let fix = format!("the {} polygons of <vcount> used", out.vcounts.len());
        ctx.repair(err, &fix)?;
    }
    for (i, &n) in out.vcounts.iter().enumerate() {
        if n < 3 {
            let msg = format!("polygon {i} has {n} vertices (at least 3 needed)");
            return Err(match nth_token(vc, i) {
                Some(tok) => ctx.err_token(vc, tok, ErrorKind::BadPolygon, msg),
                None => ctx.err(vc, ErrorKind::BadPolygon, msg),
            });
        }
    }
    if needed != found {
        let err = ctx.err(
            p,
            ErrorKind::CountMismatch,
            format!("<vcount> needs {needed} indices but <p> has {found}"),
        );
        // Only a `<p>` that ends inside the last polygon is repaired: every
        // other polygon is whole, and nothing is invented for the last.
        let last = out.vcounts.last().map_or(0, |&n| u64::from(n) * stride);
        if found > needed || found < needed - last {
            return Err(err);
        }
        ctx.repair(err, "the incomplete last polygon dropped")?;
        out.vcounts.pop();
        out.p.truncate((needed - last) as usize);
    }
    Ok(())
}

fn read_polygons<'a, 'i>(
    ctx: &Ctx<'a, 'i>,
    out: &mut Primitive<'a, 'i>,
    count: Option<usize>,
) -> Result<(), LoadError> {
    let mut polys = 0;
    for el in elements(out.node) {
        let p = match el.tag_name().name() {
            "p" => el,
            "ph" => {
                ctx.warn(el, "holes in <ph> not supported; outer polygon kept")?;
                match child(el, "p") {
                    Some(p) => p,
                    None => continue,
                }
            }
            _ => continue,
        };
        polys += 1;
        let idx = indices(ctx, p, None)?;
        if idx.len() % out.stride != 0 {
            return Err(ctx.err(
                p,
                ErrorKind::CountMismatch,
                format!(
                    "{} indices is not a multiple of the {} inputs",
                    idx.len(),
                    out.stride
                ),
            ));
        }
        let n = idx.len() / out.stride;
        if n < 3 {
            return Err(ctx.err(
                p,
                ErrorKind::BadPolygon,
                format!("polygon has {n} vertices (at least 3 needed)"),
            ));
        }
        out.p_nodes.push((p, out.p.len()));
        out.p.extend_from_slice(&idx);
        out.vcounts.push(n as u32);
    }
    if let Some(c) = count.filter(|&c| c != polys) {
        let err = ctx.err(
            out.node,
            ErrorKind::CountMismatch,
            format!("count=\"{c}\" but {polys} polygons"),
        );
        ctx.repair(err, &format!("the {polys} <p> polygons used"))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::fan;

    #[test]
    fn fan_triangulates_around_the_first_corner() {
        assert_eq!(fan(3).collect::<Vec<_>>(), vec![[0, 1, 2]]);
        assert_eq!(
            fan(5).collect::<Vec<_>>(),
            vec![[0, 1, 2], [0, 2, 3], [0, 3, 4]]
        );
        assert_eq!(fan(2).count(), 0);
        assert_eq!(fan(0).count(), 0);
    }
}
