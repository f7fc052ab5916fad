//! From the elements of a PLY body to a [`MeshDesc`]: vertices, faces
//! (fan-triangulated), and everything else read past and reported.

use super::body::{Body, ReadError};
use super::header::{Element, Header, Property, Scalar};
use super::located;
use crate::desc::MeshDesc;
use crate::error::{ErrorKind, LoadError};
use crate::report::Collector;
use candela_image::srgb_decode;
use glam::{Vec2, Vec3};
use std::path::Path;

/// Property names of the vertex attributes read, in the order
/// x y z nx ny nz u v red green blue; each entry lists the accepted
/// spellings.
const VERTEX_FIELDS: [&[&str]; 11] = [
    &["x"],
    &["y"],
    &["z"],
    &["nx"],
    &["ny"],
    &["nz"],
    &["u", "s", "texture_u"],
    &["v", "t", "texture_v"],
    &["red", "r"],
    &["green", "g"],
    &["blue", "b"],
];

/// Where the vertex colours are in [`VERTEX_FIELDS`].
const COLOR_FIELDS: std::ops::Range<usize> = 8..11;

/// Reads every element of the body described by `header`.
pub(crate) fn read(
    bytes: &[u8],
    header: &Header,
    file: &Path,
    warnings: &mut Collector,
) -> Result<MeshDesc, LoadError> {
    let mut body = Body::new(bytes, header.body_start, header.encoding, header.body_line);
    let mut mesh = MeshDesc::default();
    let mut has_normals = false;
    let mut has_uvs = false;
    let mut vertices_seen = false;
    // Each face's vertex list, reused (it grows only with data actually read).
    let mut corners: Vec<u32> = Vec::new();
    for element in &header.elements {
        let min = element.min_bytes(header.encoding);
        if element.count.saturating_mul(min) > body.remaining() {
            return Err(located(
                file,
                element.loc,
                &format!("element {}", element.name),
                ErrorKind::TooLarge,
                format!(
                    "{} {}s need at least {} bytes but only {} remain in the file",
                    element.count,
                    element.name,
                    element.count.saturating_mul(min),
                    body.remaining()
                ),
            ));
        }
        let fail = |e: ReadError, i: u64| {
            let message = format!("{} {i}: {}", element.name, e.message);
            located(
                file,
                e.loc.unwrap_or(element.loc),
                &format!("element {}", element.name),
                e.kind,
                message,
            )
        };
        match element.name.as_str() {
            "vertex" if !vertices_seen => {
                vertices_seen = true;
                let fields = field_slots(element);
                if fields[..3].iter().any(Option::is_none) {
                    return Err(located(
                        file,
                        element.loc,
                        "element vertex",
                        ErrorKind::MissingElement,
                        "vertices need x, y and z properties".into(),
                    ));
                }
                has_normals = fields[3..6].iter().all(Option::is_some);
                has_uvs = fields[6..8].iter().all(Option::is_some);
                let colors = fields[COLOR_FIELDS]
                    .iter()
                    .all(Option::is_some)
                    .then(|| ColorEncoding::of(element));
                report_skipped(element, |p| slot_of(p).is_none(), warnings)?;
                // Bounded above by the file's size (checked above).
                mesh.positions.reserve(element.count as usize);
                for i in 0..element.count {
                    let mut values = [0f64; 11];
                    for property in &element.properties {
                        match (property, slot_of(property.name())) {
                            (Property::Scalar { ty, .. }, Some(k)) => {
                                values[k] = body.read(*ty).map_err(|e| fail(e, i))?
                            }
                            _ => skip(&mut body, property).map_err(|e| fail(e, i))?,
                        }
                    }
                    if let Some(k) = [0, 1, 2, 6, 7]
                        .into_iter()
                        .chain(if has_normals { 3..6 } else { 0..0 })
                        .chain(if colors.is_some() { COLOR_FIELDS } else { 0..0 })
                        .find(|&k| !(values[k] as f32).is_finite())
                    {
                        return Err(fail(
                            body.error(
                                ErrorKind::NonFinite,
                                format!("{} is {:?}", VERTEX_FIELDS[k][0], values[k]),
                            ),
                            i,
                        ));
                    }
                    let v = values.map(|x| x as f32);
                    mesh.positions.push(Vec3::new(v[0], v[1], v[2]));
                    if has_normals {
                        mesh.normals.push(Vec3::new(v[3], v[4], v[5]));
                    }
                    if has_uvs {
                        mesh.uvs.push(Vec2::new(v[6], v[7]));
                    }
                    if let Some(encoding) = colors {
                        let rgb = [8, 9, 10].map(|k| encoding.linear(values[k]));
                        mesh.colors.push(Vec3::from_array(rgb));
                    }
                }
            }
            "face" => {
                let list = element.properties.iter().position(|p| {
                    matches!(p, Property::List { name, .. } if name == "vertex_indices" || name == "vertex_index")
                });
                let Some(list) = list else {
                    return Err(located(
                        file,
                        element.loc,
                        "element face",
                        ErrorKind::MissingElement,
                        "faces need a vertex_indices list property".into(),
                    ));
                };
                report_skipped(element, |p| p != element.properties[list].name(), warnings)?;
                for i in 0..element.count {
                    for (k, property) in element.properties.iter().enumerate() {
                        if k != list {
                            skip(&mut body, property).map_err(|e| fail(e, i))?;
                            continue;
                        }
                        let Property::List { count, item, .. } = property else {
                            continue;
                        };
                        let n = list_length(&mut body, *count).map_err(|e| fail(e, i))?;
                        body.ensure(n, *item).map_err(|e| fail(e, i))?;
                        corners.clear();
                        for _ in 0..n {
                            let index = body.read(*item).map_err(|e| fail(e, i))?;
                            if index < 0.0 || index > f64::from(u32::MAX) || index.fract() != 0.0 {
                                return Err(fail(
                                    body.error(
                                        ErrorKind::IndexOutOfRange,
                                        format!("vertex index {index} is not a vertex"),
                                    ),
                                    i,
                                ));
                            }
                            corners.push(index as u32);
                        }
                        if corners.len() < 3 {
                            return Err(fail(
                                body.error(
                                    ErrorKind::BadPolygon,
                                    format!("a face needs 3 or more vertices, not {n}"),
                                ),
                                i,
                            ));
                        }
                        for j in 1..corners.len() - 1 {
                            mesh.triangles
                                .push([corners[0], corners[j], corners[j + 1]]);
                        }
                    }
                }
            }
            _ => {
                warnings.warn(
                    format!("element {}", element.name),
                    "element skipped".into(),
                    || element.loc,
                )?;
                for i in 0..element.count {
                    for property in &element.properties {
                        skip(&mut body, property).map_err(|e| fail(e, i))?;
                    }
                }
            }
        }
    }
    finish(&mut mesh, header, file, has_normals, has_uvs, warnings)?;
    Ok(mesh)
}

