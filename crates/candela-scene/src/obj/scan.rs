//! The checking pass over an OBJ file: every number, every face index and
//! every statement is checked here, with its place, before `tobj` assembles
//! the meshes. The pass also writes the file out again in the plain form
//! `tobj` reads (comments and CRs gone, unsupported statements dropped), so
//! that nothing `tobj` could mis-read or panic on reaches it.

use super::statements::{error, number, statements, Statement};
use crate::desc::SourceLoc;
use crate::error::{ErrorKind, LoadError};
use crate::report::Collector;
use std::path::Path;

/// What the checking pass found besides the cleaned text.
pub(crate) struct Scan {
    /// The file in the plain form handed to `tobj`.
    pub clean: String,
    /// `mtllib` arguments with their places.
    pub mtllibs: Vec<(String, SourceLoc)>,
    /// `usemtl` names with their places.
    pub usemtls: Vec<(String, SourceLoc)>,
    /// The place of the first face of each mesh `tobj` will return, in order.
    pub mesh_locs: Vec<SourceLoc>,
}

/// Statements of the OBJ specification Candela does not render.
const IGNORED: &[(&str, &str)] = &[
    ("l", "lines are not rendered"),
    ("p", "points are not rendered"),
    ("vp", "free-form geometry is not supported"),
    ("cstype", "free-form geometry is not supported"),
    ("deg", "free-form geometry is not supported"),
    ("bmat", "free-form geometry is not supported"),
    ("step", "free-form geometry is not supported"),
    ("curv", "free-form geometry is not supported"),
    ("curv2", "free-form geometry is not supported"),
    ("surf", "free-form geometry is not supported"),
    ("parm", "free-form geometry is not supported"),
    ("trim", "free-form geometry is not supported"),
    ("hole", "free-form geometry is not supported"),
    ("scrv", "free-form geometry is not supported"),
    ("sp", "free-form geometry is not supported"),
    ("end", "free-form geometry is not supported"),
    ("con", "free-form geometry is not supported"),
    ("mg", "merging groups are not supported"),
    ("bevel", "display attributes are ignored"),
    ("c_interp", "display attributes are ignored"),
    ("d_interp", "display attributes are ignored"),
    ("lod", "display attributes are ignored"),
    ("shadow_obj", "display attributes are ignored"),
    ("trace_obj", "display attributes are ignored"),
    ("ctech", "display attributes are ignored"),
    ("stech", "display attributes are ignored"),
    ("maplib", "texture map libraries are not supported"),
    ("usemap", "texture map libraries are not supported"),
];

/// Checks `text` (the OBJ file `file`) and writes its plain form.
pub(crate) fn scan(text: &str, file: &Path, warnings: &mut Collector) -> Result<Scan, LoadError> {
    let mut out = Scan {
        clean: String::with_capacity(text.len()),
        mtllibs: Vec::new(),
        usemtls: Vec::new(),
        mesh_locs: Vec::new(),
    };
    // Counts of v, vt, vn so far (faces index what precedes them).
    let mut counts = [0usize; 3];
    // How many `v` carry a colour (`v x y z r g b`).
    let mut colored = 0usize;
    let mut faces_pending = false;
    let mut material: Option<&str> = None;
    for st in statements(text) {
        if st.rest.ends_with('\\') {
            return Err(error(
                file,
                st.loc(),
                st.keyword,
                ErrorKind::BadValue,
                "line continuation (\\) is not supported".into(),
            ));
        }
        match st.keyword {
            "v" => {
                if !matches!(st.args.len(), 3 | 4 | 6 | 7) {
                    return Err(arity(file, &st, "3 coordinates (then w or r g b)"));
                }
                for i in 0..st.args.len() {
                    number(file, &st, i)?;
                }
                if st.args.len() == 4 && number(file, &st, 3)? == 0.0 {
                    return Err(error(
                        file,
                        st.arg_loc(3),
                        "v",
                        ErrorKind::BadValue,
                        "weight w = 0".into(),
                    ));
                }
                counts[0] += 1;
                colored += usize::from(st.args.len() >= 6);
                // tobj reads 3 values, or 3 and w, or 3 and a colour.
                push_numbers(&mut out.clean, &st, st.args.len().min(6));
            }
            "vt" => {
                if !matches!(st.args.len(), 2 | 3) {
                    return Err(arity(file, &st, "u and v (then w)"));
                }
                for i in 0..st.args.len() {
                    number(file, &st, i)?;
                }
                counts[1] += 1;
                push_numbers(&mut out.clean, &st, 2);
            }
            "vn" => {
                if st.args.len() != 3 {
                    return Err(arity(file, &st, "3 components"));
                }
                let n = [0, 1, 2].map(|i| number(file, &st, i));
                let [x, y, z] = [n[0].clone()?, n[1].clone()?, n[2].clone()?];
                if x * x + y * y + z * z == 0.0 {
                    return Err(error(
                        file,
                        st.arg_loc(0),
                        "vn",
                        ErrorKind::BadValue,
                        "zero-length normal".into(),
                    ));
                }
                counts[2] += 1;
                push_numbers(&mut out.clean, &st, 3);
            }
            "f" | "fo" => {
                if st.args.len() < 3 {
                    return Err(error(
                        file,
                        st.loc(),
                        st.keyword,
                        ErrorKind::BadPolygon,
                        format!("a face needs 3 or more vertices, not {}", st.args.len()),
                    ));
                }
                out.clean.push('f');
                for &(corner, col) in &st.args {
                    out.clean.push(' ');
                    corner_indices(file, &st, corner, col, &counts, &mut out.clean)?;
                }
                out.clean.push('\n');
                if !faces_pending {
                    out.mesh_locs.push(st.loc());
                    faces_pending = true;
                }
            }
            "o" | "g" => {
                faces_pending = false;
                out.clean.push_str(&format!("{} {}\n", st.keyword, st.rest));
            }
            "s" => {
                if !matches!(st.rest, "off" | "0") {
                    warnings.warn(
                        "s".into(),
                        "smoothing groups ignored: faces without vn are flat-shaded".into(),
                        || st.loc(),
                    )?;
                }
            }
            "mtllib" => {
                if st.rest.is_empty() {
                    return Err(missing_name(file, &st, "a material library file"));
                }
                out.mtllibs.push((st.rest.to_string(), st.loc()));
                out.clean.push_str(&format!("mtllib {}\n", st.rest));
            }
            "usemtl" => {
                if st.rest.is_empty() {
                    return Err(missing_name(file, &st, "a material name"));
                }
                if material != Some(st.rest) {
                    faces_pending = false;
                }
                material = Some(st.rest);
                out.usemtls.push((st.rest.to_string(), st.loc()));
                out.clean.push_str(&format!("usemtl {}\n", st.rest));
            }
            other => {
                let message = IGNORED
                    .iter()
                    .find(|(k, _)| *k == other)
                    .map_or("unknown statement ignored", |(_, m)| m);
                warnings.warn(other.into(), message.into(), || st.loc())?;
            }
        }
    }
    if colored > 0 && colored < counts[0] {
        warnings.warn(
            "v r g b".into(),
            format!(
                "{colored} of {} vertices have a colour; vertex colours ignored",
                counts[0]
            ),
            SourceLoc::default,
        )?;
        out.clean = without_vertex_colors(&out.clean);
    }
    Ok(out)
}

