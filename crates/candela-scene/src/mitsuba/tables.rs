//! Named indices of refraction (Mitsuba's `int_ior="bk7"`) and conductor
//! presets (`material="Au"`).
//!
//! The dielectric IORs are Mitsuba's documented table (values at about
//! 589 nm). The conductors' complex IORs are the measured spectra of
//! `data/metals/` converted to RGB once, as Mitsuba 3's RGB variants do
//! (the table and its provenance: [`crate::metals`]).

use crate::metals::METALS;
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

/// (eta, k) of the conductor Mitsuba calls `name`, if known: the measured
/// metals of [`crate::metals`], or "none", Mitsuba's perfect mirror (eta 0,
/// k 1 gives a Fresnel reflectance of 1 at every angle).
pub(super) fn conductor(name: &str) -> Option<(Vec3, Vec3)> {
    if name == "none" {
        return Some((Vec3::ZERO, Vec3::ONE));
    }
    METALS
        .iter()
        .find(|(n, _, _)| *n == name)
        .map(|&(_, eta, k)| (Vec3::from(eta), Vec3::from(k)))
}

/// Every conductor name, for messages.
pub(super) fn conductor_names() -> String {
    let mut names: Vec<&str> = METALS.iter().map(|(n, _, _)| *n).collect();
    names.push("none");
    names.join(", ")
}
