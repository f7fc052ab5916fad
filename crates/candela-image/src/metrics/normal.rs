//! The standard normal tail and its inverse, for z-test thresholds.

/// The complementary error function, via the Chebyshev fit of Numerical
/// Recipes (`erfcc`): relative error below 1.2e-7 for every `x`, ample for
/// choosing a test threshold.
fn erfc(x: f64) -> f64 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let poly = -z * z - 1.265_512_23
        + t * (1.000_023_68
            + t * (0.374_091_96
                + t * (0.096_784_18
                    + t * (-0.186_288_06
                        + t * (0.278_868_07
                            + t * (-1.135_203_98
                                + t * (1.488_515_87 + t * (-0.822_152_23 + t * 0.170_872_77))))))));
    let tail = t * poly.exp();
    if x >= 0.0 {
        tail
    } else {
        2.0 - tail
    }
}

/// `P(|Z| > z)` for a standard normal `Z`: the two-sided p-value of `z`.
pub fn normal_two_sided_p(z: f64) -> f64 {
    erfc(z.abs() / std::f64::consts::SQRT_2)
}

/// The `|z|` above which `tests` two-sided tests together raise a false
/// alarm with probability at most `false_alarm_rate` (Bonferroni: each test
/// at level `false_alarm_rate / tests`). Bonferroni holds for dependent
/// tests too, which matters because the R, G and B of a block are
/// correlated.
///
/// Returns `f64::INFINITY` for a rate of 0 or no tests (nothing may fail),
/// and 0 for a rate of 1 or more.
pub fn two_sided_z_threshold(false_alarm_rate: f64, tests: usize) -> f64 {
    if tests == 0 || false_alarm_rate.is_nan() || false_alarm_rate <= 0.0 {
        return f64::INFINITY;
    }
    let target = false_alarm_rate / tests as f64;
    if target >= 1.0 {
        return 0.0;
    }
    // The p-value falls monotonically in z; bisect it.
    let (mut low, mut high) = (0.0_f64, 40.0_f64);
    for _ in 0..200 {
        let mid = 0.5 * (low + high);
        if normal_two_sided_p(mid) > target {
            low = mid;
        } else {
            high = mid;
        }
    }
    high
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn erfc_known_values() {
        // erfc(0) = 1, erfc(1) = 0.157299207, erfc(2) = 0.004677735, erfc(-1) = 1.842700793.
        assert!((erfc(0.0) - 1.0).abs() < 2e-7);
        assert!((erfc(1.0) - 0.157_299_207).abs() < 0.157 * 1.2e-7 + 1e-12);
        assert!((erfc(2.0) - 0.004_677_735).abs() < 0.0047 * 1.2e-7 + 1e-12);
        assert!((erfc(-1.0) - 1.842_700_793).abs() < 1e-7);
    }

    #[test]
    fn thresholds_match_normal_quantiles() {
        // Textbook two-sided quantiles: 1.959964 (5 %), 2.575829 (1 %), 3.290527 (0.1 %).
        assert!((two_sided_z_threshold(0.05, 1) - 1.959_964).abs() < 1e-5);
        assert!((two_sided_z_threshold(0.01, 1) - 2.575_829).abs() < 1e-5);
        assert!((two_sided_z_threshold(0.01, 10) - 3.290_527).abs() < 1e-5);
        assert_eq!(two_sided_z_threshold(0.0, 5), f64::INFINITY);
        assert_eq!(two_sided_z_threshold(0.5, 0), f64::INFINITY);
        assert_eq!(two_sided_z_threshold(2.0, 1), 0.0);
    }
}
