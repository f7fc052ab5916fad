//! Large traversal arrays on 2 MiB pages, where the OS allows.
//!
//! Incoherent rays through a mesh of a million triangles touch nodes and
//! leaves scattered over some 70 MB. With 4 KiB pages nearly every such
//! access also misses the TLB (a Zen 3 core's 2,048 L2 TLB entries cover
//! 8 MB), and the page walk adds a second dependent memory access to the
//! cache miss. With 2 MiB pages the same entries cover 4 GB. Linux gives
//! anonymous memory huge pages when asked with `madvise(MADV_HUGEPAGE)`
//! before the pages are first touched (the default "madvise" mode of
//! transparent huge pages); [`on_huge_pages`] copies an array into a fresh
//! allocation so advised. Elsewhere, or when the kernel declines, it is a
//! plain copy: the advice never changes contents or results.

/// Arrays smaller than this stay where they are (a few TLB entries cover
/// them, and copying would only cost time).
const MIN_BYTES: usize = 4 << 20;
/// The huge page size on x86-64 and most aarch64 kernels.
const HUGE_PAGE: usize = 2 << 20;

/// Returns `v`'s contents in memory advised for huge pages when it is at
/// least a few MiB on Linux; `v` itself otherwise. The allocation has up to
/// one huge page of spare capacity, so that a whole aligned huge page fits.
pub fn on_huge_pages<T: Copy>(v: Vec<T>) -> Vec<T> {
    let bytes = std::mem::size_of_val(v.as_slice());
    if !cfg!(target_os = "linux") || bytes < MIN_BYTES || std::mem::size_of::<T>() == 0 {
        return v;
    }
    let spare = HUGE_PAGE.div_ceil(std::mem::size_of::<T>());
    let mut out: Vec<T> = Vec::with_capacity(v.len() + spare);
    advise(
        out.as_ptr() as usize,
        out.capacity() * std::mem::size_of::<T>(),
    );
    out.extend_from_slice(&v);
    out
}

/// Advises the whole huge pages inside `[start, start + len)`.
#[cfg(target_os = "linux")]
fn advise(start: usize, len: usize) {
    let first = start.next_multiple_of(HUGE_PAGE);
    let end = (start + len) / HUGE_PAGE * HUGE_PAGE;
    if end > first {
        // SAFETY: the range lies inside an allocation this function's caller
        // owns and has not shared; MADV_HUGEPAGE changes only how the kernel
        // backs it, never its contents. A failure leaves 4 KiB pages.
        unsafe {
            libc::madvise(first as *mut libc::c_void, end - first, libc::MADV_HUGEPAGE);
        }
    }
}

#[cfg(not(target_os = "linux"))]
fn advise(_start: usize, _len: usize) {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contents_survive_the_move() {
        let big: Vec<u32> = (0..(MIN_BYTES / 4 + 12345) as u32).collect();
        let moved = on_huge_pages(big.clone());
        assert_eq!(moved, big);
        let small = vec![1u8, 2, 3];
        assert_eq!(on_huge_pages(small.clone()), small);
    }
}
