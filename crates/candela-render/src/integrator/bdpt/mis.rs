//! The multiple-importance weight of strategy (s, t) by the power
//! heuristic, from the ratio recurrence over the subpaths' forward and
//! reverse area densities (Veach 1997 §10.2.1, eq. 10.9; pbrt-v4's
//! `MISWeight`, which uses the balance heuristic).
//!
//! With p_i the density of the path had it been made with i light
//! vertices, p_{i+1}/p_i = p_rev/p_fwd of the vertex that changes sides;
//! the weight of p_s is p_s² / Σ p_i² = 1 / (1 + Σ (p_i/p_s)²). Strategies
//! that cannot exist are left out: those that would connect at a delta
//! vertex (specular scattering, a delta light's position), and `t = 0`.
//! A zero density (a delta lobe, whose pdf is a discrete probability
//! elsewhere) counts as 1 in the ratios, so a chain of specular vertices
//! passes its neighbours' ratios through unchanged (pbrt's `remap0`).
//! (1, 1) is not one of BDPT's strategies (s = 0, t = 2 finds emitters
//! seen directly), so paths of two vertices take weight 1.

use super::vertex::Vertex;
use crate::scene::Scene;

fn remap0(p: f32) -> f32 {
    if p != 0.0 {
        p
    } else {
        1.0
    }
}

/// The power-heuristic weight of strategy (s, t); `sampled` is the vertex
/// [`super::connect`] drew afresh (s = 1 or t = 1).
pub(crate) fn mis_weight(
    scene: &Scene,
    light: &[Vertex],
    camera: &[Vertex],
    sampled: Option<Vertex>,
    s: usize,
    t: usize,
) -> f32 {
    if s + t == 2 {
        return 1.0;
    }
    let mut lv: Vec<Vertex> = light[..s].to_vec();
    let mut cv: Vec<Vertex> = camera[..t].to_vec();
    if let Some(v) = sampled {
        if s == 1 {
            lv[0] = v;
        } else if t == 1 {
            cv[0] = v;
        }
    }
    let delta_light = lv.first().is_some_and(|v| v.is_delta_light(scene));
    // The densities of the connection's ends as the other side samples them.
    let pt_rev = if s > 0 {
        lv[s - 1].pdf(scene, s.checked_sub(2).map(|i| &lv[i]), &cv[t - 1])
    } else {
        cv[t - 1].pdf_light_origin(scene, &cv[t - 2])
    };
    let pt_minus_rev = (t > 1).then(|| {
        if s > 0 {
            cv[t - 1].pdf(scene, Some(&lv[s - 1]), &cv[t - 2])
        } else {
            cv[t - 1].pdf_light(scene, &cv[t - 2])
        }
    });
    let qs_rev =
        (s > 0).then(|| cv[t - 1].pdf(scene, t.checked_sub(2).map(|i| &cv[i]), &lv[s - 1]));
    let qs_minus_rev = (s > 1).then(|| lv[s - 1].pdf(scene, Some(&cv[t - 1]), &lv[s - 2]));
    cv[t - 1].pdf_rev = pt_rev;
    cv[t - 1].delta = false;
    if let Some(p) = pt_minus_rev {
        cv[t - 2].pdf_rev = p;
    }
    if let Some(p) = qs_rev {
        lv[s - 1].pdf_rev = p;
        lv[s - 1].delta = false;
    }
    if let Some(p) = qs_minus_rev {
        lv[s - 2].pdf_rev = p;
    }

    let mut sum = 0.0f32;
    let mut ri = 1.0f32;
    for i in (1..t).rev() {
        ri *= remap0(cv[i].pdf_rev) / remap0(cv[i].pdf_fwd);
        if !cv[i].delta && !cv[i - 1].delta {
            sum += ri * ri;
        }
    }
    ri = 1.0;
    for i in (0..s).rev() {
        ri *= remap0(lv[i].pdf_rev) / remap0(lv[i].pdf_fwd);
        let delta_before = if i > 0 { lv[i - 1].delta } else { delta_light };
        if !lv[i].delta && !delta_before {
            sum += ri * ri;
        }
    }
    let w = 1.0 / (1.0 + sum);
    if w.is_finite() {
        w
    } else {
        0.0
    }
}
