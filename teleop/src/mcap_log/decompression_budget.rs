//! How much a trial log may make us decompress, checked against each chunk's *declared*
//! uncompressed size before anything is decompressed (the declared size is what the
//! decompressor allocates). A crafted file can declare 1 GiB per chunk in a few bytes each;
//! `pomdar score` reads files on every core, so without a budget a handful of such files
//! would exhaust memory.
//!
//! The limits, and why real logs never reach them:
//! - one chunk: [`MAX_CHUNK_BYTES`] = 64 MiB. The station's writer closes a chunk at 1 MiB
//!   uncompressed (and at every flush); rosbag2 and the `mcap` tools default to a few MiB.
//!   A chunk over the limit could only come from one message over 64 MiB.
//! - one file, all chunks together: [`MAX_RATIO`] = 200 × the file's size, at least
//!   [`MIN_FILE_BYTES`] = 256 MiB and at most [`MAX_FILE_BYTES`] = 4 GiB. A 60-minute trial
//!   log holds about 0.3–1 GB of CDR messages (glove keypoints at 100–200 Hz, joint and arm
//!   targets at 25 Hz, status): under the 4 GiB cap; zstd shrinks that float data 2–10×,
//!   never 200× (a whole file compressed 200× would be almost all repeated bytes).

/// The largest declared uncompressed size of one chunk, bytes.
pub const MAX_CHUNK_BYTES: u64 = 64 << 20;
/// A file may decompress to at most this many times its own size...
pub const MAX_RATIO: u64 = 200;
/// ...but always at least this many bytes...
pub const MIN_FILE_BYTES: u64 = 256 << 20;
/// ...and never more than this many.
pub const MAX_FILE_BYTES: u64 = 4 << 30;

/// The budget of one file: what it may still decompress.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DecompressionBudget {
    file_size: u64,
    limit: u64,
    used: u64,
}

impl DecompressionBudget {
    /// The budget of a file of `file_size` bytes.
    pub fn for_file(file_size: u64) -> DecompressionBudget {
        DecompressionBudget {
            file_size,
            limit: file_size
                .saturating_mul(MAX_RATIO)
                .clamp(MIN_FILE_BYTES, MAX_FILE_BYTES),
            used: 0,
        }
    }

    /// The file's total limit, bytes.
    pub fn limit(&self) -> u64 {
        self.limit
    }

    /// Takes a chunk declaring `declared` uncompressed bytes out of the budget, or says which
    /// limit it breaks (nothing is taken then).
    pub fn charge(&mut self, declared: u64) -> Result<(), String> {
        if declared > MAX_CHUNK_BYTES {
            return Err(format!(
                "a chunk declares {declared} bytes uncompressed, over the limit of {MAX_CHUNK_BYTES} \
                 bytes (64 MiB) per chunk"
            ));
        }
        let total = self.used.saturating_add(declared);
        if total > self.limit {
            return Err(format!(
                "its chunks declare over {} bytes uncompressed in all, over this file's \
                 decompression budget of {} bytes ({MAX_RATIO} × its {} bytes, at least \
                 {MIN_FILE_BYTES}, at most {MAX_FILE_BYTES})",
                total, self.limit, self.file_size
            ));
        }
        self.used = total;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_limits_are_per_chunk_and_per_file() {
        let mut small = DecompressionBudget::for_file(1000);
        assert_eq!(small.limit(), MIN_FILE_BYTES);
        assert!(small.charge(1 << 30).unwrap_err().contains("per chunk"));
        for _ in 0..4 {
            assert!(small.charge(MAX_CHUNK_BYTES).is_ok());
        }
        let e = small.charge(1).unwrap_err();
        assert!(e.contains("budget of 268435456 bytes"), "{e}");
        assert_eq!(DecompressionBudget::for_file(2 << 20).limit(), 400 << 20);
        assert_eq!(
            DecompressionBudget::for_file(1 << 40).limit(),
            MAX_FILE_BYTES
        );
        assert_eq!(
            DecompressionBudget::for_file(u64::MAX).limit(),
            MAX_FILE_BYTES
        );
    }
}
