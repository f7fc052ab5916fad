//! Per-strategy layers (`--technique-layers`): the contribution of every
//! strategy (s, t) to the image, MIS-weighted and unweighted, as extra film
//! layers (`film/layers.rs`) — Veach's figure of the strategies of each
//! path length (Veach 1997, fig. 10.3) from one render.
//!
//! Layers are ordered by path length k = s + t − 2 (bounces), then by s:
//! for each strategy `s{s}_t{t}` (weighted; all of them add up to the
//! image) then `s{s}_t{t}_unweighted` (that strategy alone, an estimate of
//! all light of k bounces, noisy where the strategy is poor). t ≥ 2
//! strategies add to the sample's pixel; t = 1 strategies are splats and
//! go to the splat layer's per-layer sums (`film/splat.rs`), resolved over
//! the same light-subpath count as the image's splats.

/// The strategies BDPT uses up to `max_depth` bounces, in layer order:
/// t ≥ 1, s + t ≥ 2, s + t − 2 ≤ max_depth, without (1, 1).
pub fn strategies(max_depth: u32) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    for k in 0..=max_depth as usize {
        let n = k + 2;
        for s in 0..n {
            let t = n - s;
            if !(s == 1 && t == 1) {
                out.push((s, t));
            }
        }
    }
    out
}

/// The extra layers' names for `max_depth` bounces.
pub fn layer_names(max_depth: u32) -> Vec<String> {
    strategies(max_depth)
        .into_iter()
        .flat_map(|(s, t)| [format!("s{s}_t{t}"), format!("s{s}_t{t}_unweighted")])
        .collect()
}

/// The index of the weighted layer of (s, t) (the unweighted one follows).
pub fn layer_index(s: usize, t: usize) -> usize {
    let k = s + t - 2;
    // Lengths 0..k hold (j + 2) strategies each, less (1, 1) at length 0.
    let before: usize = (0..k).map(|j| j + 2).sum::<usize>() - usize::from(k > 0);
    let within = if k == 0 { usize::from(s == 2) } else { s };
    2 * (before + within)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_follow_the_names() {
        let names = layer_names(4);
        for (s, t) in strategies(4) {
            let i = layer_index(s, t);
            assert_eq!(names[i], format!("s{s}_t{t}"));
            assert_eq!(names[i + 1], format!("s{s}_t{t}_unweighted"));
        }
        assert_eq!(names.len(), 2 * (2 + 3 + 4 + 5 + 6 - 1));
    }
}
