//! Fresnel reflectance of dielectrics and conductors, and Snell refraction.

use glam::Vec3;

/// Unpolarised Fresnel reflectance of a smooth dielectric interface.
///
/// `cos_i` is the cosine between the incident direction and the normal,
/// negative when the direction is on the inside; `eta` is the IOR of the
/// inside over the outside. Returns 1 under total internal reflection.
pub(crate) fn fresnel_dielectric(cos_i: f32, eta: f32) -> f32 {
    let (cos_i, eta) = if cos_i < 0.0 {
        (-cos_i, 1.0 / eta)
    } else {
        (cos_i, eta)
    };
    let cos_i = cos_i.min(1.0);
    let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let parallel = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let perpendicular = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    0.5 * (parallel * parallel + perpendicular * perpendicular)
}

/// The direction refracted from `w` (pointing away from the surface, on the
/// side of `n`) through the interface, with `eta` the IOR of the far side
/// over the near side; `None` under total internal reflection.
pub(crate) fn refract(w: Vec3, n: Vec3, eta: f32) -> Option<Vec3> {
    let cos_i = w.dot(n);
    let sin2_t = (1.0 - cos_i * cos_i).max(0.0) / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((-w / eta + (cos_i / eta - cos_t) * n).normalize())
}

/// A minimal complex number for the conductor Fresnel equations.
#[derive(Clone, Copy, Debug)]
struct Complex {
    re: f32,
    im: f32,
}

impl Complex {
    fn new(re: f32, im: f32) -> Self {
        Self { re, im }
    }
    fn add(self, o: Self) -> Self {
        Self::new(self.re + o.re, self.im + o.im)
    }
    fn sub(self, o: Self) -> Self {
        Self::new(self.re - o.re, self.im - o.im)
    }
    fn mul(self, o: Self) -> Self {
        Self::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
    fn scale(self, s: f32) -> Self {
        Self::new(self.re * s, self.im * s)
    }
    fn norm_sqr(self) -> f32 {
        self.re * self.re + self.im * self.im
    }
    fn div(self, o: Self) -> Self {
        let d = o.norm_sqr();
        Self::new(
            (self.re * o.re + self.im * o.im) / d,
            (self.im * o.re - self.re * o.im) / d,
        )
    }
    /// The principal square root (non-negative real part).
    fn sqrt(self) -> Self {
        let r = self.norm_sqr().sqrt();
        let re = (0.5 * (r + self.re)).max(0.0).sqrt();
        let im = (0.5 * (r - self.re)).max(0.0).sqrt().copysign(self.im);
        Self::new(re, im)
    }
}

/// Exact Fresnel reflectance of a conductor with complex IOR `eta + i·k`
/// for light at `cos_i` (clamped to [0, 1]), one channel: the dielectric
/// formula evaluated in complex arithmetic.
fn fresnel_complex(cos_i: f32, eta: f32, k: f32) -> f32 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let n = Complex::new(eta, k);
    let sin2_i = 1.0 - cos_i * cos_i;
    let sin2_t = Complex::new(sin2_i, 0.0).div(n.mul(n));
    let cos_t = Complex::new(1.0, 0.0).sub(sin2_t).sqrt();
    let c = Complex::new(cos_i, 0.0);
    let parallel = n.scale(cos_i).sub(cos_t).div(n.scale(cos_i).add(cos_t));
    let perpendicular = c.sub(n.mul(cos_t)).div(c.add(n.mul(cos_t)));
    0.5 * (parallel.norm_sqr() + perpendicular.norm_sqr())
}

/// Per-channel conductor reflectance (see [`fresnel_complex`]).
pub(crate) fn fresnel_conductor(cos_i: f32, eta: Vec3, k: Vec3) -> Vec3 {
    Vec3::new(
        fresnel_complex(cos_i, eta.x, k.x),
        fresnel_complex(cos_i, eta.y, k.y),
        fresnel_complex(cos_i, eta.z, k.z),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dielectric_fresnel_matches_known_values() {
        let eta = 1.5f32;
        let normal = ((eta - 1.0) / (eta + 1.0)).powi(2);
        assert!((fresnel_dielectric(1.0, eta) - normal).abs() < 1e-6);
        assert!((fresnel_dielectric(-1.0, eta) - normal).abs() < 1e-6);
        // Brewster's angle: the parallel polarisation vanishes, so F is half
        // the perpendicular reflectance, sin²(θi − θt) / sin²(θi + θt).
        let theta_b = eta.atan();
        let theta_t = (theta_b.sin() / eta).asin();
        let rs = ((theta_b - theta_t).sin() / (theta_b + theta_t).sin()).powi(2);
        assert!((fresnel_dielectric(theta_b.cos(), eta) - 0.5 * rs).abs() < 1e-5);
        // Total internal reflection beyond the critical angle from inside.
        let critical = (1.0 / eta).asin();
        assert_eq!(fresnel_dielectric(-(critical + 0.01).cos(), eta), 1.0);
        assert!(fresnel_dielectric(-(critical - 0.01).cos(), eta) < 1.0);
        assert_eq!(fresnel_dielectric(0.0, eta), 1.0);
        assert_eq!(fresnel_dielectric(0.7, 1.0), 0.0);
    }

    #[test]
    fn dielectric_fresnel_is_symmetric_across_the_interface() {
        // Reflectance is the same for the two directions of one light path.
        let eta = 1.33f32;
        for cos_i in [0.1f32, 0.4, 0.8, 1.0] {
            let sin_t = (1.0 - cos_i * cos_i).sqrt() / eta;
            let cos_t = (1.0 - sin_t * sin_t).sqrt();
            assert!(
                (fresnel_dielectric(cos_i, eta) - fresnel_dielectric(-cos_t, eta)).abs() < 1e-5
            );
        }
    }

    #[test]
    fn refraction_obeys_snell() {
        let w = Vec3::new(0.6, 0.0, 0.8);
        let t = refract(w, Vec3::Z, 1.5).unwrap_or(Vec3::ZERO);
        assert!((t.length() - 1.0).abs() < 1e-6 && t.z < 0.0 && t.x < 0.0);
        assert!((w.x - 1.5 * -t.x).abs() < 1e-6, "sin θi = η sin θt");
        assert!(refract(Vec3::new(0.9, 0.0, 0.436), Vec3::Z, 1.0 / 1.5).is_none());
    }

    #[test]
    fn conductor_fresnel_matches_known_values() {
        let (eta, k) = (Vec3::new(0.2, 0.9, 1.1), Vec3::new(3.9, 2.4, 2.1));
        let normal = ((eta - 1.0).powf(2.0) + k * k) / ((eta + 1.0).powf(2.0) + k * k);
        assert!(
            (fresnel_conductor(1.0, eta, k) - normal)
                .abs()
                .max_element()
                < 1e-5
        );
        assert!(
            (fresnel_conductor(0.0, eta, k) - Vec3::ONE)
                .abs()
                .max_element()
                < 1e-5
        );
        // With k = 0 the conductor is a dielectric.
        for cos_i in [0.05f32, 0.3, 0.7, 1.0] {
            let c = fresnel_conductor(cos_i, Vec3::splat(1.5), Vec3::ZERO).x;
            assert!((c - fresnel_dielectric(cos_i, 1.5)).abs() < 1e-5, "{cos_i}");
        }
        // A purely imaginary IOR reflects everything: the furnace conductor.
        for cos_i in [0.05f32, 0.5, 1.0] {
            let f = fresnel_conductor(cos_i, Vec3::ZERO, Vec3::ONE);
            assert!((f - Vec3::ONE).abs().max_element() < 1e-5);
        }
    }
}
