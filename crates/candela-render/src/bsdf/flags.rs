//! What kind of scattering a BSDF or one of its samples is.

use std::ops::BitOr;

/// A small bit set: {reflection, transmission} × {diffuse, glossy, specular}.
///
/// The integrator reads it to skip light sampling on specular bounces (a
/// delta lobe can never be hit by a light sample), to set MIS weights, and
/// to route AOVs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct BsdfFlags(u8);

impl BsdfFlags {
    /// No scattering at all.
    pub const EMPTY: Self = Self(0);
    /// Scatters into the hemisphere of `wo`.
    pub const REFLECTION: Self = Self(1);
    /// Scatters into the opposite hemisphere.
    pub const TRANSMISSION: Self = Self(2);
    /// A smooth lobe spread over the hemisphere.
    pub const DIFFUSE: Self = Self(4);
    /// A peaked but finite lobe.
    pub const GLOSSY: Self = Self(8);
    /// A Dirac delta lobe: `f` and `pdf` are zero for every given pair of
    /// directions; only `sample` finds the one direction it scatters into.
    pub const SPECULAR: Self = Self(16);

    /// Both sets of flags (usable in constants, unlike `|`).
    pub const fn union(self, other: Self) -> Self {
        Self(self.0 | other.0)
    }

    /// Whether every flag of `other` is set.
    pub fn contains(self, other: Self) -> bool {
        self.0 & other.0 == other.0
    }

    /// Whether any flag of `other` is set.
    pub fn intersects(self, other: Self) -> bool {
        self.0 & other.0 != 0
    }

    /// Whether every lobe is a delta: a specular sample, or a BSDF that
    /// light sampling cannot help (and whose bounce MIS must not weight).
    /// A BSDF with a delta lobe *and* a smooth one (smooth plastic: a
    /// mirror coat over a diffuse base) is not specular: its smooth lobe
    /// needs light samples, because the emitter its diffuse bounce finds is
    /// MIS-weighted against them.
    pub fn is_specular(self) -> bool {
        self.intersects(Self::SPECULAR) && !self.is_non_specular()
    }

    /// Whether some lobe is non-delta, i.e. light sampling can help.
    pub fn is_non_specular(self) -> bool {
        self.intersects(Self::DIFFUSE | Self::GLOSSY)
    }

    /// Whether it reflects.
    pub fn is_reflection(self) -> bool {
        self.intersects(Self::REFLECTION)
    }

    /// Whether it transmits.
    pub fn is_transmission(self) -> bool {
        self.intersects(Self::TRANSMISSION)
    }
}

impl BitOr for BsdfFlags {
    type Output = Self;

    fn bitor(self, rhs: Self) -> Self {
        Self(self.0 | rhs.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flag_queries() {
        let glass = BsdfFlags::REFLECTION | BsdfFlags::TRANSMISSION | BsdfFlags::SPECULAR;
        assert!(glass.is_specular() && glass.is_reflection() && glass.is_transmission());
        assert!(!glass.is_non_specular());
        let diffuse = BsdfFlags::REFLECTION | BsdfFlags::DIFFUSE;
        assert!(!diffuse.is_specular() && diffuse.is_non_specular() && !diffuse.is_transmission());
        assert!(glass.contains(BsdfFlags::REFLECTION | BsdfFlags::SPECULAR));
        assert!(!diffuse.contains(glass));
        assert!(!BsdfFlags::EMPTY.intersects(glass));
    }

    #[test]
    fn a_delta_lobe_beside_a_smooth_one_is_not_specular() {
        // Smooth plastic's flags: the path tracer samples lights at such a
        // vertex only when this is false.
        let plastic = BsdfFlags::REFLECTION | BsdfFlags::DIFFUSE | BsdfFlags::SPECULAR;
        assert!(!plastic.is_specular() && plastic.is_non_specular());
        assert!((BsdfFlags::REFLECTION | BsdfFlags::SPECULAR).is_specular());
    }
}
