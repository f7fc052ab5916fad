//! Named indices of refraction (Mitsuba's `int_ior="bk7"`) and conductor
//! presets (`material="Au"`).
//!
//! The dielectric IORs are Mitsuba's documented table (values at about
//! 589 nm). The conductors' complex IORs are RGB values: Mitsuba 0.5's
//! spectral eta/k data (Palik's handbook, via pbrt) integrated against the
//! sRGB colour matching functions, as widely reproduced (e.g. pbrt-v3's
//! named spectra converted to RGB); they match Johnson & Christy's gold and
//! copper at roughly 650/550/450 nm.

use glam::Vec3;

/// IORs by Mitsuba's names.
const IORS: &[(&str, f32)] = &[
    ("vacuum", 1.0),
    ("helium", 1.000036),
    ("hydrogen", 1.000132),
    ("air", 1.000277),
    ("carbon dioxide", 1.00045),
    ("water", 1.333),
    ("acetone", 1.36),
    ("ethanol", 1.361),
    ("carbon tetrachloride", 1.461),
    ("glycerol", 1.4729),
    ("benzene", 1.501),
    ("silicone oil", 1.52045),
    ("bromine", 1.661),
    ("water ice", 1.31),
    ("fused quartz", 1.458),
    ("pyrex", 1.47),
    ("acrylic glass", 1.49),
    ("polypropylene", 1.49),
    ("bk7", 1.5046),
    ("sodium chloride", 1.544),
    ("amber", 1.55),
    ("pet", 1.575),
    ("diamond", 2.419),
];

/// The IOR Mitsuba calls `name`, if any.
pub(super) fn named_ior(name: &str) -> Option<f32> {
    IORS.iter().find(|(n, _)| *n == name).map(|&(_, v)| v)
}

/// Every IOR name, for messages.
pub(super) fn ior_names() -> String {
    IORS.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", ")
}

/// Conductors: (name, eta RGB, k RGB).
const CONDUCTORS: &[(&str, [f32; 3], [f32; 3])] = &[
    (
        "Ag",
        [0.155_265, 0.116_723, 0.138_381],
        [4.828_343, 3.122_246, 2.146_950],
    ),
    (
        "Al",
        [1.657_460, 0.880_369, 0.521_229],
        [9.223_869, 6.269_523, 4.837_001],
    ),
    (
        "Au",
        [0.143_119, 0.374_957, 1.442_479],
        [3.983_160, 2.385_721, 1.603_215],
    ),
    (
        "Cr",
        [4.369_683, 2.916_702, 1.654_701],
        [5.206_434, 4.231_365, 3.754_947],
    ),
    (
        "Cu",
        [0.200_438, 0.924_033, 1.102_212],
        [3.912_949, 2.452_848, 2.142_188],
    ),
    (
        "Be",
        [4.185_059, 3.185_060, 2.784_091],
        [3.835_440, 3.010_126, 2.869_009],
    ),
    // Mitsuba's "none": a perfect mirror (eta 0, k 1 gives Fresnel 1).
    ("none", [0.0, 0.0, 0.0], [1.0, 1.0, 1.0]),
];

/// (eta, k) of the conductor Mitsuba calls `name`, if this table has it.
pub(super) fn conductor(name: &str) -> Option<(Vec3, Vec3)> {
    CONDUCTORS
        .iter()
        .find(|(n, _, _)| *n == name)
        .map(|&(_, eta, k)| (Vec3::from(eta), Vec3::from(k)))
}

/// Every conductor name, for messages.
pub(super) fn conductor_names() -> String {
    CONDUCTORS
        .iter()
        .map(|(n, _, _)| *n)
        .collect::<Vec<_>>()
        .join(", ")
}
