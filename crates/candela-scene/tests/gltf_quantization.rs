//! `KHR_mesh_quantization`: one triangle written with float attributes and
//! again in every quantised form the extension allows (8- and 16-bit,
//! signed and unsigned, normalised and not), dequantised as gltfpack does
//! (positions by the node's scale and translation, texture coordinates by
//! `KHR_texture_transform`), loads to the same surface within a
//! quantisation step; a component type the extension forbids is refused.

#[allow(dead_code)]
mod gltf;

use candela_scene::{load, ErrorKind, LoadOptions, Loaded, TextureSlot};
use glam::{Vec2, Vec3, Vec4};
use serde_json::{json, Value};

const FLOAT: u32 = 5126;
const BYTE: u32 = 5120;
const UNSIGNED_BYTE: u32 = 5121;
const SHORT: u32 = 5122;
const UNSIGNED_SHORT: u32 = 5123;

const POSITIONS: [[f32; 3]; 3] = [[-0.7, 0.3, 1.2], [2.5, -1.1, 0.4], [0.1, 1.9, -0.8]];
const NORMALS: [[f32; 3]; 3] = [[0.3, 0.5, 0.81], [-0.9, 0.1, 0.2], [0.05, -0.7, -0.6]];
const TANGENTS: [[f32; 4]; 3] = [
    [0.8, -0.2, 0.3, 1.0],
    [0.1, 0.9, -0.4, -1.0],
    [-0.6, 0.3, 0.7, 1.0],
];
const UVS: [[f32; 2]; 3] = [[0.1, 0.2], [0.9, 0.35], [0.45, 1.0]];

/// How an attribute is stored: a glTF component type and the normalised flag.
#[derive(Clone, Copy, Debug)]
struct Form {
    ty: u32,
    normalized: bool,
}

impl Form {
    const FLOAT: Form = Form {
        ty: FLOAT,
        normalized: false,
    };

    fn signed(self) -> bool {
        matches!(self.ty, BYTE | SHORT)
    }

    /// The largest code: 2^b - 1 unsigned, 2^(b-1) - 1 signed (1 for floats).
    fn max_code(self) -> f32 {
        match self.ty {
            BYTE => 127.0,
            UNSIGNED_BYTE => 255.0,
            SHORT => 32767.0,
            UNSIGNED_SHORT => 65535.0,
            _ => 1.0,
        }
    }

    /// What the largest code decodes to: 1 normalised, the code itself not.
    fn max_decoded(self) -> f32 {
        if self.normalized || self.ty == FLOAT {
            1.0
        } else {
            self.max_code()
        }
    }

    fn component_bytes(self) -> usize {
        match self.ty {
            BYTE | UNSIGNED_BYTE => 1,
            SHORT | UNSIGNED_SHORT => 2,
            _ => 4,
        }
    }

    /// The signed type of the same width, normalised: what normals and
    /// tangents take.
    fn for_directions(self) -> Form {
        let ty = match self.ty {
            BYTE | UNSIGNED_BYTE => BYTE,
            SHORT | UNSIGNED_SHORT => SHORT,
            t => t,
        };
        Form {
            ty,
            normalized: ty != FLOAT,
        }
    }

    /// One component (a code, already rounded; or a float) as stored.
    fn bytes(self, c: f32) -> Vec<u8> {
        match self.ty {
            BYTE => (c as i8).to_le_bytes().to_vec(),
            UNSIGNED_BYTE => (c as u8).to_le_bytes().to_vec(),
            SHORT => (c as i16).to_le_bytes().to_vec(),
            UNSIGNED_SHORT => (c as u16).to_le_bytes().to_vec(),
            _ => c.to_le_bytes().to_vec(),
        }
    }

