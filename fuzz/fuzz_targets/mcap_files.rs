//! Any bytes as a trial log on disk: scoring's event reader, then `recover` (its output must
//! read): teleop/tests/suite/mcap_oracle. Scratch files in RAM where /dev/shm exists.
#![no_main]

use std::path::PathBuf;
use std::sync::OnceLock;

#[allow(dead_code)]
#[path = "../../teleop/tests/suite/mcap_oracle/mod.rs"]
mod mcap_oracle;

fn scratch() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let base = std::path::Path::new("/dev/shm");
        let base = if base.is_dir() {
            base.to_path_buf()
        } else {
            std::env::temp_dir()
        };
        let dir = base.join(format!("pomdar-cargo-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("scratch directory");
        dir
    })
}

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    mcap_oracle::check_files(data, scratch(), "case");
});
