//! The memory budget of a run: how much a job may hold at once.
//!
//! A pipeline that can tell before it starts how much it will keep (a
//! winding program's blocks and per-layer files) compares that estimate with
//! the budget and refuses a job that would exceed it, instead of running
//! until the allocator aborts the process. The budget is one process-wide
//! setting ([`max_memory_bytes`], [`set_max_memory_bytes`]),
//! [`DEFAULT_MAX_MEMORY_BYTES`] unless changed: the command line sets it once
//! from `--max-memory-mb`.

use std::sync::atomic::{AtomicU64, Ordering};

/// The default budget: 2 GiB.
pub const DEFAULT_MAX_MEMORY_BYTES: u64 = 2 * 1024 * 1024 * 1024;

/// The budget in force (bytes).
static MAX_MEMORY_BYTES: AtomicU64 = AtomicU64::new(DEFAULT_MAX_MEMORY_BYTES);

/// The most a run may hold at once, in bytes.
pub fn max_memory_bytes() -> u64 {
    MAX_MEMORY_BYTES.load(Ordering::Relaxed)
}

/// Sets the most a run may hold at once, in bytes, for the whole process (the
/// command line's `--max-memory-mb`).
pub fn set_max_memory_bytes(bytes: u64) {
    MAX_MEMORY_BYTES.store(bytes, Ordering::Relaxed);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_is_two_gib() {
        assert_eq!(DEFAULT_MAX_MEMORY_BYTES, 2_147_483_648);
    }
}
