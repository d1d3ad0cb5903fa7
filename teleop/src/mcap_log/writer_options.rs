//! How a [`TrialWriter`](super::TrialWriter) writes: compression, chunking, flushing.

use std::path::Path;

use super::{LogError, OfferedQos};

/// Chunk compression.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LogCompression {
    /// zstd (what rosbag2's `zstd_fast`/`zstd_small` presets use). The default.
    #[default]
    Zstd,
    /// lz4: faster, larger.
    Lz4,
    /// Chunks stored uncompressed.
    None,
}

impl LogCompression {
    pub(crate) fn to_mcap(self) -> Option<mcap::Compression> {
        match self {
            LogCompression::Zstd => Some(mcap::Compression::Zstd),
            LogCompression::Lz4 => Some(mcap::Compression::Lz4),
            LogCompression::None => None,
        }
    }
}

/// Options of a [`TrialWriter`](super::TrialWriter). `Default` is what the station uses.
#[derive(Debug, Clone, PartialEq)]
pub struct TrialWriterOptions {
    /// Chunk compression.
    pub compression: LogCompression,
    /// A chunk is closed when its uncompressed size reaches this (and on every flush).
    /// Default 1 MiB.
    pub chunk_size_bytes: u64,
    /// Flush when the log time of a write is this far past the last flush, so a crash loses at
    /// most about this much log time. `None`: only explicit flushes, trial events and metadata.
    /// Default 1 s.
    pub auto_flush_interval_ns: Option<i64>,
    /// After each flush, also `fsync` the file, so a power cut (not only a crashed process)
    /// loses at most what came after the flush. Default `true`.
    pub sync_on_flush: bool,
    /// With `sync_on_flush`: sync on a thread of the writer's own, so the writing thread goes
    /// on handing messages to the OS while a sync takes its time (a killed process then loses
    /// only what came after the last flush, however slow the disk). Default `false`: the
    /// flush returns once synced. The station's trial logs sync in the background.
    pub sync_in_background: bool,
    /// Replace an existing final file on [`finish`](super::TrialWriter::finish). Default
    /// `false`: the writer refuses, at creation and again at finish.
    pub overwrite: bool,
    /// QoS recorded in `offered_qos_profiles` for channels created on their first write.
    /// Default: reliable, keep last 10 (the rclcpp publisher default).
    pub default_qos: OfferedQos,
}

impl Default for TrialWriterOptions {
    fn default() -> Self {
        TrialWriterOptions {
            compression: LogCompression::Zstd,
            chunk_size_bytes: 1024 * 1024,
            auto_flush_interval_ns: Some(1_000_000_000),
            sync_on_flush: true,
            sync_in_background: false,
            overwrite: false,
            default_qos: OfferedQos::default(),
        }
    }
}

/// zstd worker threads. 0 = compress in the writing thread: the same output on every machine,
/// and no extra threads competing with the control loop on a 2-core station.
const ZSTD_THREADS: u32 = 0;

impl TrialWriterOptions {
    /// The mcap crate's options for a file with this header.
    pub(crate) fn mcap_options(&self, profile: &str, library: &str) -> mcap::WriteOptions {
        mcap::WriteOptions::new()
            .profile(profile)
            .library(library)
            .compression(self.compression.to_mcap())
            .compression_threads(ZSTD_THREADS)
            .chunk_size(Some(self.chunk_size_bytes))
    }

    /// Checks the ranges; errors name the file the writer is for.
    pub(crate) fn validate(&self, path: &Path) -> Result<(), LogError> {
        if !(1..=(1 << 30)).contains(&self.chunk_size_bytes) {
            return Err(LogError::InvalidOption {
                path: path.to_path_buf(),
                option: "chunk_size_bytes",
                value: self.chunk_size_bytes.to_string(),
                allowed: "1 to 2^30 bytes",
            });
        }
        if let Some(interval) = self.auto_flush_interval_ns
            && interval <= 0
        {
            return Err(LogError::InvalidOption {
                path: path.to_path_buf(),
                option: "auto_flush_interval_ns",
                value: interval.to_string(),
                allowed: "a positive number of nanoseconds, or None",
            });
        }
        Ok(())
    }
}
