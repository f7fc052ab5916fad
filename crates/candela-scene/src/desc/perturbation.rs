//! How a normal or bump map becomes the shading frame, where formats
//! disagree. The map itself (a tangent-space normal, or a height whose
//! gradient tilts the normal) means the same everywhere; what differs is
//! the tangent frame a normal map is read in, what happens when the
//! perturbed normal turns away from the viewer, and whether the bumps
//! shadow one another. A loader states its format's rules here; the
//! renderer follows them without knowing the format.

/// The rules of one material's normal and bump maps. The default is glTF's
/// (and the other loaders' but Mitsuba's).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct PerturbationRules {
    /// The frame a normal map's (x, y, z) is read in.
    pub tangent_frame: TangentFrame,
    /// A perturbed normal that the viewer sees from behind.
    pub away_from_viewer: AwayFromViewer,
    /// Whether reflection is attenuated by the microfacet-style shadowing
    /// of Estevez et al. 2019 ("A Microfacet-Based Shadowing Function to
    /// Solve the Bump Terminator Problem"), which darkens light arriving
    /// at grazing angles more the more the map tilts the normal.
    pub shadow_terminator: bool,
}

impl PerturbationRules {
    /// Mitsuba 3's `normalmap` and `bumpmap` with their defaults
    /// (`flip_invalid_normals` and `use_shadowing_function` true).
    pub const MITSUBA: Self = Self {
        tangent_frame: TangentFrame::SurfaceDpDu,
        away_from_viewer: AwayFromViewer::MirrorTangent,
        shadow_terminator: true,
    };
}

/// The tangent frame (T, B, N) a normal map's texel is read in; N is always
/// the surface's shading normal.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum TangentFrame {
    /// T the mesh's per-vertex tangent (glTF `TANGENT`, else generated
    /// smooth from the UVs, MikkTSpace-like), B = w · N × T, so a map
    /// baked with mirrored UVs keeps its handedness; a surface without
    /// per-vertex tangents uses its dp/du and turns B to the side of dp/dv.
    /// glTF, Blender, OpenGL: +Y (green) toward +v.
    #[default]
    VertexTangents,
    /// T the surface's own dp/du (a triangle's, from its corners and UVs)
    /// made orthogonal to N, and B = N × T, right-handed whatever the UVs
    /// do (Mitsuba's shading frame).
    SurfaceDpDu,
}

/// What a perturbed normal the viewer sees from behind (the viewer on the
/// other side of it than of the unperturbed normal) becomes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum AwayFromViewer {
    /// Rotated toward the viewer until it sees it at a grazing angle (the
    /// smallest change; Keller et al. 2017, Iray §A.3).
    #[default]
    BendTowardViewer,
    /// Mirrored about the unperturbed normal (its tangential part negated),
    /// Schüssler et al. 2017's flip, as Mitsuba's `flip_invalid_normals`.
    MirrorTangent,
}
