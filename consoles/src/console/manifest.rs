//! The session manifest's data: what a session is (task, embodiment, user, operator, plan) and
//! every trial it ran, with its file and result, and which trial log names a manifest may give.
//! Reading and writing it (atomically, after every change) is `teleop::console::manifest`.

use std::path::Path;

use serde::{Deserialize, Serialize};

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
}

/// The suffixes the console adds to a trial log's name: none (scored or unscorable),
/// `.redone` (set aside by the operator), `.interrupted` (cut short, recovered) and
/// `.part.interrupted` (cut short, not recoverable: the `.part` file kept as it was).
pub const TRIAL_FILE_SUFFIXES: [&str; 4] = ["", ".redone", ".interrupted", ".part.interrupted"];

/// Why `file` is not a trial log name the console writes for `task`, or `None` when it is:
/// `TASK-pNN[-aN].mcap` or `TASK-tNN[-aN].mcap` (NN: two or more digits), then one of
/// [`TRIAL_FILE_SUFFIXES`]. So no path separator, no `..` component, nothing absolute.
pub fn trial_file_problem(file: &str, task: &str) -> Option<String> {
    if file.contains(['/', '\\']) || file.contains('\0') {
        return Some("a path, not a file name (it contains a path separator)".into());
    }
    if file == ".." || file == "." {
        return Some("a directory, not a file name".into());
    }
    if Path::new(file).is_absolute() {
        return Some("an absolute path".into());
    }
    let Some(log) = TRIAL_FILE_SUFFIXES.iter().rev().find_map(|suffix| {
        file.strip_suffix(suffix)
            .filter(|rest| rest.ends_with(".mcap"))
    }) else {
        return Some("not a trial log (.mcap, or one set aside)".into());
    };
    let rest = log
        .strip_suffix(".mcap")
        .and_then(|r| r.strip_prefix(task))
        .and_then(|r| r.strip_prefix('-'));
    let Some(rest) = rest else {
        return Some(format!("not a trial log of task {task}"));
    };
    let (slot, attempt) = match rest.split_once("-a") {
        Some((slot, attempt)) => (slot, Some(attempt)),
        None => (rest, None),
    };
    let digits = |d: &str| !d.is_empty() && d.len() <= 10 && d.bytes().all(|b| b.is_ascii_digit());
    let slot_ok = slot
        .strip_prefix(['p', 't'])
        .is_some_and(|n| n.len() >= 2 && digits(n));
    if !slot_ok || !attempt.is_none_or(digits) {
        return Some("not a trial log name the console writes".into());
    }
    None
}

/// An empty manifest for `task` with `practice` + `trials` planned (tests).
#[cfg(any(test, feature = "test-support"))]
pub fn test_manifest(task: &str, practice: u32, trials: u32) -> Manifest {
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

/// A trial record of task V1: practice or recorded, its index, status and score (tests).
#[cfg(any(test, feature = "test-support"))]
pub fn test_trial(
    practice: bool,
    index: u32,
    status: TrialStatus,
    score: Option<f64>,
) -> ManifestTrial {
    ManifestTrial {
        file: format!("V1-{}{index:02}.mcap", if practice { 'p' } else { 't' }),
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

/// A manifest of task V1 with 1 + 2 trials planned, holding `trials` (tests).
#[cfg(any(test, feature = "test-support"))]
pub fn test_v1_manifest(trials: Vec<ManifestTrial>) -> Manifest {
    Manifest {
        trials,
        ..test_manifest("V1", 1, 2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use super::{test_trial as trial, test_v1_manifest as manifest};

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
    fn only_the_consoles_own_trial_log_names_are_taken() {
        for good in [
            "V1-p01.mcap",
            "V1-t12.mcap",
            "V1-t01-a2.mcap",
            "V1-t01.mcap.redone",
            "V1-p03-a3.mcap.interrupted",
            "V1-t101.mcap.part.interrupted",
        ] {
            assert_eq!(trial_file_problem(good, "V1"), None, "{good}");
        }
        for (bad, why) in [
            ("../../etc/passwd", "path separator"),
            ("/etc/passwd", "path separator"),
            ("..", "directory"),
            ("..\\x.mcap", "path separator"),
            ("V1-t01.mcap/../../x", "path separator"),
            ("G1-t01.mcap", "of task V1"),
            ("V1-x01.mcap", "console writes"),
            ("V1-t1.mcap", "console writes"),
            ("V1-t01-a.mcap", "console writes"),
            ("V1-t01.mcap.part", "not a trial log"),
            ("V1-t01.mcap.bak", "not a trial log"),
            ("session.json", "not a trial log"),
            ("", "not a trial log"),
        ] {
            let problem = trial_file_problem(bad, "V1").unwrap_or_default();
            assert!(problem.contains(why), "{bad}: {problem}");
        }
    }
}
