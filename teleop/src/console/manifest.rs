//! The session manifest: what a session is (task, embodiment, user, operator, plan) and every
//! trial it ran, with its file and result. Written atomically after every change, so a crash
//! loses nothing the manifest had said, and a session resumes from it.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::ConsoleError;
use crate::atomic_file::write_atomically;

/// The manifest's format name.
pub const MANIFEST_FORMAT: &str = "pomdar-session/1";

/// The manifest's file name in the session directory.
pub const MANIFEST_FILE: &str = "session.json";

/// What became of a trial.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TrialStatus {
    /// Logged and scored: it counts in the series.
    Scored,
    /// Logged but not scorable (the reason is kept): it is run again.
    Unscorable,
    /// Set aside by the operator (redo): kept as `FILE.redone`, run again.
    Redone,
    /// Cut short by quit, Ctrl-C or a crash: kept as `FILE.interrupted`, run again.
    Interrupted,
}

impl TrialStatus {
    /// Whether the trial takes its place in the series (is not run again).
    pub fn counts(self) -> bool {
        self == TrialStatus::Scored
    }
}

/// One trial of the session.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ManifestTrial {
    /// The log's file name in the session directory (as it is now).
    pub file: String,
    /// A practice trial (not in the series' mean).
    pub practice: bool,
    /// 1-based index among the practice or the recorded trials.
    pub index: u32,
    /// What became of it.
    pub status: TrialStatus,
    /// `completed`, `aborted` or `timed_out` (scored trials).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub outcome: Option<String>,
    /// Trial time, s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time_s: Option<f64>,
    /// Progress in the task's unit.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub progress: Option<f64>,
    /// Correctness in [0, 1].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub correctness: Option<f64>,
    /// 0.8·correctness + 0.2·speed, with a baseline.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub score: Option<f64>,
    /// Why it is not scored, or other remarks.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
}

/// The session.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// [`MANIFEST_FORMAT`].
    pub format: String,
    /// Task ID.
    pub task: String,
    /// Embodiment.
    pub embodiment: String,
    /// The user wearing the glove.
    pub user: String,
    /// The operator.
    pub operator: String,
    /// Practice trials planned.
    pub practice_planned: u32,
    /// Recorded trials planned.
    pub trials_planned: u32,
    /// The calibration profile in use (path), if any.
    pub calibration_profile: Option<String>,
    /// The station configuration's digest (as in each trial's metadata).
    pub config_digest: String,
    /// The baseline file, if any.
    pub baseline: Option<String>,
    /// When the session was created and last changed (UTC, `YYYYMMDDTHHMMSSZ`).
    pub created_utc: String,
    /// Last change.
    pub updated_utc: String,
    /// How many times the session was (re)started.
    pub runs: u32,
    /// Trials in the order they were run.
    pub trials: Vec<ManifestTrial>,
    /// Notes given between trials.
    #[serde(default)]
    pub notes: Vec<String>,
}

impl Manifest {
    /// Trials of a kind that count.
    pub fn done(&self, practice: bool) -> u32 {
        let n = self
            .trials
            .iter()
            .filter(|t| t.practice == practice && t.status.counts())
            .count();
        u32::try_from(n).unwrap_or(u32::MAX)
    }

    /// The next trial to run, `(practice, index)`, or `None` when the plan is done.
    pub fn next_slot(&self) -> Option<(bool, u32)> {
        let practice = self.done(true);
        if practice < self.practice_planned {
            return Some((true, practice + 1));
        }
        let recorded = self.done(false);
        (recorded < self.trials_planned).then_some((false, recorded + 1))
    }

    /// Attempts already made at a slot (any status).
    pub fn attempts(&self, practice: bool, index: u32) -> usize {
        self.trials
            .iter()
            .filter(|t| t.practice == practice && t.index == index)
            .count()
    }

    /// Scores (or correctness, without a baseline) of the counted recorded trials.
    pub fn series(&self) -> Vec<f64> {
        self.trials
            .iter()
            .filter(|t| !t.practice && t.status.counts())
            .filter_map(|t| t.score.or(t.correctness))
            .collect()
    }

    /// Reads a manifest; errors name the file.
    pub fn load(path: &Path) -> Result<Manifest, ConsoleError> {
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
        Ok(manifest)
    }

    /// Writes the manifest atomically.
    pub fn save(&self, path: &Path) -> Result<(), ConsoleError> {
        let mut text =
            serde_json::to_string_pretty(self).map_err(|source| ConsoleError::EncodeManifest {
                path: path.to_path_buf(),
                source,
            })?;
        text.push('\n');
        Ok(write_atomically(path, text)?)
    }
}

/// An empty manifest for `task` with `practice` + `trials` planned (tests).
#[cfg(test)]
pub(crate) fn test_manifest(task: &str, practice: u32, trials: u32) -> Manifest {
    Manifest {
        format: MANIFEST_FORMAT.into(),
        task: task.into(),
        embodiment: "orca_full".into(),
        user: "u".into(),
        operator: "o".into(),
        practice_planned: practice,
        trials_planned: trials,
        calibration_profile: None,
        config_digest: String::new(),
        baseline: None,
        created_utc: String::new(),
        updated_utc: String::new(),
        runs: 1,
        trials: vec![],
        notes: vec![],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn trial(practice: bool, index: u32, status: TrialStatus, score: Option<f64>) -> ManifestTrial {
        ManifestTrial {
            file: format!("t{index}.mcap"),
            practice,
            index,
            status,
            outcome: None,
            time_s: None,
            progress: None,
            correctness: Some(0.5),
            score,
            notes: vec![],
        }
    }

    fn manifest(trials: Vec<ManifestTrial>) -> Manifest {
        Manifest {
            trials,
            ..test_manifest("V1", 1, 2)
        }
    }

    #[test]
    fn the_next_slot_skips_counted_trials_and_repeats_set_aside_ones() {
        assert_eq!(manifest(vec![]).next_slot(), Some((true, 1)));
        let m = manifest(vec![
            trial(true, 1, TrialStatus::Scored, None),
            trial(false, 1, TrialStatus::Scored, Some(0.9)),
            trial(false, 2, TrialStatus::Interrupted, None),
        ]);
        assert_eq!(m.next_slot(), Some((false, 2)));
        assert_eq!(m.attempts(false, 2), 1);
        assert_eq!(m.series(), vec![0.9]);
        let mut done = m.clone();
        done.trials.push(trial(false, 2, TrialStatus::Scored, None));
        assert_eq!(done.next_slot(), None);
        assert_eq!(done.series(), vec![0.9, 0.5]);
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
