//! The session manifest's file: read, its names checked, and written atomically after every
//! change, so a crash loses nothing the manifest had said, and a session resumes from it. The
//! manifest's data is the core crate's (`consoles::console::manifest`, re-exported here).

use std::path::Path;

pub use consoles::console::manifest::{
    MANIFEST_FILE, MANIFEST_FORMAT, Manifest, ManifestTrial, TRIAL_FILE_SUFFIXES, TrialStatus,
    trial_file_problem,
};

use super::ConsoleError;
use crate::atomic_file::write_atomically;

/// A manifest's file: read and checked, written atomically. A trait because the manifest's type
/// is the core crate's; bring it into scope to call `Manifest::load` and `manifest.save`.
pub trait ManifestFile: Sized {
    /// Reads a manifest; errors name the file.
    fn load(path: &Path) -> Result<Self, ConsoleError>;

    /// Checks every name the manifest gives that becomes part of a path: the task (it names
    /// the trial logs) and each trial's file, which must be a trial log name this console
    /// writes for this task ([`trial_file_problem`]). `path` names the manifest in errors.
    fn check_names(&self, path: &Path) -> Result<(), ConsoleError>;

    /// Writes the manifest atomically.
    fn save(&self, path: &Path) -> Result<(), ConsoleError>;
}

impl ManifestFile for Manifest {
    fn load(path: &Path) -> Result<Manifest, ConsoleError> {
        let text = std::fs::read_to_string(path).map_err(|source| ConsoleError::ReadManifest {
            path: path.to_path_buf(),
            source,
        })?;
        let manifest: Manifest =
            serde_json::from_str(&text).map_err(|source| ConsoleError::NotAManifest {
                path: path.to_path_buf(),
                source,
            })?;
        if manifest.format != MANIFEST_FORMAT {
            return Err(ConsoleError::ManifestFormat {
                path: path.to_path_buf(),
                found: manifest.format,
                expected: MANIFEST_FORMAT,
            });
        }
        manifest.check_names(path)?;
        Ok(manifest)
    }

    fn check_names(&self, path: &Path) -> Result<(), ConsoleError> {
        let refuse = |field: String, value: &str, reason: String, allowed: &str| {
            Err(ConsoleError::ManifestName {
                path: path.to_path_buf(),
                field,
                value: value.to_string(),
                reason,
                allowed: allowed.to_string(),
            })
        };
        if check_name("task", &self.task).is_err() {
            return refuse(
                "task".into(),
                &self.task,
                "not a task name".into(),
                "1–64 letters, digits, '_', '-' or '.', not starting with '.'",
            );
        }
        for (i, trial) in self.trials.iter().enumerate() {
            if let Some(reason) = trial_file_problem(&trial.file, &self.task) {
                return refuse(
                    format!("trials[{i}].file"),
                    &trial.file,
                    reason,
                    &allowed_trial_files(&self.task),
                );
            }
        }
        Ok(())
    }

    fn save(&self, path: &Path) -> Result<(), ConsoleError> {
        let mut text =
            serde_json::to_string_pretty(self).map_err(|source| ConsoleError::EncodeManifest {
                path: path.to_path_buf(),
                source,
            })?;
        text.push('\n');
        Ok(write_atomically(path, text)?)
    }
}

/// The trial log names allowed for `task`, for a person.
fn allowed_trial_files(task: &str) -> String {
    format!(
        "{task}-pNN.mcap or {task}-tNN.mcap, with -aN after NN for a repeated attempt, \
         optionally followed by .redone, .interrupted or .part.interrupted; a plain file name \
         in the session directory"
    )
}

/// Checks a name used in file names and metadata: letters, digits, `_`, `-`, `.`.
pub fn check_name(flag: &str, value: &str) -> Result<(), ConsoleError> {
    let ok = !value.is_empty()
        && value.len() <= 64
        && !value.starts_with('.')
        && value
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.'));
    if !ok {
        return Err(ConsoleError::Name {
            flag: flag.to_string(),
            value: value.to_string(),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use consoles::console::manifest::{test_trial as trial, test_v1_manifest as manifest};

    #[test]
    fn a_tampered_manifest_is_refused_naming_file_field_and_rule() {
        let dir = std::env::temp_dir().join(format!("pomdar-manifest-bad-{}", std::process::id()));
        let path = dir.join(MANIFEST_FILE);
        let mut m = manifest(vec![
            trial(false, 1, TrialStatus::Scored, None),
            trial(false, 2, TrialStatus::Scored, None),
        ]);
        m.trials[0].file = "V1-t01.mcap".into();
        m.trials[1].file = "../other/V1-t02.mcap".into();
        assert!(m.save(&path).is_ok());
        let e = Manifest::load(&path).unwrap_err().to_string();
        assert!(e.starts_with(&path.display().to_string()), "{e}");
        assert!(
            e.contains("trials[1].file = \"../other/V1-t02.mcap\""),
            "{e}"
        );
        assert!(e.contains("allowed: V1-pNN.mcap or V1-tNN.mcap"), "{e}");
        let mut m = manifest(vec![]);
        m.task = "../V1".into();
        assert!(m.save(&path).is_ok());
        let e = Manifest::load(&path).unwrap_err().to_string();
        assert!(e.contains("task = \"../V1\""), "{e}");
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn round_trips_through_a_file_and_refuses_other_formats() {
        let dir = std::env::temp_dir().join(format!("pomdar-manifest-{}", std::process::id()));
        let path = dir.join(MANIFEST_FILE);
        let m = manifest(vec![trial(true, 1, TrialStatus::Redone, None)]);
        assert!(m.save(&path).is_ok());
        assert_eq!(Manifest::load(&path).ok(), Some(m.clone()));
        let mut other = m;
        other.format = "x".into();
        assert!(other.save(&path).is_ok());
        assert_eq!(
            Manifest::load(&path).map_err(|e| e.to_string()).err(),
            Some(format!(
                "{}: format \"x\", expected \"pomdar-session/1\"",
                path.display()
            ))
        );
        std::fs::write(&path, "{").unwrap();
        let e = Manifest::load(&path).unwrap_err().to_string();
        assert!(
            e.starts_with(&format!("{}: not a session manifest: ", path.display())),
            "{e}"
        );
        let missing = dir.join("missing.json");
        let e = Manifest::load(&missing).unwrap_err().to_string();
        assert!(
            e.starts_with(&format!(
                "cannot read the session manifest {}: ",
                missing.display()
            )),
            "{e}"
        );
        std::fs::remove_dir_all(&dir).ok();
    }
}
