//! All the lights of a scene, and how one is chosen for a light sample.

use super::backs::LampBacks;
use super::tree::LightTree;
use super::{LampSize, Light, LightSample};
use crate::shape::{PrimKind, PrimRef};
use glam::{Vec2, Vec3};
use std::ops::Range;
use std::sync::OnceLock;

const NONE: u32 = u32::MAX;

/// The scene's lights. Delta lights are each sampled once per shading point
/// (CS184: one sample per delta light); one of the others is chosen per
/// light sample ([`LightSet::selector`]: uniformly, by power or by the
/// light tree), so a lamp made of many triangles costs one sample, not one
/// per triangle.
#[derive(Clone, Debug, Default)]
pub struct LightSet {
    lights: Vec<Light>,
    delta: Vec<u32>,
    infinite: Vec<u32>,
    /// Non-delta lights and the running sum of their selection probability.
    sampled: Vec<u32>,
    cdf: Vec<f32>,
    /// Per entry of `sampled`, what a choice by power returns, read as one
    /// record (a light sample's choice read three arrays, each with its
    /// bounds check).
    power_choices: Vec<PowerChoice>,
    /// Selection probability per light (0 for delta lights).
    pmf: Vec<f32>,
    /// Per primitive kind, the light index of each emissive primitive
    /// (by index within its kind), `NONE` for the others.
    prim_light: [Vec<u32>; PrimKind::COUNT],
    /// Surface area and centre per area light (zero for the others),
    /// computed once instead of per light sample.
    sizes: Vec<LampSize>,
    /// Whether rays can hit each light ([`Light::is_hittable`]), read
    /// once per light sample.
    hittable: Vec<bool>,
    /// Running sum of every light's probability of being chosen to emit
    /// (delta lights included), and that probability per light.
    emit_cdf: Vec<f32>,
    emit_pmf: Vec<f32>,
    /// The planes of the sampled lights when all are planar lamps.
    backs: LampBacks,
    /// The light tree, built when a selector first asks for it.
    tree: OnceLock<LightTree>,
}

/// Caps the share of the choices that the lights at infinity get by power
/// at `n / (n + 1)` (`n` of them), the share pbrt-v4's light BVH gives
/// them, rescaling each group's power weights so that each keeps its own
/// ratios. An environment's power figure is its radiance through a disk of
/// the whole scene's size, the most any set of receivers could take from
/// it. Beside a long ground plane that figure outweighs a small lamp by
/// orders of magnitude, although both light the points near the lamp alike.
/// By power alone, a lamp of 5 cm radius under a sky with a 400 m ground got
/// 10^-4 of the light samples, and the image 1000× the relative error of a
/// uniform choice (BENCHMARKS.md). At worst the cap costs a sky-lit point
/// half its sky samples, and BSDF samples still find the sky under MIS.
/// Where the overstated figure still gives the sky less than the cap (lamps
/// brighter than the sky, as in a city at night), the choice stays by
/// power. A group without power keeps no share.
fn share_with_lights_at_infinity(weights: &mut [f32], at_infinity: &[bool]) {
    let sum = |infinite: bool| -> f32 {
        weights
            .iter()
            .zip(at_infinity)
            .filter(|&(_, &inf)| inf == infinite)
            .map(|(w, _)| w)
            .sum()
    };
    let (sky, lamps) = (sum(true), sum(false));
    if sky <= 0.0 || lamps <= 0.0 || !(sky + lamps).is_finite() {
        return;
    }
    let n = at_infinity.iter().filter(|&&inf| inf).count() as f32;
    let cap = n / (n + 1.0);
    if sky / (sky + lamps) <= cap {
        return;
    }
    let sky_scale = cap / sky;
    let lamp_scale = (1.0 - cap) / lamps;
    for (w, &inf) in weights.iter_mut().zip(at_infinity) {
        *w *= if inf { sky_scale } else { lamp_scale };
    }
}