/// The plain text `clean` with every `v` cut to its position: tobj pairs
/// colours with vertices by count, so colours on only some vertices would
/// land on the wrong ones.
fn without_vertex_colors(clean: &str) -> String {
    let mut out = String::with_capacity(clean.len());
    for line in clean.lines() {
        match line.strip_prefix("v ") {
            Some(rest) if rest.split_whitespace().count() >= 6 => {
                out.push('v');
                for x in rest.split_whitespace().take(3) {
                    out.push(' ');
                    out.push_str(x);
                }
            }
            _ => out.push_str(line),
        }
        out.push('\n');
    }
    out
}

/// Checks one face corner `v`, `v/vt`, `v//vn` or `v/vt/vn` against the
/// counts so far and writes it with absolute indices.
fn corner_indices(
    file: &Path,
    st: &Statement,
    corner: &str,
    col: u32,
    counts: &[usize; 3],
    clean: &mut String,
) -> Result<(), LoadError> {
    const WHAT: [&str; 3] = ["vertices", "texture coordinates", "normals"];
    let parts: Vec<&str> = corner.split('/').collect();
    if parts.len() > 3 || parts[0].is_empty() {
        return Err(error(
            file,
            st.at(col),
            st.keyword,
            ErrorKind::BadValue,
            format!("\"{corner}\" is not v, v/vt, v//vn or v/vt/vn"),
        ));
    }
    for (k, part) in parts.iter().enumerate() {
        if k > 0 {
            clean.push('/');
        }
        if part.is_empty() {
            continue;
        }
        let index: i64 = part.parse().map_err(|_| {
            error(
                file,
                st.at(col),
                st.keyword,
                ErrorKind::BadNumber,
                format!("\"{part}\" in \"{corner}\" is not an index"),
            )
        })?;
        let count = counts[k] as i64;
        // 1-based from the start, or negative from the end of what precedes.
        let absolute = if index < 0 { count + index + 1 } else { index };
        if index == 0 || absolute < 1 || absolute > count {
            return Err(error(
                file,
                st.at(col),
                st.keyword,
                ErrorKind::IndexOutOfRange,
                format!(
                    "index {index} in \"{corner}\" is outside the {count} {} defined so far",
                    WHAT[k]
                ),
            ));
        }
        clean.push_str(&absolute.to_string());
    }
    Ok(())
}

fn push_numbers(clean: &mut String, st: &Statement, n: usize) {
    clean.push_str(st.keyword);
    for (token, _) in st.args.iter().take(n) {
        clean.push(' ');
        clean.push_str(token);
    }
    clean.push('\n');
}

fn arity(file: &Path, st: &Statement, expected: &str) -> LoadError {
    error(
        file,
        st.loc(),
        st.keyword,
        ErrorKind::CountMismatch,
        format!("expected {expected}, found {} values", st.args.len()),
    )
}

fn missing_name(file: &Path, st: &Statement, what: &str) -> LoadError {
    error(
        file,
        st.loc(),
        st.keyword,
        ErrorKind::MissingElement,
        format!("expected {what}"),
    )
}
