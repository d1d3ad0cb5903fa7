//! Any text as a URDF, imported with the shipped ORCA import file:
//! retarget/tests/suite/config_oracle. Seed it with ../shared/reference/orcahand_v1_right.urdf.
#![no_main]

use std::sync::OnceLock;

use retarget::{FrameSpec, UrdfImport};

#[allow(dead_code)]
#[path = "../../retarget/tests/suite/config_oracle/mod.rs"]
mod config_oracle;

fn import() -> &'static UrdfImport {
    static IMPORT: OnceLock<UrdfImport> = OnceLock::new();
    IMPORT.get_or_init(|| {
        #[derive(serde::Deserialize)]
        struct ImportFile {
            strip_prefix: String,
            frames: FrameSpec,
        }
        let file: ImportFile = toml::from_str(include_str!(
            "../../launch_configs/hands/orca_v1_right_urdf.toml"
        ))
        .expect("the shipped import file parses");
        UrdfImport {
            strip_prefix: file.strip_prefix,
            frames: file.frames,
        }
    })
}

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    config_oracle::check_urdf(&String::from_utf8_lossy(data), import());
});