impl LightSet {
    /// Collects `lights`; `prim_light` pairs each emissive primitive with
    /// the index of its light. `scene_radius` sizes lights at infinity.
    pub fn new(lights: Vec<Light>, prim_light: &[(PrimRef, u32)], scene_radius: f32) -> Self {
        let mut by_kind: [Vec<u32>; PrimKind::COUNT] = Default::default();
        for &(prim, light) in prim_light {
            let table = &mut by_kind[prim.kind() as usize];
            let i = prim.index() as usize;
            if table.len() <= i {
                table.resize(i + 1, NONE);
            }
            table[i] = light;
        }
        let mut delta = Vec::new();
        let mut infinite = Vec::new();
        let mut sampled = Vec::new();
        let mut weights = Vec::new();
        for (i, light) in lights.iter().enumerate() {
            if light.is_delta() {
                delta.push(i as u32);
                continue;
            }
            if light.is_infinite() {
                infinite.push(i as u32);
            }
            sampled.push(i as u32);
            weights.push(light.power(scene_radius).max(0.0));
        }
        let total: f32 = weights.iter().sum();
        if total <= 0.0 || !total.is_finite() {
            // No usable power figure: choose uniformly.
            weights.iter_mut().for_each(|w| *w = 1.0);
        }
        let at_infinity: Vec<bool> = sampled
            .iter()
            .map(|&i| lights[i as usize].is_infinite())
            .collect();
        share_with_lights_at_infinity(&mut weights, &at_infinity);
        let total: f32 = weights.iter().sum();
        let mut pmf = vec![0.0; lights.len()];
        let mut cdf = Vec::with_capacity(weights.len());
        let mut running = 0.0;
        for (&i, &w) in sampled.iter().zip(&weights) {
            pmf[i as usize] = w / total;
            running += w / total;
            cdf.push(running);
        }
        let power_choices = sampled
            .iter()
            .enumerate()
            .map(|(k, &light)| PowerChoice {
                light,
                pmf: pmf[light as usize],
                start: if k == 0 { 0.0 } else { cdf[k - 1] },
                end: cdf[k],
            })
            .collect();
        let (emit_pmf, emit_cdf) = emission_pmf(&lights, scene_radius);
        let sizes = lights
            .iter()
            .map(|l| match l {
                Light::Area(a) => LampSize::of(&a.shape),
                _ => LampSize::default(),
            })
            .collect();
        let hittable = lights.iter().map(Light::is_hittable).collect();
        let backs = LampBacks::new(&lights, &sampled);
        Self {
            sizes,
            hittable,
            backs,
            lights,
            delta,
            infinite,
            sampled,
            cdf,
            power_choices,
            pmf,
            prim_light: by_kind,
            emit_cdf,
            emit_pmf,
            tree: OnceLock::new(),
        }
    }

    /// All lights.
    pub fn lights(&self) -> &[Light] {
        &self.lights
    }

    /// Whether the scene has no light at all.
    pub fn is_empty(&self) -> bool {
        self.lights.is_empty()
    }

    /// Delta lights (sampled once each), with their indices.
    pub fn delta_lights(&self) -> impl Iterator<Item = (u32, &Light)> {
        self.delta.iter().map(|&i| (i, &self.lights[i as usize]))
    }

