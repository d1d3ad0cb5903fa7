//! Calibration profiles on disk: loading one for the station (errors name the file and the
//! key), the one-line description the station prints, and writing a new one atomically
//! (`FILE.part`, fsync, rename), so a profile is either the old one or the complete new one.

use std::io::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Context as _;
use calibration::CalibrationProfile;
use retarget::{HandModel, KeypointLayout};

/// Read, parse and validate the profile at `path` and check that it was made for `model` and
/// `layout`; errors name the file (and the key, from the calibration crate's error).
pub fn load_profile(
    path: &Path,
    model: &HandModel,
    layout: KeypointLayout,
) -> anyhow::Result<CalibrationProfile> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read calibration profile {}", path.display()))?;
    let profile = CalibrationProfile::from_toml_str(&text)
        .map_err(|e| anyhow::anyhow!("calibration profile {}: {e}", path.display()))?;
    profile
        .check_fits(model, layout)
        .map_err(|e| anyhow::anyhow!("calibration profile {}: {e}", path.display()))?;
    Ok(profile)
}

/// One line: who, when, and the transform (scale, roll/pitch/yaw in degrees).
pub fn describe(profile: &CalibrationProfile) -> String {
    let p = &profile.parameters;
    format!(
        "calibration profile: user {}, date {}, scale {:.3}, roll {:.1}°, pitch {:.1}°, yaw {:.1}°",
        profile.user,
        profile.date,
        p.scale,
        p.roll_rad.to_degrees(),
        p.pitch_rad.to_degrees(),
        p.yaw_rad.to_degrees()
    )
}

/// `path` with `.part` appended.
fn part_path(path: &Path) -> PathBuf {
    let mut name = path.as_os_str().to_os_string();
    name.push(".part");
    PathBuf::from(name)
}

/// Write `text` to `path` atomically: `path.part`, fsync, rename over `path`, fsync of the
/// directory. Creates the directory if needed. On failure the `.part` is removed and `path`
/// is untouched.
pub fn write_atomically(path: &Path, text: &str) -> anyhow::Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    std::fs::create_dir_all(&dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let part = part_path(path);
    let written = (|| -> std::io::Result<()> {
        let mut file = std::fs::File::create(&part)?;
        file.write_all(text.as_bytes())?;
        file.sync_all()?;
        drop(file);
        std::fs::rename(&part, path)?;
        // Make the rename durable too (best effort: not every platform opens directories).
        if let Ok(d) = std::fs::File::open(&dir) {
            d.sync_all().ok();
        }
        Ok(())
    })();
    if let Err(e) = written {
        std::fs::remove_file(&part).ok();
        return Err(e).with_context(|| format!("cannot write {}", path.display()));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    #[test]
    fn atomic_writes_replace_the_file_and_leave_no_part() {
        let dir = std::env::temp_dir().join(format!("pomdar-profile-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        let path = dir.join("sub/alice.toml");
        write_atomically(&path, "a = 1\n").unwrap();
        write_atomically(&path, "a = 2\n").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "a = 2\n");
        assert!(!part_path(&path).exists());
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn a_missing_profile_is_named() {
        let err = load_profile(
            Path::new("/nonexistent/bob.toml"),
            &HandModel::orca_v1_right(),
            KeypointLayout::Lab22,
        )
        .unwrap_err();
        assert!(
            format!("{err:#}").contains("/nonexistent/bob.toml"),
            "{err:#}"
        );
    }
}