    /// Elements of `codes` with 4-byte-aligned stride, the padding filled
    /// with junk so that a reader ignoring the stride reads it. Returns the
    /// bytes and the stride.
    fn elements(self, codes: &[Vec<f32>]) -> (Vec<u8>, usize) {
        let elem = codes[0].len() * self.component_bytes();
        let stride = elem.next_multiple_of(4);
        let mut out = Vec::new();
        for e in codes {
            out.extend(e.iter().flat_map(|&c| self.bytes(c)));
            out.resize(out.len() + stride - elem, 0x5A);
        }
        (out, stride)
    }

    /// Codes of `values` in [-1, 1] (signed) or [0, 1] (unsigned): v scaled
    /// to the largest code and rounded; floats as they are.
    fn codes(self, values: &[f32]) -> Vec<f32> {
        match self.ty {
            FLOAT => values.to_vec(),
            _ => values
                .iter()
                .map(|v| (v * self.max_code()).round())
                .collect(),
        }
    }

    /// The accessor JSON (without its `bufferView`) of `count` elements.
    fn accessor(self, ty: &str, count: usize) -> Value {
        let mut acc = json!({"componentType": self.ty, "count": count, "type": ty});
        if self.normalized {
            acc["normalized"] = json!(true);
        }
        acc
    }
}

/// Every quantised form of POSITION and TEXCOORD_0 the extension allows.
fn quantised_forms() -> Vec<Form> {
    let mut forms = Vec::new();
    for ty in [BYTE, UNSIGNED_BYTE, SHORT, UNSIGNED_SHORT] {
        for normalized in [true, false] {
            forms.push(Form { ty, normalized });
        }
    }
    forms
}

/// Positions as codes of `form` and the node (translation, uniform scale)
/// that dequantises them, as gltfpack writes: the bounding box's corner
/// (unsigned) or centre (signed) and its largest extent over the codes'
/// range. Floats keep the identity.
fn quantised_positions(form: Form) -> (Vec<Vec<f32>>, Vec3, f32) {
    let ps: Vec<Vec3> = POSITIONS.iter().map(|p| Vec3::from_array(*p)).collect();
    if form.ty == FLOAT {
        return (
            POSITIONS.iter().map(|p| p.to_vec()).collect(),
            Vec3::ZERO,
            1.0,
        );
    }
    let lo = ps.iter().copied().reduce(Vec3::min).unwrap();
    let hi = ps.iter().copied().reduce(Vec3::max).unwrap();
    let (origin, extent) = match form.signed() {
        true => ((lo + hi) / 2.0, (hi - lo).max_element() / 2.0),
        false => (lo, (hi - lo).max_element()),
    };
    let codes = ps
        .iter()
        .map(|p| form.codes(&((*p - origin) / extent).to_array()))
        .collect();
    (codes, origin, extent / form.max_decoded())
}

