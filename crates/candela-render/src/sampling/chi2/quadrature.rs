//! Nested adaptive Simpson quadrature over rectangles.

/// Below this many nested refinements a Simpson estimate is trusted.
const MAX_DEPTH: u32 = 10;
/// Relative tolerance of each integral; expected counts are then accurate to
/// far better than their Poisson noise at a million samples.
const REL_TOL: f64 = 1e-6;
/// Initial panels per axis, so that lobes narrower than a cell are seen.
/// Densities with hard edges (lights) ask for more with
/// [`integrate_2d_panels`]: a panel whose five probes all miss a sliver of
/// the pdf reports zero for it.
const PANELS: usize = 4;

/// ∫∫ f(s, t) over `[s0, s1] × [t0, t1]`, integrating t inside s.
pub(crate) fn integrate_2d(f: impl Fn(f64, f64) -> f64, s: (f64, f64), t: (f64, f64)) -> f64 {
    integrate_2d_panels(f, s, t, PANELS)
}

/// [`integrate_2d`] starting from `panels` panels per axis.
pub(crate) fn integrate_2d_panels(
    f: impl Fn(f64, f64) -> f64,
    s: (f64, f64),
    t: (f64, f64),
    panels: usize,
) -> f64 {
    integrate_panels(
        &|s_val| integrate_panels(&|t_val| f(s_val, t_val), t.0, t.1, panels),
        s.0,
        s.1,
        panels,
    )
}

/// ∫ f over [a, b]: fixed panels, each refined adaptively.
pub(crate) fn integrate_1d(f: &dyn Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    integrate_panels(f, a, b, PANELS)
}

fn integrate_panels(f: &dyn Fn(f64) -> f64, a: f64, b: f64, panels: usize) -> f64 {
    let h = (b - a) / panels as f64;
    (0..panels)
        .map(|i| {
            let (x0, x1) = (a + i as f64 * h, a + (i + 1) as f64 * h);
            let (f0, fm, f1) = (f(x0), f((x0 + x1) / 2.0), f(x1));
            let whole = (x1 - x0) / 6.0 * (f0 + 4.0 * fm + f1);
            adaptive(f, x0, x1, f0, fm, f1, whole, MAX_DEPTH)
        })
        .sum()
}

#[allow(clippy::too_many_arguments)]
fn adaptive(
    f: &dyn Fn(f64) -> f64,
    a: f64,
    b: f64,
    fa: f64,
    fm: f64,
    fb: f64,
    whole: f64,
    depth: u32,
) -> f64 {
    let m = (a + b) / 2.0;
    let (lm, rm) = ((a + m) / 2.0, (m + b) / 2.0);
    let (flm, frm) = (f(lm), f(rm));
    let left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
    let right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
    let delta = left + right - whole;
    let tol = REL_TOL * (left + right).abs() + 1e-15 * (b - a);
    if depth == 0 || delta.abs() <= 15.0 * tol {
        return left + right + delta / 15.0;
    }
    adaptive(f, a, m, fa, flm, fm, left, depth - 1)
        + adaptive(f, m, b, fm, frm, fb, right, depth - 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integrates_smooth_and_discontinuous_functions() {
        let sphere = integrate_2d(|s, _| s.sin(), (0.0, std::f64::consts::PI), (0.0, 1.0));
        assert!((sphere - 2.0).abs() < 1e-6, "{sphere}");
        let step = integrate_1d(&|x| if x < 0.3 { 1.0 } else { 0.0 }, 0.0, 1.0);
        assert!((step - 0.3).abs() < 1e-4, "{step}");
    }
}
