//! The 8-wide node test with AVX2, and the traversal loop compiled for it.
//!
//! The loop ([`crate::wide_traverse`]) and the caller's leaf test are
//! inlined into one `#[target_feature(enable = "avx2,fma")]` function, so
//! the whole query runs with 256-bit registers and VEX encoding; it is only
//! entered after [`has_avx2`] said yes. The slab test performs the same
//! operations as the portable 4-lane one (`(plane - origin) * inv_dir`, not
//! the fused form, whose cancellation would void the conservative
//! `ROBUST_SCALE` bound), so both give bit-identical results.

use crate::traverse::StatsSink;
use crate::RayBoxQuery;

/// Whether this CPU runs the AVX2 path (AVX2 and FMA; cached by std).
pub fn has_avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

#[cfg(target_arch = "x86_64")]
pub(crate) use imp::walk;

#[cfg(target_arch = "x86_64")]
mod imp {
    use super::*;
    use crate::traverse::ROBUST_SCALE;
    use crate::wide_traverse::{near_rows, walk_with, NodeTest};
    use crate::Bvh8;
    use std::arch::x86_64::*;

    /// The ray broadcast to 8 lanes. Only built inside [`walk`], that is
    /// after AVX2 was detected, which makes its safe methods sound.
    struct Ray8 {
        origin: [__m256; 3],
        inv_dir: [__m256; 3],
        near_row: [usize; 3],
    }

    impl NodeTest<8> for Ray8 {
        #[inline(always)]
        fn enter(&self, b: &[[f32; 8]; 6], t_max: f32) -> ([f32; 8], u32) {
            // SAFETY: a `Ray8` exists only where AVX2 is available (see the
            // type), and every load reads a whole `[f32; 8]` row.
            unsafe {
                let mut near = _mm256_setzero_ps();
                let mut far = _mm256_set1_ps(t_max * ROBUST_SCALE);
                for a in 0..3 {
                    let nr = self.near_row[a];
                    let fr = if nr >= 3 { nr - 3 } else { nr + 3 };
                    let pn = _mm256_loadu_ps(b[nr].as_ptr());
                    let pf = _mm256_loadu_ps(b[fr].as_ptr());
                    let tn = _mm256_mul_ps(_mm256_sub_ps(pn, self.origin[a]), self.inv_dir[a]);
                    let tf = _mm256_mul_ps(_mm256_sub_ps(pf, self.origin[a]), self.inv_dir[a]);
                    // Running value second: a NaN lane keeps it (as `maxps`).
                    near = _mm256_max_ps(tn, near);
                    far = _mm256_min_ps(tf, far);
                }
                let mut dist = [0.0f32; 8];
                _mm256_storeu_ps(dist.as_mut_ptr(), near);
                let mask = _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(near, far)) as u32;
                (dist, mask)
            }
        }
    }

    /// The traversal of an 8-wide tree with the AVX2 node test.
    ///
    /// # Safety
    /// The CPU must support AVX2 and FMA ([`has_avx2`]).
    #[target_feature(enable = "avx2,fma")]
    pub(crate) unsafe fn walk<const ORDERED: bool, S: StatsSink>(
        bvh: &Bvh8,
        ray: &RayBoxQuery,
        t_max: &mut f32,
        stats: &mut S,
        prefetch_leaf: impl Fn(u32, u32),
        visit: impl FnMut(u32, u32, &mut f32) -> bool,
    ) -> bool {
        let (o, inv) = (ray.origin(), ray.inv_dir());
        let r = Ray8 {
            origin: [
                _mm256_set1_ps(o.x),
                _mm256_set1_ps(o.y),
                _mm256_set1_ps(o.z),
            ],
            inv_dir: [
                _mm256_set1_ps(inv.x),
                _mm256_set1_ps(inv.y),
                _mm256_set1_ps(inv.z),
            ],
            near_row: near_rows(ray),
        };
        walk_with::<8, ORDERED, S, Ray8>(bvh, &r, t_max, stats, prefetch_leaf, visit)
    }
}