/// The triangle with every attribute in `form` (normals and tangents in
/// its signed normalised counterpart), drawn by one node, textured through
/// a `KHR_texture_transform` that dequantises the UVs.
fn document(form: Form, required: bool) -> Vec<u8> {
    let (positions, origin, scale) = quantised_positions(form);
    let dir = form.for_directions();
    let normals: Vec<Vec<f32>> = NORMALS
        .iter()
        .map(|n| dir.codes(&Vec3::from_array(*n).normalize().to_array()))
        .collect();
    let tangents: Vec<Vec<f32>> = TANGENTS
        .iter()
        .map(|t| {
            let xyz = Vec3::from_array([t[0], t[1], t[2]]).normalize();
            dir.codes(&xyz.extend(t[3]).to_array())
        })
        .collect();
    let uvs: Vec<Vec<f32>> = UVS.iter().map(|uv| form.codes(uv)).collect();
    let png =
        gltf::data_uri(b"\x89PNG not really").replace("application/octet-stream", "image/png");
    let uv_scale = 1.0 / form.max_decoded();
    gltf::gltf_text(|d| {
        let mut buf = gltf::buffer();
        let mut attribute = |d: &mut Value, form: Form, ty: &str, codes: &[Vec<f32>]| {
            let (bytes, stride) = form.elements(codes);
            let acc = form.accessor(ty, codes.len());
            gltf::push_accessor(d, &mut buf, &bytes, Some(stride), acc)
        };
        let pos = attribute(d, form, "VEC3", &positions);
        // POSITION must carry its bounds (in codes).
        let axis = |f: fn(f32, f32) -> f32| -> Vec<f32> {
            let bound = |k: usize| positions.iter().map(|c| c[k]).reduce(f).unwrap();
            (0..3).map(bound).collect()
        };
        d["accessors"][pos]["min"] = json!(axis(f32::min));
        d["accessors"][pos]["max"] = json!(axis(f32::max));
        let normal = attribute(d, dir, "VEC3", &normals);
        let tangent = attribute(d, dir, "VEC4", &tangents);
        let uv = attribute(d, form, "VEC2", &uvs);
        gltf::set_buffer(d, &buf);
        d["meshes"][0]["primitives"][0]["attributes"] =
            json!({"POSITION": pos, "NORMAL": normal, "TANGENT": tangent, "TEXCOORD_0": uv});
        d["scenes"][0]["nodes"] = json!([0]);
        d["nodes"][0] = json!({
            "mesh": 0,
            "translation": origin.to_array(),
            "scale": [scale, scale, scale]
        });
        d["images"] = json!([{"uri": png}]);
        d["textures"] = json!([{"source": 0}]);
        let transform = json!({"scale": [uv_scale, uv_scale]});
        d["materials"][0]["pbrMetallicRoughness"] = json!({
            "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": transform}}
        });
        let mut used = vec!["KHR_lights_punctual", "KHR_texture_transform"];
        if form.ty != FLOAT {
            used.push("KHR_mesh_quantization");
            if required {
                d["extensionsRequired"] = json!(["KHR_mesh_quantization"]);
            }
        }
        d["extensionsUsed"] = json!(used);
    })
}

fn load_ok(name: &str, bytes: &[u8]) -> Loaded {
    let path = gltf::write(name, bytes);
    load(&path, &LoadOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// What the renderer sees of the triangle: world positions, normals and
/// tangents in the mesh's space (the node's scale is uniform), and the
/// uvs at which the base colour texture is read.
struct Surface {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    tangents: Vec<Vec4>,
    uvs: Vec<Vec2>,
}

fn surface(l: &Loaded) -> Surface {
    assert_eq!(l.scene.meshes.len(), 1);
    assert_eq!(l.scene.instances.len(), 1);
    let mesh = &l.scene.meshes[0];
    let world = l.scene.instances[0].world_from_object;
    let texture = l.scene.materials[mesh.material]
        .textures
        .get(TextureSlot::Color)
        .expect("base colour texture");
    Surface {
        positions: mesh
            .positions
            .iter()
            .map(|&p| world.transform_point3(p))
            .collect(),
        normals: mesh.normals.clone(),
        tangents: mesh.tangents.clone(),
        uvs: mesh.uvs.iter().map(|&uv| texture.uv.apply(uv)).collect(),
    }
}

/// The largest difference of any component.
fn worst<T: Copy>(a: &[T], b: &[T], diff: impl Fn(T, T) -> f32) -> f32 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(&x, &y)| diff(x, y))
        .fold(0.0, f32::max)
}

