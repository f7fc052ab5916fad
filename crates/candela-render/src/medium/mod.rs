//! Homogeneous participating media: what fills the space between surfaces
//! (fog, smoke, murky water, the inside of a jade figure), absorbing and
//! scattering light at the same rates everywhere inside.
//!
//! Media are attached to surfaces, as in pbrt-v4 and Mitsuba 3: a
//! material may carry a [`MediumInterface`] naming the medium on each side
//! of its surfaces, and a ray that crosses or scatters off such a surface
//! goes on in the medium of the side it leaves toward. A surface without an
//! interface changes nothing. The camera sits in [`Media::camera`].
//!
//! Distances are sampled per channel with one-sample MIS over the three
//! channels (pbrt-v4's spectral MIS, here with RGB's three): a channel is
//! chosen uniformly, a distance drawn from its exponential, and the
//! estimate divided by the average of the three channels' densities. That
//! stays unbiased and bounded for coloured media, where sampling one
//! channel's distance for all (Mitsuba's choice) makes the others' weights
//! grow without bound.

mod phase;

pub use phase::HenyeyGreenstein;

use candela_scene::{MediumDesc, SceneDesc};
use glam::{Vec2, Vec3};

/// One homogeneous medium.
#[derive(Clone, Debug, PartialEq)]
pub struct Medium {
    /// Extinction per unit length, per channel.
    pub sigma_t: Vec3,
    /// Scattering per unit length, per channel (`albedo · sigma_t`).
    pub sigma_s: Vec3,
    /// How it scatters.
    pub phase: HenyeyGreenstein,
}

/// What a ray segment of a medium did with the path (see
/// [`Medium::sample_distance`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FreeFlight {
    /// It scattered at `distance` along the ray; the throughput is
    /// multiplied by `weight` (`σ_s · T(distance) / pdf`).
    Scattered {
        /// Distance from the ray's origin, in world units.
        distance: f32,
        /// Throughput factor.
        weight: Vec3,
    },
    /// It went through to the segment's end; the throughput is multiplied
    /// by `weight` (`T(length) / P(passing)`).
    Passed {
        /// Throughput factor.
        weight: Vec3,
    },
}

impl Medium {
    /// The medium a description names.
    pub fn from_desc(d: &MediumDesc) -> Self {
        let sigma_t = d.sigma_t.max(Vec3::ZERO);
        Self {
            sigma_t,
            sigma_s: sigma_t * d.albedo.clamp(Vec3::ZERO, Vec3::ONE),
            phase: HenyeyGreenstein::new(d.phase_g),
        }
    }

    /// The fraction of light per channel that crosses `length` of the
    /// medium (Beer–Lambert); an infinite length leaves the channels with no
    /// extinction untouched.
    pub fn transmittance(&self, length: f32) -> Vec3 {
        let exponent = |s: f32| if s == 0.0 { 0.0 } else { -s * length };
        Vec3::new(
            exponent(self.sigma_t.x).exp(),
            exponent(self.sigma_t.y).exp(),
            exponent(self.sigma_t.z).exp(),
        )
    }

    /// Samples where a path entering a segment of `length` (infinite for a
    /// ray that meets no surface) first interacts with the medium, from
    /// `u.x` (the channel) and `u.y` (the distance). Null collisions are
    /// not needed: the medium is homogeneous, so the transmittance is known.
    pub fn sample_distance(&self, length: f32, u: Vec2) -> FreeFlight {
        let channel = ((u.x * 3.0) as usize).min(2);
        let sigma = self.sigma_t[channel];
        let distance = if sigma > 0.0 {
            -(1.0 - u.y).ln() / sigma
        } else {
            f32::INFINITY
        };
        if distance < length {
            let tr = self.transmittance(distance);
            // The average over the channels of the density of scattering here.
            let pdf = (self.sigma_t * tr).dot(Vec3::ONE) / 3.0;
            let weight = if pdf > 0.0 {
                self.sigma_s * tr / pdf
            } else {
                Vec3::ZERO
            };
            FreeFlight::Scattered { distance, weight }
        } else {
            let tr = self.transmittance(length);
            // The average over the channels of the chance of passing.
            let p = tr.dot(Vec3::ONE) / 3.0;
            let weight = if p > 0.0 { tr / p } else { Vec3::ZERO };
            FreeFlight::Passed { weight }
        }
    }
}

/// The media on the two sides of a surface, by index into [`Media`]'s
/// list (`None`: vacuum).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MediumInterface {
    /// Behind the surface's own (unflipped) geometric normal.
    pub interior: Option<u32>,
    /// On the side the geometric normal points to.
    pub exterior: Option<u32>,
}

impl MediumInterface {
    /// The medium a ray is in after it leaves a surface it met on its
    /// `front_face` (arriving against the surface normal) going on along
    /// `below = dot(wi, ng) < 0`, `ng` the normal flipped toward the
    /// arriving ray (as [`crate::shape::SurfaceHit::ng`]): going on below
    /// means crossing to the other side.
    pub fn after(&self, front_face: bool, crosses: bool) -> Option<u32> {
        // The side the ray arrived from is the exterior when it met the
        // front face; crossing flips it.
        if front_face != crosses {
            self.exterior
        } else {
            self.interior
        }
    }
}

/// Every medium of a scene, where they are, and where the camera is.
#[derive(Clone, Debug, Default)]
pub struct Media {
    media: Vec<Medium>,
    /// Per material: the interface of its surfaces, if they bound media.
    interfaces: Vec<Option<MediumInterface>>,
    /// The medium the camera sits in.
    pub camera: Option<u32>,
}

impl Media {
    /// The media of a description with `materials` materials (the scene
    /// may add a default one beyond the description's).
    pub fn from_desc(desc: &SceneDesc, materials: usize) -> Self {
        let valid = |i: usize| (i < desc.media.len()).then_some(i as u32);
        let mut interfaces = vec![None; materials];
        for &(material, iface) in &desc.medium_interfaces {
            if let Some(slot) = interfaces.get_mut(material) {
                *slot = Some(MediumInterface {
                    interior: iface.interior.and_then(valid),
                    exterior: iface.exterior.and_then(valid),
                });
            }
        }
        Self {
            media: desc.media.iter().map(Medium::from_desc).collect(),
            interfaces,
            camera: desc.camera_medium.and_then(valid),
        }
    }

    /// Whether the scene has any medium (else every path is in vacuum).
    #[inline(always)]
    pub fn any(&self) -> bool {
        !self.media.is_empty()
    }

    /// Medium `i`.
    pub fn get(&self, i: u32) -> &Medium {
        &self.media[i as usize]
    }

    /// The interface of material `material`'s surfaces, if they bound media.
    #[inline]
    pub fn interface(&self, material: u32) -> Option<&MediumInterface> {
        self.interfaces.get(material as usize)?.as_ref()
    }

    /// The medium after a surface of `material` met on its `front_face`,
    /// going on across it (`crosses`) or back; `current` where the surface
    /// bounds no media.
    #[inline]
    pub fn after(
        &self,
        material: u32,
        front_face: bool,
        crosses: bool,
        current: Option<u32>,
    ) -> Option<u32> {
        match self.interface(material) {
            Some(iface) => iface.after(front_face, crosses),
            None => current,
        }
    }
}

#[cfg(test)]
mod tests;
