//! A global allocator for sweep tests that refuses any single allocation
//! over a limit, so a loader that trusts a count from the file (and asks
//! for 48 GB) fails the test at once, naming the input, instead of being
//! killed by the machine's out-of-memory handler minutes later.
//!
//! Use it in one test binary:
//! `#[global_allocator] static A: CappedAlloc = CappedAlloc::new(256 << 20);`
//! and call [`CappedAlloc::label`] before each input.

use std::alloc::{GlobalAlloc, Layout, System};
use std::io::Write;
use std::sync::Mutex;

/// The system allocator with a ceiling on each request.
pub struct CappedAlloc {
    limit: usize,
}

/// The input being run, printed with a refused request. Locked only to set
/// it and to print it (neither allocates while holding the lock, bar the
/// label's own small growth, which is under any sensible limit).
static LABEL: Mutex<String> = Mutex::new(String::new());

impl CappedAlloc {
    /// Refuses requests above `limit` bytes.
    pub const fn new(limit: usize) -> Self {
        Self { limit }
    }

    /// Names the input now running, for the message of a refused request.
    pub fn label(name: &str) {
        if let Ok(mut label) = LABEL.lock() {
            label.clear();
            label.push_str(name);
        }
    }

    /// Prints the refusal without allocating; the caller then returns null
    /// and the standard library aborts with its own "memory allocation of
    /// N bytes failed".
    fn refuse(&self, size: usize) -> *mut u8 {
        let mut digits = [0u8; 20];
        let mut i = digits.len();
        let mut n = size;
        loop {
            i -= 1;
            digits[i] = b'0' + (n % 10) as u8;
            n /= 10;
            if n == 0 {
                break;
            }
        }
        let mut err = std::io::stderr().lock();
        let _ = err.write_all(b"\ncapped allocator: refused ");
        let _ = err.write_all(&digits[i..]);
        let _ = err.write_all(b" bytes while running: ");
        if let Ok(label) = LABEL.try_lock() {
            let _ = err.write_all(label.as_bytes());
        }
        let _ = err.write_all(b"\n");
        std::ptr::null_mut()
    }
}

// SAFETY: every request is passed to `System` unchanged or refused with
// null, which `GlobalAlloc` allows.
unsafe impl GlobalAlloc for CappedAlloc {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if layout.size() > self.limit {
            return self.refuse(layout.size());
        }
        // SAFETY: the caller's contract is passed on.
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if layout.size() > self.limit {
            return self.refuse(layout.size());
        }
        // SAFETY: the caller's contract is passed on.
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: the caller's contract is passed on.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if new_size > self.limit {
            return self.refuse(new_size);
        }
        // SAFETY: the caller's contract is passed on.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}