    /// Indices of non-delta lights at infinity (seen by escaping rays).
    pub fn infinite_lights(&self) -> impl Iterator<Item = u32> + '_ {
        self.infinite.iter().copied()
    }

    /// Whether any non-delta light can be chosen by [`LightSet::choose`].
    pub fn has_sampled_lights(&self) -> bool {
        !self.sampled.is_empty()
    }

    /// Whether `p` is behind every non-delta light (all planar lamps, which
    /// emit on one side), so that every light sample from it would be
    /// rejected (`backs.rs`); false when that is not certain.
    #[inline]
    pub fn behind_every_lamp(&self, p: Vec3) -> bool {
        self.backs.all_behind(p)
    }

    /// The number of non-delta lights (those a light sample chooses among).
    pub fn sampled_count(&self) -> usize {
        self.sampled.len()
    }

    /// The light tree over the non-delta lights, built on first use (its
    /// power figures are the power selection's probabilities, so lights
    /// the power choice never picks have no importance in the tree either).
    pub fn tree(&self) -> &LightTree {
        self.tree
            .get_or_init(|| LightTree::new(&self.lights, &self.pmf))
    }

    /// Chooses a non-delta light by power: (light index, probability).
    pub(super) fn choose_by_power(&self, u: f32) -> Option<(u32, f32)> {
        self.choose_by_power_within(u).map(|(i, pmf, _)| (i, pmf))
    }

    /// [`LightSet::choose_by_power`], with the interval of [0, 1) whose
    /// values of `u` choose that light (its share of the running sum).
    #[inline]
    pub(super) fn choose_by_power_within(&self, u: f32) -> Option<(u32, f32, Range<f32>)> {
        let last = self.power_choices.len().checked_sub(1)?;
        let k = entries_at_most(&self.cdf, u).min(last);
        let choice = &self.power_choices[k];
        Some((choice.light, choice.pmf, choice.start..choice.end))
    }

    /// Probability that [`LightSet::choose_by_power`] picks light `i`.
    pub(super) fn power_pmf(&self, i: u32) -> f32 {
        self.pmf[i as usize]
    }

    /// Chooses a non-delta light, each equally likely.
    pub(super) fn choose_uniformly(&self, u: f32) -> Option<(u32, f32)> {
        self.choose_uniformly_within(u).map(|(i, pmf, _)| (i, pmf))
    }

    /// [`LightSet::choose_uniformly`], with the interval of [0, 1) whose
    /// values of `u` choose that light.
    #[inline]
    pub(super) fn choose_uniformly_within(&self, u: f32) -> Option<(u32, f32, Range<f32>)> {
        let n = self.sampled.len();
        if n == 0 {
            return None;
        }
        let k = ((u * n as f32) as usize).min(n - 1);
        let n_f = n as f32;
        Some((
            self.sampled[k],
            1.0 / n_f,
            k as f32 / n_f..(k + 1) as f32 / n_f,
        ))
    }

    /// Probability that [`LightSet::choose_uniformly`] picks light `i`.
    pub(super) fn uniform_pmf(&self, i: u32) -> f32 {
        if self.lights[i as usize].is_delta() {
            0.0
        } else {
            1.0 / self.sampled.len() as f32
        }
    }

    /// Chooses the light a light subpath starts from: any light, delta
    /// lights included, in proportion to [`Light::power`] (the figure that
    /// also weighs next-event estimation's choice; for spot lights an upper
    /// bound that ignores the falloff, for lights at infinity the flux
    /// through the scene's disk: only the variance depends on it, any
    /// positive probability is unbiased). Uniform when no light reports a
    /// positive power. Returns (light index, probability).
    pub fn choose_emitter(&self, u: f32) -> Option<(u32, f32)> {
        if self.emit_cdf.is_empty() {
            return None;
        }
        let k = self
            .emit_cdf
            .partition_point(|&c| c <= u)
            .min(self.emit_cdf.len() - 1);
        Some((k as u32, self.emit_pmf[k]))
    }

    /// Probability that [`LightSet::choose_emitter`] picks light `i` (what
    /// a camera path that hits light `i` needs for its MIS weight).
    pub fn emitter_pmf(&self, i: u32) -> f32 {
        self.emit_pmf[i as usize]
    }

    /// The light of emissive primitive `prim`, if it is one.
    pub fn light_of_prim(&self, prim: PrimRef) -> Option<u32> {
        match self.prim_light[prim.kind() as usize].get(prim.index() as usize) {
            Some(&l) if l != NONE => Some(l),
            _ => None,
        }
    }

    /// Light `i`.
    pub fn get(&self, i: u32) -> &Light {
        &self.lights[i as usize]
    }

    /// `get(i).is_hittable()`, precomputed.
    #[inline]
    pub fn is_hittable(&self, i: u32) -> bool {
        self.hittable[i as usize]
    }

    /// `get(i).sample_li(p, u)`, with the size of an area light precomputed.
    pub fn sample_li(&self, i: u32, p: Vec3, u: Vec2) -> Option<LightSample> {
        match &self.lights[i as usize] {
            Light::Area(a) => a.sample_li_with_size(p, u, &self.sizes[i as usize]),
            light => light.sample_li(p, u),
        }
    }

    /// `get(i).pdf_li(p, wi, p_light)`, with the size of an area light precomputed.
    pub fn pdf_li(&self, i: u32, p: Vec3, wi: Vec3, p_light: Vec3) -> f32 {
        match &self.lights[i as usize] {
            Light::Area(a) => a.pdf_li_with_size(p, wi, p_light, &self.sizes[i as usize]),
            light => light.pdf_li(p, wi, p_light),
        }
    }
}

