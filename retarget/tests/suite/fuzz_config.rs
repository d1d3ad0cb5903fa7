//! Fuzzing of the retargeting configuration, model and embodiment loaders on stable Rust: the
//! shipped files mutated key by key (`fuzz/support/toml_mutation.rs`) and as text. No panic;
//! errors are `Err`; and whatever loads works — a configuration that loads builds a
//! retargeter whose command for a real frame is finite and within the joint limits, a model
//! that loads has finite forward kinematics, an embodiment catalog that loads retargets.
//!
//! URDF import: the reference ORCA URDF (`../shared/reference/`, skipped with a notice where
//! it is absent; CI has it) with numbers replaced by hostile ones, bytes changed, and cut,
//! read with the shipped import file.
//!
//! CI budget: 1,500 cases per loader (300 for the URDF); `PROPTEST_CASES=N` for longer.

use crate::common;
use crate::config_oracle;
use crate::toml_mutation;

use std::sync::OnceLock;

use proptest::prelude::*;
use proptest::sample::Index;
use retarget::{EMBODIMENTS_TOML, FrameSpec, ORCA_V1_RIGHT_TOML, RetargetConfig, UrdfImport};
use toml_mutation::{budget, edits, mutate};

fn shipped_config() -> String {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../launch_configs/retarget/orca_full_lab22.toml"
    );
    std::fs::read_to_string(path).unwrap()
}

proptest! {
    #![proptest_config(budget(1500))]

    // Each mutated file is tried as every kind (a model file as a configuration, ...).

    #[test]
    fn mutated_retarget_configs_load_and_work_or_fail(
        base in any::<bool>(),
        edits in prop::collection::vec(edits(), 1..4),
    ) {
        let seed = if base {
            shipped_config()
        } else {
            toml::to_string(&RetargetConfig::default()).unwrap()
        };
        config_oracle::check_text(&mutate(&seed, &edits));
    }

    #[test]
    fn mutated_model_files_load_with_finite_kinematics_or_fail(
        edits in prop::collection::vec(edits(), 1..4),
    ) {
        config_oracle::check_text(&mutate(ORCA_V1_RIGHT_TOML, &edits));
    }

    #[test]
    fn mutated_embodiment_catalogs_load_and_retarget_or_fail(
        edits in prop::collection::vec(edits(), 1..4),
    ) {
        config_oracle::check_text(&mutate(EMBODIMENTS_TOML, &edits));
    }
}

/// The reference URDF and the shipped import file, or `None` (skip) without reference data.
fn reference_urdf() -> Option<&'static (String, UrdfImport)> {
    static URDF: OnceLock<Option<(String, UrdfImport)>> = OnceLock::new();
    URDF.get_or_init(|| {
        #[derive(serde::Deserialize)]
        struct ImportFile {
            strip_prefix: String,
            frames: FrameSpec,
        }
        let path = common::reference_file("fuzz_config::urdf", "orcahand_v1_right.urdf")?;
        let urdf = std::fs::read_to_string(path).unwrap();
        let import: ImportFile = toml::from_str(
            &std::fs::read_to_string(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../launch_configs/hands/orca_v1_right_urdf.toml"
            ))
            .unwrap(),
        )
        .unwrap();
        Some((
            urdf,
            UrdfImport {
                strip_prefix: import.strip_prefix,
                frames: import.frames,
            },
        ))
    })
    .as_ref()
}

/// One edit of a URDF's text.
#[derive(Debug, Clone)]
enum UrdfEdit {
    /// Replace the n-th number in the document.
    Number(Index, &'static str),
    /// Change one byte.
    Byte(Index, u8),
    /// Cut the text.
    Truncate(Index),
    /// Remove a range of bytes (a tag, an attribute, half of each).
    Remove(Index, usize),
}

fn urdf_edits() -> impl Strategy<Value = UrdfEdit> {
    let numbers = prop::sample::select(vec![
        "nan", "inf", "-inf", "1e308", "-1e308", "0", "-0", "1e-320", "1e9", "-", "", "1 2",
        "0x10", "3.14159", "-3",
    ]);
    prop_oneof![
        6 => (any::<Index>(), numbers).prop_map(|(i, n)| UrdfEdit::Number(i, n)),
        2 => (any::<Index>(), any::<u8>()).prop_map(|(i, b)| UrdfEdit::Byte(i, b)),
        1 => any::<Index>().prop_map(UrdfEdit::Truncate),
        1 => (any::<Index>(), 1usize..200).prop_map(|(i, n)| UrdfEdit::Remove(i, n)),
    ]
}

fn edit_urdf(text: &str, edits: &[UrdfEdit]) -> String {
    let mut bytes = text.as_bytes().to_vec();
    for edit in edits {
        let len = bytes.len();
        match edit {
            UrdfEdit::Number(i, replacement) => {
                // Numbers: maximal runs of digits, '.', '-', 'e' starting with a digit or '-'.
                let starts: Vec<usize> = (0..len)
                    .filter(|&k| {
                        (bytes[k].is_ascii_digit() || bytes[k] == b'-')
                            && (k == 0 || matches!(bytes[k - 1], b'"' | b' '))
                    })
                    .collect();
                if starts.is_empty() {
                    continue;
                }
                let start = starts[i.index(starts.len())];
                let end = (start..len)
                    .find(|&k| !matches!(bytes[k], b'0'..=b'9' | b'.' | b'-' | b'e' | b'E' | b'+'))
                    .unwrap_or(len);
                bytes.splice(start..end, replacement.bytes());
            }
            UrdfEdit::Byte(i, b) if len > 0 => bytes[i.index(len)] = *b,
            UrdfEdit::Truncate(i) => bytes.truncate(i.index(len + 1)),
            UrdfEdit::Remove(i, n) if len > 0 => {
                let at = i.index(len);
                bytes.drain(at..(at + n).min(len));
            }
            _ => {}
        }
    }
    String::from_utf8_lossy(&bytes).into_owned()
}

proptest! {
    #![proptest_config(budget(300))]

    #[test]
    fn mutated_urdfs_import_with_finite_kinematics_or_fail(
        edits in prop::collection::vec(urdf_edits(), 1..4),
    ) {
        let Some((urdf, import)) = reference_urdf() else {
            return Ok(());
        };
        config_oracle::check_urdf(&edit_urdf(urdf, &edits), import);
    }
}
