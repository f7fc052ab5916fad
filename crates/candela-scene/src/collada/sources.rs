//! `<source>` elements: a float array read through its accessor.

use super::numbers::{attr_usize, count_mismatch, floats};
use super::xml::{child, require, Ctx, XNode};
use crate::error::{ErrorKind, LoadError};
use glam::{Vec2, Vec3};
use roxmltree::NodeId;
use std::collections::hash_map::{Entry, HashMap};

/// The numbers of one source and how its accessor walks them.
pub(crate) struct Source {
    data: Vec<f32>,
    /// Number of elements (vectors) the accessor exposes.
    pub count: usize,
    stride: usize,
    offset: usize,
}

impl Source {
    /// Element `i` as a 3-vector (the source was checked to have 3 components).
    pub fn vec3(&self, i: u32) -> Vec3 {
        let s = self.offset + i as usize * self.stride;
        Vec3::new(self.data[s], self.data[s + 1], self.data[s + 2])
    }

    /// Element `i` as a 2-vector (the source was checked to have 2 components).
    pub fn vec2(&self, i: u32) -> Vec2 {
        let s = self.offset + i as usize * self.stride;
        Vec2::new(self.data[s], self.data[s + 1])
    }
}

/// Sources of one mesh, each parsed once however many primitives use it.
#[derive(Default)]
pub(crate) struct SourceCache {
    parsed: HashMap<(NodeId, usize), Source>,
}

impl SourceCache {
    /// The parsed `<source>`, checked to provide `components` numbers per element.
    pub fn get(
        &mut self,
        ctx: &Ctx,
        source: XNode,
        components: usize,
    ) -> Result<&Source, LoadError> {
        let key = (source.id(), components);
        match self.parsed.entry(key) {
            Entry::Occupied(e) => Ok(e.into_mut()),
            Entry::Vacant(e) => Ok(e.insert(read_source(ctx, source, components)?)),
        }
    }
}

/// Reads a `<source>` through `technique_common/accessor`.
fn read_source(ctx: &Ctx, source: XNode, components: usize) -> Result<Source, LoadError> {
    let tc = require(ctx, source, "technique_common")?;
    let acc = require(ctx, tc, "accessor")?;
    let count = attr_usize(ctx, acc, "count")?
        .ok_or_else(|| ctx.err(acc, ErrorKind::MissingElement, "missing attribute count"))?;
    let stride = attr_usize(ctx, acc, "stride")?.unwrap_or(1);
    let offset = attr_usize(ctx, acc, "offset")?.unwrap_or(0);
    let array = match acc.attribute("source") {
        Some(_) => ctx.resolve(acc, "source", &["float_array"])?,
        None => child(source, "float_array"),
    }
    .ok_or_else(|| ctx.err(source, ErrorKind::MissingElement, "missing <float_array>"))?;
    let declared = attr_usize(ctx, array, "count")?;
    let data = floats(ctx, array, None)?;
    let needed = match count {
        0 => 0,
        n => (n - 1)
            .checked_mul(stride)
            .and_then(|x| x.checked_add(offset + components))
            .unwrap_or(usize::MAX),
    };
    if let Some(c) = declared.filter(|&c| c != data.len()) {
        // The accessor says how many numbers are used: when the array holds
        // them, its own count is only a wrong summary.
        let err = count_mismatch(ctx, array, c, data.len());
        if needed > data.len() {
            return Err(err);
        }
        ctx.repair(
            err,
            &format!(
                "the {} numbers present used (the accessor needs {needed})",
                data.len()
            ),
        )?;
    }
    if stride < components {
        return Err(ctx.err(
            acc,
            ErrorKind::BadValue,
            format!("stride {stride} is less than the {components} components needed"),
        ));
    }
    if needed > data.len() {
        return Err(ctx.err(
            acc,
            ErrorKind::CountMismatch,
            format!(
                "count=\"{count}\" stride=\"{stride}\" needs {needed} numbers but the array has {}",
                data.len()
            ),
        ));
    }
    Ok(Source {
        data,
        count,
        stride,
        offset,
    })
}
