//! The Mitsuba loader's tessellated built-in shapes carry Mitsuba's own uv,
//! which textures, the tangent of anisotropic BSDFs (dp/du) and normal and
//! bump maps follow. The expected values were read from Mitsuba 3.9 by ray
//! queries (`si.uv`, `si.dp_du`, `si.dp_dv` of `mi.load_dict({"type":
//! "cube"})` and `"disk"`); Candela's v is Mitsuba's 1 − v (Mitsuba reads
//! images from the top row), so its dp/dv is Mitsuba's negated.
//! benches/mitsuba_conformance/tex-shapes*.xml and tex-cube-back.xml show
//! the same in whole images.

use candela_scene::{load, LoadOptions, MeshDesc};
use glam::{Vec2, Vec3};

/// uv, dp/du and dp/dv at the point `p` of `mesh`, from the triangle that
/// holds it: the uv interpolated, the derivatives from the triangle's
/// corners and uvs (as the renderer computes them).
fn surface_at(mesh: &MeshDesc, p: Vec3) -> (Vec2, Vec3, Vec3) {
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let [a, b, c] = tri.map(|v| mesh.positions[v as usize]);
        let (e1, e2) = (b - a, c - a);
        let n = e1.cross(e2);
        if n.length() < 1e-12 || (p - a).dot(n.normalize()).abs() > 1e-5 {
            continue;
        }
        // Barycentrics of p in the triangle's plane.
        let area = n.length_squared();
        let b1 = (p - a).cross(e2).dot(n) / area;
        let b2 = e1.cross(p - a).dot(n) / area;
        if b1 < -1e-6 || b2 < -1e-6 || b1 + b2 > 1.0 + 1e-6 {
            continue;
        }
        let [t0, t1, t2] = mesh.uv_indices[t].map(|k| mesh.uvs[k as usize]);
        let uv = t0 + b1 * (t1 - t0) + b2 * (t2 - t0);
        let (d1, d2) = (t1 - t0, t2 - t0);
        let det = d1.x * d2.y - d1.y * d2.x;
        let dpdu = (d2.y * e1 - d1.y * e2) / det;
        let dpdv = (d1.x * e2 - d2.x * e1) / det;
        return (uv, dpdu, dpdv);
    }
    panic!("no triangle of {} holds {p}", mesh.name);
}

fn load_shape(kind: &str) -> MeshDesc {
    let dir = candela_testkit::TempDir::new(&format!("mitsuba-shape-uv-{kind}"));
    let path = dir.join("s.xml");
    std::fs::write(
        &path,
        format!(r#"<scene version="3.0.0"><shape type="{kind}"/></scene>"#),
    )
    .unwrap();
    let mut l = load(&path, &LoadOptions::default()).unwrap();
    assert!(l.report.is_empty(), "{}", l.report);
    l.scene.meshes.remove(0)
}

/// Mitsuba's uv in Candela's rows.
fn candela_uv(mitsuba: Vec2) -> Vec2 {
    Vec2::new(mitsuba.x, 1.0 - mitsuba.y)
}

#[test]
fn the_cube_has_mitsubas_uv_and_tangents_on_every_face() {
    // Was each face's (u, v) from its own axes in cyclic order: on +Z, u
    // along +X where Mitsuba's runs along +Y (a bitmap +54% / −23% red /
    // green, an anisotropic conductor +98 … +143% in tex-shapes*.xml).
    let cube = load_shape("cube");
    // (point, Mitsuba's uv, Mitsuba's dp/du, Mitsuba's dp/dv)
    let probes = [
        (
            (0.3, 0.5, 1.0),
            (0.75, 0.65),
            (0.0, 2.0, 0.0),
            (2.0, 0.0, 0.0),
        ),
        (
            (0.3, 0.5, -1.0),
            (0.25, 0.65),
            (0.0, -2.0, 0.0),
            (2.0, 0.0, 0.0),
        ),
        (
            (1.0, 0.3, 0.5),
            (0.65, 0.25),
            (0.0, 2.0, 0.0),
            (0.0, 0.0, -2.0),
        ),
        (
            (-1.0, 0.3, 0.5),
            (0.65, 0.75),
            (0.0, 2.0, 0.0),
            (0.0, 0.0, 2.0),
        ),
        (
            (0.3, 1.0, 0.5),
            (0.35, 0.25),
            (-2.0, 0.0, 0.0),
            (0.0, 0.0, -2.0),
        ),
        (
            (0.3, -1.0, 0.5),
            (0.75, 0.65),
            (0.0, 0.0, 2.0),
            (2.0, 0.0, 0.0),
        ),
    ];
    for (p, uv, dpdu, dpdv) in probes {
        let p = Vec3::from(p);
        let (got_uv, got_dpdu, got_dpdv) = surface_at(&cube, p);
        let want = candela_uv(Vec2::from(uv));
        assert!(
            (got_uv - want).length() < 1e-5,
            "uv {got_uv} vs {want} at {p}"
        );
        assert!(
            (got_dpdu - Vec3::from(dpdu)).length() < 1e-4,
            "dp/du {got_dpdu} vs {dpdu:?} at {p}"
        );
        assert!(
            (got_dpdv + Vec3::from(dpdv)).length() < 1e-4,
            "dp/dv {got_dpdv} vs −{dpdv:?} at {p}"
        );
    }
}

#[test]
fn the_disk_has_mitsubas_polar_uv_and_a_radial_tangent() {
    // Mitsuba's disk has uv (r, φ/2π) and dp/du along the radius; it was
    // ((x + 1)/2, (y + 1)/2) here (a bitmap −30% / +28% red / blue, an
    // anisotropic conductor +217%, a normal map +14% in tex-shapes*.xml).
    let disk = load_shape("disk");
    // (x, y, Mitsuba's uv)
    let probes = [
        (0.5, 0.3, 0.583095, 0.0860105),
        (-0.4, 0.6, 0.72111, 0.343584),
        (0.2, -0.7, 0.728011, 0.794293),
        (-0.55, -0.45, 0.710634, 0.609137),
        (0.9, -0.05, 0.901388, 0.991167),
    ];
    // The tessellation's uv is linear between vertices that carry the
    // exact (r, φ/2π): within a tenth of a texel of a 64-texel image.
    let tolerance = 0.1 / 64.0;
    // v is constant along a spoke, so a triangle's dp/du runs along one of
    // its two spokes: the radius's direction within one segment.
    let segment = std::f32::consts::TAU / 64.0;
    for (x, y, u, v) in probes {
        let p = Vec3::new(x, y, 0.0);
        let (got_uv, dpdu, _) = surface_at(&disk, p);
        let want = candela_uv(Vec2::new(u, v));
        assert!(
            (got_uv - want).abs().max_element() < tolerance,
            "uv {got_uv} vs {want} at {p}"
        );
        let radial = p.normalize();
        assert!(
            dpdu.normalize().dot(radial) > segment.cos(),
            "dp/du {dpdu} vs the radius {radial} at {p}"
        );
    }
}