/// One light of a choice by power: its index, probability and share of
/// [0, 1) (from the running sum before it to its own).
#[derive(Clone, Copy, Debug)]
struct PowerChoice {
    light: u32,
    pmf: f32,
    start: f32,
    end: f32,
}

/// Every light's probability of being chosen to emit, in proportion to
/// its power (uniform when no power is positive), and the running sum.
fn emission_pmf(lights: &[Light], scene_radius: f32) -> (Vec<f32>, Vec<f32>) {
    let mut weights: Vec<f32> = lights
        .iter()
        .map(|l| {
            let p = l.power(scene_radius);
            if p.is_finite() {
                p.max(0.0)
            } else {
                0.0
            }
        })
        .collect();
    let total: f32 = weights.iter().sum();
    if !(total > 0.0 && total.is_finite()) {
        weights.iter_mut().for_each(|w| *w = 1.0);
    }
    let total: f32 = weights.iter().sum();
    let pmf: Vec<f32> = weights.iter().map(|w| w / total).collect();
    let mut running = 0.0;
    let mut cdf: Vec<f32> = pmf
        .iter()
        .map(|p| {
            running += p;
            running
        })
        .collect();
    // Rounding must not leave u near 1 past the last light that can be
    // chosen (nor let it pick a zero-probability light after it).
    if let Some(last) = pmf.iter().rposition(|&p| p > 0.0) {
        cdf[last..].iter_mut().for_each(|c| *c = 1.0);
    }
    (pmf, cdf)
}

/// Entries of a running sum this short are counted rather than searched.
const SHORT_CDF: usize = 8;

