//! Zeroed weight buffers that ask the system for huge pages.
//!
//! A controller decoded from 8 M connections holds 64 MB of weights, written
//! once right after they are allocated. In 4 KiB pages that is 16,384 page
//! faults, each clearing its page: a fifth of the decode (`perf`, 2026-12-06).
//! Linux's transparent huge pages, where enabled for the regions that ask for
//! them (its `madvise` mode, the common default), fault in 2 MiB at a time.
//! The request is a hint that changes no value — the memory reads zero either
//! way — so a system without huge pages only loses the speed.

/// Buffers smaller than this are left alone: they hold at most one whole
/// 2 MiB page, and smaller ones come from the allocator's heap, already mapped.
const HINT_FROM_BYTES: usize = 4 << 20;

/// A huge page's size on x86-64 and most other Linux systems.
#[cfg(target_os = "linux")]
const HUGE_PAGE: usize = 2 << 20;

/// `len` zeros, in huge pages where the system gives them to regions that ask.
pub(super) fn zeroed<T: Copy + Default>(len: usize) -> Vec<T> {
    // A vector of float zeros is allocated zeroed (calloc: a large buffer's
    // fresh pages are not touched), so the hint comes before any page is
    // faulted in; the huge-page test below fails if that ever changes.
    let v = vec![T::default(); len];
    let bytes = len * size_of::<T>();
    if bytes >= HINT_FROM_BYTES {
        advise_huge(v.as_ptr().cast(), bytes);
    }
    v
}

/// Asks for huge pages on every whole 2 MiB page of `bytes` bytes at `start`.
#[cfg(target_os = "linux")]
fn advise_huge(start: *const u8, bytes: usize) {
    let first = (start as usize).next_multiple_of(HUGE_PAGE);
    let end = (start as usize + bytes) / HUGE_PAGE * HUGE_PAGE;
    if end > first {
        // SAFETY: [first, end) lies inside the caller's live allocation and is
        // page-aligned; MADV_HUGEPAGE changes no byte of it, only how the
        // kernel backs it. A failure (no transparent huge pages) is harmless.
        unsafe {
            libc::madvise(first as *mut libc::c_void, end - first, libc::MADV_HUGEPAGE);
        }
    }
}

#[cfg(not(target_os = "linux"))]
fn advise_huge(_start: *const u8, _bytes: usize) {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn large_and_small_buffers_are_zero_and_writable() {
        for len in [0, 1, 1000, (HINT_FROM_BYTES / 8) + 12_345] {
            let mut v = zeroed::<f64>(len);
            assert_eq!(v.len(), len);
            assert!(v.iter().all(|&x| x.to_bits() == 0));
            v.iter_mut().enumerate().for_each(|(i, x)| *x = i as f64);
            assert!(v.iter().enumerate().all(|(i, &x)| x == i as f64));
        }
        let v = zeroed::<f32>(3 << 20);
        assert!(v.iter().all(|&x| x.to_bits() == 0));
    }

    /// Where the system gives huge pages to regions that ask (Linux with
    /// transparent huge pages in `madvise` or `always` mode), a large
    /// buffer's pages are huge once written.
    #[cfg(target_os = "linux")]
    #[test]
    fn a_large_buffer_gets_huge_pages_where_the_system_gives_them() {
        let mode = std::fs::read_to_string("/sys/kernel/mm/transparent_hugepage/enabled");
        let Ok(mode) = mode else {
            eprintln!("SKIPPED: no transparent huge pages on this system");
            return;
        };
        if mode.contains("[never]") {
            eprintln!(
                "SKIPPED: transparent huge pages are off here ({})",
                mode.trim()
            );
            return;
        }
        // A container may turn them off for its processes (PR_SET_THP_DISABLE).
        let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
        if status
            .lines()
            .any(|l| l.replace(char::is_whitespace, "") == "THP_enabled:0")
        {
            eprintln!("SKIPPED: transparent huge pages are off for this process");
            return;
        }
        let mut v = zeroed::<f64>(16 << 20 >> 3);
        v.iter_mut().for_each(|x| *x = 1.0);
        let (start, end) = (v.as_ptr() as usize, v.as_ptr() as usize + (16 << 20));
        let smaps = std::fs::read_to_string("/proc/self/smaps").unwrap();
        // AnonHugePages of every mapping overlapping the buffer (the hint
        // splits its mapping at the first and last whole huge page).
        let mut huge_kb = None;
        let mut inside = false;
        for line in smaps.lines() {
            if let Some((range, _)) = line.split_once(' ')
                && let Some((a, b)) = range.split_once('-')
                && let (Ok(a), Ok(b)) = (usize::from_str_radix(a, 16), usize::from_str_radix(b, 16))
            {
                inside = a < end && start < b;
            } else if inside && let Some(kb) = line.strip_prefix("AnonHugePages:") {
                let kb = kb
                    .trim()
                    .trim_end_matches("kB")
                    .trim()
                    .parse::<usize>()
                    .unwrap();
                huge_kb = Some(huge_kb.unwrap_or(0) + kb);
            }
        }
        let huge_kb = huge_kb.expect("the buffer's mapping in /proc/self/smaps");
        // At least one huge page: the unaligned ends are in small pages, and a
        // fragmented system may not have every huge page at hand.
        assert!(
            huge_kb >= 2 << 10,
            "{huge_kb} kB in huge pages ({})",
            mode.trim()
        );
        std::hint::black_box(&v);
    }
}
