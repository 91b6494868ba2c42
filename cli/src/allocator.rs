//! The command's memory allocator: mimalloc, for the pages it asks the kernel for.
//!
//! A ray reads a few dozen cache lines of nodes and triangles scattered over the whole
//! structure. On a large mesh (tens of megabytes) with 4 KiB pages nearly each of those lines
//! sits on a page of its own, and most of them miss the processor's caches of page
//! translations; with 2 MiB pages the same structure spans a few dozen pages. On Linux the
//! kernel grants such pages (transparent huge pages) to memory marked for them (`madvise`, the
//! common default), and the system allocator marks none. mimalloc marks the large blocks it
//! maps, so a built or loaded structure lands on huge pages wherever the kernel allows;
//! Embree's allocator marks its trees the same way. Answers do not depend on the allocator,
//! only the time a query waits for its memory.

#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

#[cfg(all(test, target_os = "linux"))]
mod tests {
    /// The `AnonHugePages` (KiB) of the mapping of this process that holds `address`, from
    /// `/proc/self/smaps` (a header line `start-end perms …` per mapping, then its fields).
    fn huge_kib_around(address: usize) -> Option<u64> {
        let smaps = std::fs::read_to_string("/proc/self/smaps").ok()?;
        let mut inside = false;
        for line in smaps.lines() {
            let first = line.split_whitespace().next().unwrap_or("");
            let range = first.split_once('-').and_then(|(start, end)| {
                let start = usize::from_str_radix(start, 16).ok()?;
                let end = usize::from_str_radix(end, 16).ok()?;
                Some(start..end)
            });
            if let Some(range) = range {
                inside = range.contains(&address);
            } else if inside && let Some(kib) = line.strip_prefix("AnonHugePages:") {
                return kib.trim().trim_end_matches("kB").trim().parse().ok();
            }
        }
        None
    }

    /// A 64 MiB block, written page by page as a structure being built is, lands mostly on
    /// huge pages when the kernel grants them to marked memory (`always` or `madvise`). The
    /// system allocator in `madvise` mode (the common default) gives it none.
    #[test]
    fn large_blocks_land_on_huge_pages_where_the_kernel_grants_them() {
        let mode = std::fs::read_to_string("/sys/kernel/mm/transparent_hugepage/enabled")
            .unwrap_or_default();
        if !(mode.contains("[always]") || mode.contains("[madvise]")) {
            eprintln!(
                "skipped: transparent huge pages are off here ({})",
                mode.trim()
            );
            return;
        }
        const BYTES: usize = 64 << 20;
        let mut block = vec![0u8; BYTES];
        for page in block.chunks_mut(4096) {
            page[0] = 1;
        }
        let huge = huge_kib_around(block.as_ptr() as usize + BYTES / 2)
            .expect("the block's mapping is listed in /proc/self/smaps");
        std::hint::black_box(&block);
        // A quarter of the block: the kernel may run short of free 2 MiB frames now and
        // then, but an allocator that never marks its memory gets none at all.
        assert!(
            huge >= (BYTES / 4 / 1024) as u64,
            "{huge} KiB of huge pages under a {} KiB block",
            BYTES / 1024
        );
    }
}