/// How many entries of the non-decreasing running sum `cdf` are at most `u`:
/// `cdf.partition_point(|&c| c <= u)`, the same index. A scene's few lamps
/// are counted without branches (the binary search cost about 15
/// instructions per light sample); longer sums are searched.
#[inline(always)]
fn entries_at_most(cdf: &[f32], u: f32) -> usize {
    if cdf.len() <= SHORT_CDF {
        cdf.iter().map(|&c| usize::from(c <= u)).sum()
    } else {
        cdf.partition_point(|&c| c <= u)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::light::{
        AmbientLight, AreaLight, AreaShape, LightContext, LightSelection, PointLight,
    };
    use std::f32::consts::PI;

    /// The count is the binary search's index for running sums of every
    /// length up to past the short ones, with repeated entries (lights of no
    /// power), at and between the entries, at 0, 1 and NaN.
    #[test]
    fn counting_finds_the_binary_searchs_index() {
        let mut x = 0x9e37_79b9u32;
        let mut unit = || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            (x >> 8) as f32 / 16_777_216.0
        };
        for len in 0..=2 * SHORT_CDF {
            for _ in 0..200 {
                let weights: Vec<f32> = (0..len)
                    .map(|_| if unit() < 0.2 { 0.0 } else { unit() })
                    .collect();
                let total: f32 = weights.iter().sum::<f32>().max(1e-3);
                let mut running = 0.0;
                let cdf: Vec<f32> = weights
                    .iter()
                    .map(|w| {
                        running += w / total;
                        running
                    })
                    .collect();
                let mut probes = vec![0.0, 1.0, f32::NAN, unit(), unit()];
                probes.extend(cdf.iter().flat_map(|&c| [c, c.next_down(), c.next_up()]));
                for u in probes {
                    let expected = cdf.partition_point(|&c| c <= u);
                    assert_eq!(entries_at_most(&cdf, u), expected, "{cdf:?} at {u}");
                }
            }
        }
    }

    #[test]
    fn lights_are_chosen_in_proportion_to_power() {
        let sky = |r: f32| {
            Light::Ambient(AmbientLight {
                radiance: Vec3::splat(r),
            })
        };
        let point = Light::Point(PointLight {
            position: Vec3::ZERO,
            intensity: Vec3::ONE,
        });
        let set = LightSet::new(vec![sky(1.0), point, sky(3.0)], &[], 1.0);
        assert_eq!(set.delta_lights().count(), 1);
        assert!((set.power_pmf(0) - 0.25).abs() < 1e-6);
        assert_eq!(set.power_pmf(1), 0.0);
        assert!((set.power_pmf(2) - 0.75).abs() < 1e-6);
        let n = 1000;
        let picks_of_2 = (0..n)
            .filter(|k| set.choose_by_power((*k as f32 + 0.5) / n as f32).unwrap().0 == 2)
            .count();
        assert_eq!(picks_of_2, 750);
    }

    /// Lights at infinity get at most `n / (n + 1)` of the choices, by power
    /// and by the light tree alike, each group split by its own powers,
    /// however the scene's size inflates a sky's power figure; below the
    /// cap the choice stays by power.
    #[test]
    fn lights_at_infinity_share_the_choices_with_the_lamps() {
        let sky = |r: f32| {
            Light::Ambient(AmbientLight {
                radiance: Vec3::splat(r),
            })
        };
        let lamp = |radiance: f32| {
            Light::Area(AreaLight {
                shape: AreaShape::Triangle {
                    v: [Vec3::ZERO, Vec3::X, Vec3::Z],
                    normal: Vec3::NEG_Y,
                },
                radiance: Vec3::splat(radiance),
                textured: None,
            })
        };
        // A sky's power figure grows with the scene radius squared: at
        // radius 1000 these skies outweigh the lamps by about 10^7.
        let set = LightSet::new(vec![sky(1.0), lamp(1.0), sky(3.0), lamp(3.0)], &[], 1000.0);
        let expected = [
            2.0 / 3.0 * 0.25,
            1.0 / 3.0 * 0.25,
            2.0 / 3.0 * 0.75,
            1.0 / 3.0 * 0.75,
        ];
        for (i, want) in expected.into_iter().enumerate() {
            let got = set.power_pmf(i as u32);
            assert!((got - want).abs() < 1e-6, "light {i}: {got}, want {want}");
        }
        let tree = set.selector(LightSelection::Bvh);
        let ctx = LightContext::surface(Vec3::new(0.2, -1.0, 0.2), Vec3::Y, false);
        let skies = tree.pmf(&ctx, 0) + tree.pmf(&ctx, 2);
        assert!(
            (skies - 2.0 / 3.0).abs() < 1e-6,
            "the tree's skies: {skies}"
        );
        // Lamps brighter than the skies' overstated figure: powers alone.
        let dim = LightSet::new(vec![sky(1e-4), lamp(1.0), sky(3e-4)], &[], 1.0);
        let by_power = |l: f32| l / (PI * PI * 4e-4 + PI * 0.5);
        assert!((dim.power_pmf(0) - by_power(PI * PI * 1e-4)).abs() < 1e-6);
        assert!((dim.power_pmf(1) - by_power(PI * 0.5)).abs() < 1e-6);
        // Only skies (or only lamps): powers alone.
        let skies_only = LightSet::new(vec![sky(1.0), sky(3.0)], &[], 1000.0);
        assert!((skies_only.power_pmf(1) - 0.75).abs() < 1e-6);
    }

    /// The set's samples and densities, with the area cached, are the
    /// light's own, bit for bit.
    #[test]
    fn cached_area_gives_the_lights_own_samples() {
        let v = [
            Vec3::new(0.0, 2.0, 0.0),
            Vec3::new(1.0, 2.0, 0.3),
            Vec3::new(0.2, 2.1, 1.0),
        ];
        let normal = (v[1] - v[0]).cross(v[2] - v[0]).normalize();
        let tri = Light::Area(AreaLight {
            shape: AreaShape::Triangle { v, normal },
            radiance: Vec3::ONE,
            textured: None,
        });
        let set = LightSet::new(vec![tri.clone()], &[], 1.0);
        let mut hits = 0;
        for k in 0..64 {
            let u = Vec2::new((k % 8) as f32 / 8.0 + 0.03, (k / 8) as f32 / 8.0 + 0.05);
            let p = Vec3::new(0.1 * k as f32 - 3.0, -1.0, 0.5);
            let want = tri.sample_li(p, u);
            assert_eq!(set.sample_li(0, p, u), want);
            if let Some(s) = want {
                let q = p + s.wi * s.distance;
                assert_eq!(set.pdf_li(0, p, s.wi, q), tri.pdf_li(p, s.wi, q));
                hits += 1;
            }
        }
        assert!(hits > 32, "{hits}");
    }
}
