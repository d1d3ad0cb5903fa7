//! A session's directory: its manifest, created or resumed, and the trial logs a crash left
//! as `.part` files, recovered and set aside as interrupted before the session goes on; trial
//! logs a crash left out of the manifest (finished or set aside just before the manifest was
//! saved) are entered in it.

use std::path::{Path, PathBuf};

use scoring::TrialScore;

use crate::mcap_log::recover;
use crate::utc_date::{compact_utc, now_unix_s};

use super::ConsoleError;
use super::manifest::{
    MANIFEST_FILE, MANIFEST_FORMAT, Manifest, ManifestFile, ManifestTrial, TrialStatus,
};
use super::test_pause::test_pause;
use super::trial_flow::{Slot, logged_trial};

/// What identifies a session and what it plans.
#[derive(Debug, Clone, PartialEq)]
pub struct SessionPlan {
    /// Task ID.
    pub task: String,
    /// Embodiment.
    pub embodiment: String,
    /// User.
    pub user: String,
    /// Operator.
    pub operator: String,
    /// Practice trials.
    pub practice: u32,
    /// Recorded trials.
    pub trials: u32,
    /// Calibration profile (path).
    pub calibration_profile: Option<String>,
    /// Station configuration digest.
    pub config_digest: String,
    /// Baseline file.
    pub baseline: Option<String>,
}

pub use super::manifest::check_name;

/// The session directory of a plan under `root`: `ROOT/<user>/<embodiment>/<task>`.
pub fn session_dir(root: &Path, plan: &SessionPlan) -> PathBuf {
    root.join(&plan.user)
        .join(&plan.embodiment)
        .join(&plan.task)
}

/// Scores a finished trial log (the console's baseline, catalog and rules); `Err` says why it
/// cannot be scored.
pub type ScoreLog<'a> = &'a dyn Fn(&Path) -> Result<TrialScore, String>;

/// Opens the session in `dir`: resumes its manifest (checking it is the same task, embodiment
/// and user) or starts a new one. `.part` logs left by a crash are recovered to
/// `NAME.mcap.interrupted` and entered as interrupted trials; trial logs a crash left out of
/// the manifest (finished, or set aside, just before the manifest was to be saved) are
/// entered too, a finished one scored with `score`. Returns the manifest and what was done,
/// for the operator.
pub fn open_session(
    dir: &Path,
    plan: &SessionPlan,
    score: ScoreLog<'_>,
) -> Result<(Manifest, Vec<String>), ConsoleError> {
    std::fs::create_dir_all(dir).map_err(|source| ConsoleError::CreateSessionDir {
        dir: dir.to_path_buf(),
        source,
    })?;
    let path = dir.join(MANIFEST_FILE);
    let now = compact_utc(now_unix_s());
    let mut said = Vec::new();
    let mut manifest = if path.exists() {
        resume_manifest(&path, plan, &mut said)?
    } else {
        Manifest {
            format: MANIFEST_FORMAT.to_string(),
            task: plan.task.clone(),
            embodiment: plan.embodiment.clone(),
            user: plan.user.clone(),
            operator: plan.operator.clone(),
            practice_planned: plan.practice,
            trials_planned: plan.trials,
            calibration_profile: plan.calibration_profile.clone(),
            config_digest: plan.config_digest.clone(),
            baseline: plan.baseline.clone(),
            created_utc: now.clone(),
            updated_utc: now.clone(),
            runs: 1,
            trials: Vec::new(),
            notes: Vec::new(),
        }
    };
    said.extend(recover_parts(dir, &mut manifest)?);
    said.extend(enter_unlisted_logs(dir, &mut manifest, score)?);
    manifest.updated_utc = now;
    test_pause("opening the session: saving the manifest");
    manifest.save(&path)?;
    Ok((manifest, said))
}