#[test]
fn every_quantised_form_loads_to_the_float_surface_within_a_step() {
    let float = load_ok("float.gltf", &document(Form::FLOAT, false));
    assert!(float.report.warnings.is_empty(), "{}", float.report);
    let want = surface(&float);
    for form in quantised_forms() {
        let l = load_ok("quantised.gltf", &document(form, true));
        assert!(l.report.warnings.is_empty(), "{form:?}: {}", l.report);
        let got = surface(&l);
        // Positions: half a code of the dequantised range, per axis.
        let extent = quantised_positions(form).2 * form.max_decoded();
        let step = extent / form.max_code();
        let err = worst(&got.positions, &want.positions, |a, b| {
            (a - b).abs().max_element()
        });
        assert!(err <= 0.5 * step + 1e-5, "{form:?}: positions off by {err}");
        // Directions: unit length, within a code of the float ones.
        let dir_step = 1.0 / form.for_directions().max_code();
        for n in &got.normals {
            assert!((n.length() - 1.0).abs() < 1e-5, "{form:?}: normal {n}");
        }
        for t in &got.tangents {
            let len = t.truncate().length();
            assert!((len - 1.0).abs() < 1e-5, "{form:?}: tangent {t}");
        }
        let err = worst(&got.normals, &want.normals, |a, b| {
            (a - b).abs().max_element()
        });
        assert!(err <= 2.0 * dir_step, "{form:?}: normals off by {err}");
        let err = worst(&got.tangents, &want.tangents, |a, b| {
            (a - b).abs().max_element()
        });
        assert!(err <= 2.0 * dir_step, "{form:?}: tangents off by {err}");
        // Texture coordinates: half a code.
        let err = worst(&got.uvs, &want.uvs, |a, b| (a - b).abs().max_element());
        assert!(
            err <= 0.5 / form.max_code() + 1e-6,
            "{form:?}: uvs off by {err}"
        );
    }
}

#[test]
fn using_the_extension_without_requiring_it_loads_the_same() {
    let form = Form {
        ty: SHORT,
        normalized: true,
    };
    let required = surface(&load_ok("required.gltf", &document(form, true)));
    let used = load_ok("used.gltf", &document(form, false));
    assert!(used.report.warnings.is_empty(), "{}", used.report);
    let used = surface(&used);
    assert_eq!(required.positions, used.positions);
    assert_eq!(required.normals, used.normals);
    assert_eq!(required.tangents, used.tangents);
    assert_eq!(required.uvs, used.uvs);
}

#[test]
fn forms_the_extension_forbids_are_refused_naming_the_attribute() {
    let normalised = |ty| Form {
        ty,
        normalized: true,
    };
    let unnormalised = |ty| Form {
        ty,
        normalized: false,
    };
    // (attribute, accessor index in `document`, form, its name in the message)
    let cases = [
        (
            "NORMAL",
            3,
            normalised(UNSIGNED_BYTE),
            "normalized UNSIGNED_BYTE",
        ),
        ("NORMAL", 3, unnormalised(SHORT), "SHORT"),
        (
            "TANGENT",
            4,
            normalised(UNSIGNED_SHORT),
            "normalized UNSIGNED_SHORT",
        ),
        ("TANGENT", 4, unnormalised(BYTE), "BYTE"),
        ("POSITION", 2, unnormalised(5125), "UNSIGNED_INT"),
        ("TEXCOORD_0", 5, unnormalised(5125), "UNSIGNED_INT"),
    ];
    let base = document(Form::FLOAT, false);
    for (attribute, index, form, named) in cases {
        let mut d: Value = serde_json::from_slice(&base).unwrap();
        d["accessors"][index]["componentType"] = json!(form.ty);
        if form.normalized {
            d["accessors"][index]["normalized"] = json!(true);
        }
        let path = gltf::write("forbidden.gltf", &serde_json::to_vec(&d).unwrap());
        let e = match load(&path, &LoadOptions::default()) {
            Ok(_) => panic!("{attribute} as {named} loaded"),
            Err(e) => e,
        };
        let line = e.to_string();
        assert_eq!(e.kind, ErrorKind::BadValue, "{line}");
        assert!(!line.contains('\n'), "{line}");
        assert!(line.starts_with(&path.display().to_string()), "{line}");
        assert_eq!(e.element, format!("/accessors/{index}/componentType"));
        assert!(
            line.contains(&format!("{attribute} cannot be {named} ")),
            "{line}"
        );
    }
}