/// Checks indices against the vertex count, and shares the position
/// indices with normals and UVs (PLY attributes are per vertex).
fn finish(
    mesh: &mut MeshDesc,
    header: &Header,
    file: &Path,
    has_normals: bool,
    has_uvs: bool,
    warnings: &mut Collector,
) -> Result<(), LoadError> {
    let face_loc = |name: &str| {
        header
            .elements
            .iter()
            .find(|e| e.name == name)
            .map_or_else(Default::default, |e| e.loc)
    };
    if !header.elements.iter().any(|e| e.name == "vertex") {
        return Err(located(
            file,
            face_loc("face"),
            "element vertex",
            ErrorKind::MissingElement,
            "the file has no vertex element".into(),
        ));
    }
    let n = mesh.positions.len();
    if let Some((t, &bad)) = mesh
        .triangles
        .iter()
        .enumerate()
        .find_map(|(t, tri)| tri.iter().find(|&&i| i as usize >= n).map(|i| (t, i)))
    {
        return Err(located(
            file,
            face_loc("face"),
            "element face",
            ErrorKind::IndexOutOfRange,
            format!("a face (triangle {t}) uses vertex {bad} of {n}"),
        ));
    }
    mesh.loc = face_loc("vertex");
    if has_normals {
        if mesh.normals.iter().any(|v| v.length_squared() == 0.0) {
            warnings.warn(
                "property nx".into(),
                "zero-length vertex normals: normals dropped, flat shading".into(),
                || face_loc("vertex"),
            )?;
            mesh.normals.clear();
        } else {
            for v in &mut mesh.normals {
                *v = v.normalize();
            }
            mesh.normal_indices = mesh.triangles.clone();
        }
    }
    if has_uvs {
        mesh.uv_indices = mesh.triangles.clone();
    }
    Ok(())
}