/// The manifest at `path`, checked against `plan` (the same task, embodiment and user) and
/// updated to it; what changed is said.
fn resume_manifest(
    path: &Path,
    plan: &SessionPlan,
    said: &mut Vec<String>,
) -> Result<Manifest, ConsoleError> {
    let mut m = Manifest::load(path)?;
    for (field, found, asked) in [
        ("task", &m.task, &plan.task),
        ("embodiment", &m.embodiment, &plan.embodiment),
        ("user", &m.user, &plan.user),
    ] {
        if found != asked {
            return Err(ConsoleError::OtherSession {
                manifest: path.to_path_buf(),
                field,
                found: found.clone(),
                asked: asked.clone(),
            });
        }
    }
    if m.practice_planned != plan.practice || m.trials_planned != plan.trials {
        said.push(format!(
            "plan changed from {} practice + {} recorded to {} + {}",
            m.practice_planned, m.trials_planned, plan.practice, plan.trials
        ));
    }
    if m.config_digest != plan.config_digest {
        said.push("the station configuration differs from the session's earlier runs".to_string());
    }
    m.practice_planned = plan.practice;
    m.trials_planned = plan.trials;
    m.operator.clone_from(&plan.operator);
    m.calibration_profile.clone_from(&plan.calibration_profile);
    m.config_digest.clone_from(&plan.config_digest);
    m.baseline.clone_from(&plan.baseline);
    m.runs += 1;
    said.push(format!(
        "resumed {}: {} of {} practice and {} of {} recorded trials done",
        path.display(),
        m.done(true),
        m.practice_planned,
        m.done(false),
        m.trials_planned
    ));
    Ok(m)
}

/// `(practice, index)` of a trial log name `TASK-p03.mcap` / `TASK-t12-a2.mcap`.
fn slot_of(file: &str, task: &str) -> Option<(bool, u32)> {
    let rest = file.strip_prefix(task)?.strip_prefix('-')?;
    let rest = rest.strip_suffix(".mcap")?;
    let practice = match rest.chars().next()? {
        'p' => true,
        't' => false,
        _ => return None,
    };
    let digits: String = rest[1..].chars().take_while(char::is_ascii_digit).collect();
    Some((practice, digits.parse().ok()?))
}

/// The names of the files in `dir`, sorted.
fn file_names(dir: &Path) -> Result<Vec<String>, ConsoleError> {
    let listed = std::fs::read_dir(dir).map_err(|source| ConsoleError::ListSessionDir {
        dir: dir.to_path_buf(),
        source,
    })?;
    let mut names: Vec<String> = listed
        .flatten()
        .filter(|e| e.file_type().is_ok_and(|t| t.is_file()))
        .map(|e| e.file_name().to_string_lossy().to_string())
        .collect();
    names.sort();
    Ok(names)
}

