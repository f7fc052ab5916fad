//! Named indices of refraction (Mitsuba's `int_ior="bk7"`) and conductor
//! presets (`material="Au"`).
//!
//! The dielectric IORs are Mitsuba's documented table (values at about
//! 589 nm). The conductors' complex IORs are RGB values: Mitsuba 0.5's
//! spectral eta/k data (Palik's handbook, via pbrt) integrated against the
//! sRGB colour matching functions, as widely reproduced (e.g. pbrt-v3's
//! named spectra converted to RGB); rounded to 4 decimals; they match Johnson & Christy's gold and
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
    ("Ag", [0.1553, 0.1167, 0.1384], [4.8283, 3.1222, 2.1469]),
    ("Al", [1.6575, 0.8804, 0.5212], [9.2239, 6.2695, 4.8370]),
    ("Au", [0.1431, 0.3750, 1.4425], [3.9832, 2.3857, 1.6032]),
    ("Cr", [4.3697, 2.9167, 1.6547], [5.2064, 4.2314, 3.7549]),
    ("Cu", [0.2004, 0.9240, 1.1022], [3.9129, 2.4528, 2.1422]),
    ("Be", [4.1851, 3.1851, 2.7841], [3.8354, 3.0101, 2.8690]),
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