/// Which of [`VERTEX_FIELDS`] a property name fills.
fn slot_of(name: &str) -> Option<usize> {
    VERTEX_FIELDS.iter().position(|names| names.contains(&name))
}

/// For each of [`VERTEX_FIELDS`], whether a scalar property provides it.
fn field_slots(element: &Element) -> [Option<()>; 11] {
    let mut found = [None; 11];
    for p in &element.properties {
        if let (Property::Scalar { .. }, Some(k)) = (p, slot_of(p.name())) {
            found[k] = Some(());
        }
    }
    found
}

/// How a PLY file stores its vertex colours, by the type of `red`: floats
/// are linear and taken as given (Mitsuba reads them so); integers are
/// display colours (8 bits in the files MeshLab and Blender write), scaled
/// by the type's largest value to [0, 1] and decoded from sRGB, as an
/// 8-bit colour image is. (Mitsuba 3 keeps integer colours unscaled, 0 to
/// 255, and warns that it expects [0, 1].)
#[derive(Clone, Copy, Debug, PartialEq)]
enum ColorEncoding {
    /// Linear values as stored.
    Linear,
    /// sRGB-encoded integers up to this value.
    SrgbInteger(f64),
}

impl ColorEncoding {
    fn of(element: &Element) -> Self {
        let ty = element.properties.iter().find_map(|p| match p {
            Property::Scalar { ty, .. } if slot_of(p.name()) == Some(COLOR_FIELDS.start) => {
                Some(*ty)
            }
            _ => None,
        });
        match ty.and_then(Scalar::integer_max) {
            Some(max) => ColorEncoding::SrgbInteger(max),
            None => ColorEncoding::Linear,
        }
    }

    /// The linear value of a stored one.
    fn linear(self, stored: f64) -> f32 {
        match self {
            ColorEncoding::Linear => stored as f32,
            ColorEncoding::SrgbInteger(max) => srgb_decode((stored / max) as f32),
        }
    }
}

fn report_skipped(
    element: &Element,
    skipped: impl Fn(&str) -> bool,
    warnings: &mut Collector,
) -> Result<(), LoadError> {
    for p in element.properties.iter().filter(|p| skipped(p.name())) {
        warnings.warn(
            format!("property {}", p.name()),
            format!("{} property skipped", element.name),
            || element.loc,
        )?;
    }
    Ok(())
}

/// A list's length, checked to be a non-negative integer.
fn list_length(body: &mut Body, count: super::header::Scalar) -> Result<u64, ReadError> {
    let n = body.read(count)?;
    if n < 0.0 {
        return Err(body.error(ErrorKind::BadValue, format!("list length {n}")));
    }
    Ok(n as u64)
}

/// Reads past one property.
fn skip(body: &mut Body, property: &Property) -> Result<(), ReadError> {
    match property {
        Property::Scalar { ty, .. } => body.read(*ty).map(|_| ()),
        Property::List { count, item, .. } => {
            let n = list_length(body, *count)?;
            body.ensure(n, *item)?;
            for _ in 0..n {
                body.read(*item)?;
            }
            Ok(())
        }
    }
}