/// Whether `a` and `b` are the same file (hard links to one inode).
fn same_file(a: &Path, b: &Path) -> bool {
    use std::os::unix::fs::MetadataExt as _;
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

/// What a crash left of a trial log `NAME.mcap.part`: a recording cut short, or the leftover
/// of a step that had done its work (the finished log linked to its name, an earlier
/// recovery written) before the `.part` was removed. `None`: the `.part` is to be recovered.
fn part_leftover(dir: &Path, name: &str, log: &str, aside: &str) -> Option<String> {
    let part = dir.join(name);
    if same_file(&part, &dir.join(log)) {
        // The station's finish had linked the complete log to its name: the same file.
        std::fs::remove_file(&part).ok();
        return Some(format!(
            "{name}: the trial's log was finished ({log}) just before the console stopped; its .part name is removed"
        ));
    }
    if dir.join(aside).exists() {
        // An earlier resume recovered it and stopped before removing the .part.
        std::fs::remove_file(dir.join(format!("{aside}.recovering"))).ok();
        std::fs::remove_file(&part).ok();
        return Some(format!(
            "{name}: already recovered as {aside}; the .part is removed"
        ));
    }
    // A recovery cut short leaves its output's `.recovering`: it is written again.
    std::fs::remove_file(dir.join(format!("{aside}.recovering"))).ok();
    None
}

fn recover_parts(dir: &Path, manifest: &mut Manifest) -> Result<Vec<String>, ConsoleError> {
    let parts: Vec<String> = file_names(dir)?
        .into_iter()
        .filter(|n| n.ends_with(".mcap.part"))
        .collect();
    let mut said = Vec::new();
    for name in parts {
        let part = dir.join(&name);
        let log = name.trim_end_matches(".part").to_string();
        let Some((practice, index)) = slot_of(&log, &manifest.task) else {
            said.push(format!(
                "left {name} alone: not a trial log of this session"
            ));
            continue;
        };
        let aside = format!("{log}.interrupted");
        if let Some(note) = part_leftover(dir, &name, &log, &aside) {
            said.push(note);
            continue;
        }
        let (file, note) = match recover(&part, &dir.join(&aside)) {
            Ok(report) => {
                test_pause(&format!("opening the session: {name} recovered to {aside}"));
                std::fs::remove_file(&part).ok();
                (
                    aside,
                    format!(
                        "interrupted (the console stopped mid-trial); recovered {} messages",
                        report.message_count
                    ),
                )
            }
            Err(e) => {
                let kept = format!("{name}.interrupted");
                let to = dir.join(&kept);
                if let Err(source) = std::fs::rename(&part, &to) {
                    return Err(ConsoleError::SetAside { part, to, source });
                }
                (kept, format!("interrupted; could not be recovered: {e}"))
            }
        };
        said.push(format!(
            "{name}: {note}; kept as {file}, the trial runs again"
        ));
        manifest.trials.push(set_aside_trial(
            file,
            Slot { practice, index },
            TrialStatus::Interrupted,
            note,
        ));
    }
    Ok(said)
}

/// A trial set aside (interrupted or redone), with a note.
fn set_aside_trial(file: String, slot: Slot, status: TrialStatus, note: String) -> ManifestTrial {
    ManifestTrial {
        file,
        practice: slot.practice,
        index: slot.index,
        status,
        outcome: None,
        time_s: None,
        progress: None,
        correctness: None,
        score: None,
        notes: vec![note],
    }
}

/// Trial logs in `dir` the manifest does not name: a crash came after the step that made
/// them and before the manifest was saved. A finished log (`NAME.mcap`: the station had
/// finished it) is scored and entered; a set-aside one (`.interrupted`, `.redone`) is entered
/// as such, or, when the manifest names it by its former name, that entry is renamed.
fn enter_unlisted_logs(
    dir: &Path,
    manifest: &mut Manifest,
    score: ScoreLog<'_>,
) -> Result<Vec<String>, ConsoleError> {
    let mut said = Vec::new();
    for name in file_names(dir)? {
        if manifest.trials.iter().any(|t| t.file == name) {
            continue;
        }
        let (log, status) = if let Some(log) = name.strip_suffix(".interrupted") {
            (log.trim_end_matches(".part"), TrialStatus::Interrupted)
        } else if let Some(log) = name.strip_suffix(".redone") {
            (log, TrialStatus::Redone)
        } else {
            (name.as_str(), TrialStatus::Scored)
        };
        let Some((practice, index)) = slot_of(log, &manifest.task) else {
            continue;
        };
        let slot = Slot { practice, index };
        if status == TrialStatus::Scored {
            let trial = logged_trial(&name, slot, None, score(&dir.join(&name)));
            said.push(format!(
                "{name}: finished just before the console stopped; entered as {:?}",
                trial.status
            ));
            manifest.trials.push(trial);
            continue;
        }
        let renamed = manifest
            .trials
            .iter_mut()
            .find(|t| t.file == log && !dir.join(log).exists());
        if let Some(trial) = renamed {
            trial.file.clone_from(&name);
            trial.status = status;
            said.push(format!(
                "{log} was set aside as {name} just before the console stopped"
            ));
        } else {
            said.push(format!(
                "{name}: set aside just before the console stopped; entered as {status:?}"
            ));
            let note = "set aside just before the console stopped; entered when it resumed";
            manifest.trials.push(set_aside_trial(
                name.clone(),
                slot,
                status,
                note.to_string(),
            ));
        }
    }
    Ok(said)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mcap_log::{TrialWriter, TrialWriterOptions};
    use serde_json::json;

    fn plan() -> SessionPlan {
        SessionPlan {
            task: "V1".into(),
            embodiment: "orca_full".into(),
            user: "u".into(),
            operator: "o".into(),
            practice: 0,
            trials: 3,
            calibration_profile: None,
            config_digest: String::new(),
            baseline: None,
        }
    }

    fn not_scored(_: &Path) -> Result<TrialScore, String> {
        Err("not scored here".into())
    }

    /// A trial log cut short as a kill leaves it: `NAME.part` with its start event.
    fn killed_log(dir: &Path, name: &str) {
        let mut writer = TrialWriter::create(&dir.join(name), TrialWriterOptions::default())
            .unwrap_or_else(|e| panic!("{e}"));
        let started = writer.write_event(1_000, &json!({"event": "start"}));
        assert!(started.is_ok());
    }

    fn files(m: &Manifest) -> Vec<(&str, TrialStatus)> {
        m.trials
            .iter()
            .map(|t| (t.file.as_str(), t.status))
            .collect()
    }

    #[test]
    fn a_resume_enters_what_a_kill_left_between_a_step_and_the_manifest() {
        let dir = std::env::temp_dir().join(format!("pomdar-session-dir-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        let opened = open_session(&dir, &plan(), &not_scored);
        assert!(opened.is_ok());
        // t01 finished (the station linked it to its name, the .part not yet removed), t02
        // recovered by a resume killed before it removed the .part, t03 recovered by one
        // killed mid-recovery, t03-a2's set-aside name the manifest missed.
        killed_log(&dir, "V1-t01.mcap");
        std::fs::hard_link(dir.join("V1-t01.mcap.part"), dir.join("V1-t01.mcap")).unwrap();
        killed_log(&dir, "V1-t02.mcap");
        assert!(
            recover(
                &dir.join("V1-t02.mcap.part"),
                &dir.join("V1-t02.mcap.interrupted")
            )
            .is_ok()
        );
        killed_log(&dir, "V1-t03.mcap");
        std::fs::write(dir.join("V1-t03.mcap.interrupted.recovering"), b"cut short").unwrap();
        std::fs::write(dir.join("V1-t03-a2.mcap.redone"), b"set aside").unwrap();
        let (manifest, said) = open_session(&dir, &plan(), &not_scored).unwrap();
        assert_eq!(
            files(&manifest),
            [
                ("V1-t03.mcap.interrupted", TrialStatus::Interrupted),
                ("V1-t01.mcap", TrialStatus::Unscorable),
                ("V1-t02.mcap.interrupted", TrialStatus::Interrupted),
                ("V1-t03-a2.mcap.redone", TrialStatus::Redone),
            ],
            "{said:?}"
        );
        let mut left: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .flatten()
            .map(|e| e.file_name().to_string_lossy().to_string())
            .collect();
        left.sort();
        assert_eq!(
            left,
            [
                "V1-t01.mcap",
                "V1-t02.mcap.interrupted",
                "V1-t03-a2.mcap.redone",
                "V1-t03.mcap.interrupted",
                "session.json"
            ]
        );
        // Entered once: a second resume finds nothing more.
        let (again, _) = open_session(&dir, &plan(), &not_scored).unwrap();
        assert_eq!(files(&again), files(&manifest));
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn names_are_checked_and_slots_parse() {
        assert!(check_name("--user", "alice_2").is_ok());
        assert_eq!(
            check_name("--user", "../x")
                .map_err(|e| e.to_string())
                .err()
                .as_deref(),
            Some(
                "--user \"../x\": use 1–64 letters, digits, '_', '-' or '.' (not starting with '.'); it names the session's files"
            )
        );
        assert!(check_name("--user", "").is_err());
        assert_eq!(slot_of("V1-p03.mcap", "V1"), Some((true, 3)));
        assert_eq!(slot_of("V1-t12-a2.mcap", "V1"), Some((false, 12)));
        assert_eq!(slot_of("G1-t01.mcap", "V1"), None);
        assert_eq!(slot_of("V1-x01.mcap", "V1"), None);
    }
}
