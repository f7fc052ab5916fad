//! A mixture of two BSDFs (Mitsuba's `blendbsdf`):
//! f = (1 − w)·f₀ + w·f₁ and pdf = (1 − w)·pdf₀ + w·pdf₁.
//!
//! Sampling picks part 1 with probability w (part 0 otherwise), reusing
//! `u1` rescaled into the picked interval (as Mitsuba does: part 1 when
//! u1 < w), and samples it. A smooth sample is then valued and weighed by
//! the whole mixture at its direction (one-sample MIS over the parts, so
//! `pdf` is the density `sample` really has, as light sampling's MIS
//! needs); a delta sample cannot be reached by the other part, so it keeps
//! its own value scaled by its mixture weight and its discrete probability
//! scaled by the probability of picking it (the ratio, the sample's
//! weight, is the part's own). `f` and `pdf` only ever see the smooth
//! lobes, since the parts' delta lobes return zero there.
//!
//! Every method is out of line (`#[inline(never)]`): each recurses
//! through [`Bsdf`]'s dispatch, and out of line the recursion stays in
//! these calls while `Bsdf`'s own dispatchers (`flags`, `f`, `sample`, …)
//! stay as small as they are without blends, for the render loop to
//! inline or call cheaply.
//!
//! A part may be absent: black, as a one-sided part seen from behind is.
//! Picking it ends the path (the sample carries no energy), which keeps
//! the estimate unbiased with `pdf` the density of what `sample` returns.

use glam::{Vec2, Vec3};

use super::{Bsdf, BsdfFlags, BsdfSample, TransportMode};

/// Two BSDFs and the weight of the second.
#[derive(Clone, Debug, PartialEq)]
pub struct Blend {
    /// The weight of `parts[1]` (and probability of sampling it), in
    /// [0, 1].
    pub weight: f32,
    /// The parts; `None` is black.
    pub parts: [Option<Bsdf>; 2],
}

impl Blend {
    /// The mixture of `first` (weight 1 − `weight`) and `second`
    /// (weight `weight`, clamped to [0, 1]; NaN counts as 0).
    pub fn new(weight: f32, first: Option<Bsdf>, second: Option<Bsdf>) -> Self {
        let weight = if weight.is_nan() {
            0.0
        } else {
            weight.clamp(0.0, 1.0)
        };
        Self {
            weight,
            parts: [first, second],
        }
    }

    /// Each part with its mixture weight (= probability of sampling it).
    fn weighted(&self) -> impl Iterator<Item = (f32, &Bsdf)> {
        let w = [1.0 - self.weight, self.weight];
        w.into_iter()
            .zip(&self.parts)
            .filter_map(|(w, p)| p.as_ref().map(|p| (w, p)))
            .filter(|(w, _)| *w > 0.0)
    }

    /// The union of the parts' flags.
    #[inline(never)]
    pub fn flags(&self) -> BsdfFlags {
        self.weighted()
            .fold(BsdfFlags::EMPTY, |acc, (_, p)| acc | p.flags())
    }

    /// The mixture's value (cosine excluded) in the given mode: each part
    /// takes its own adjoint factor (their media may differ).
    #[inline(never)]
    pub fn f_mode(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> Vec3 {
        self.weighted()
            .map(|(w, p)| w * p.f_mode(wo, wi, mode))
            .sum()
    }

    /// The density with which [`Blend::sample_mode`] returns a smooth `wi`.
    #[inline(never)]
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.weighted().map(|(w, p)| w * p.pdf(wo, wi)).sum()
    }

    /// Picks a part with `u1`, samples it with the rest of `u1` and `u2`,
    /// and values the sample as the module docs say.
    #[inline(never)]
    pub fn sample_mode(
        &self,
        wo: Vec3,
        u1: f32,
        u2: Vec2,
        mode: TransportMode,
    ) -> Option<BsdfSample> {
        let w = self.weight;
        let (pick, p, u1) = if u1 < w {
            (1, w, u1 / w)
        } else {
            (0, 1.0 - w, (u1 - w) / (1.0 - w))
        };
        // Rounding may land on 1, which the parts' lobe choices exclude.
        let u1 = u1.min(1.0 - f32::EPSILON / 2.0);
        let part = self.parts[pick].as_ref()?;
        let mut s = part.sample_mode(wo, u1, u2, mode)?;
        if s.is_specular() {
            s.f *= p;
            s.pdf *= p;
            return Some(s);
        }
        s.pdf = self.pdf(wo, s.wi);
        if !(s.pdf > 0.0 && s.pdf.is_finite()) {
            return None;
        }
        s.f = self.f_mode(wo, s.wi, mode);
        Some(s)
    }

    /// The parts' albedos, mixed.
    #[inline(never)]
    pub fn albedo(&self) -> Vec3 {
        self.weighted().map(|(w, p)| w * p.albedo()).sum()
    }

    /// Whether either part is anisotropic.
    #[inline(never)]
    pub fn is_anisotropic(&self) -> bool {
        self.weighted().any(|(_, p)| p.is_anisotropic())
    }

    /// The squared relative IOR of the first part that refracts at `wo`
    /// (1 when neither does). Only Russian roulette reads it after a
    /// transmission (to judge a path's throughput without the refraction
    /// factor), so taking one part's is a heuristic, never a bias.
    #[inline(never)]
    pub fn refraction_eta2(&self, wo: Vec3) -> f32 {
        self.weighted()
            .map(|(_, p)| p.refraction_eta2(wo))
            .find(|&e| e != 1.0)
            .unwrap_or(1.0)
    }
}
