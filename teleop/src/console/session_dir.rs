//! A session's directory: its manifest, created or resumed, and the trial logs a crash left
//! as `.part` files, recovered and set aside as interrupted before the session goes on.

use std::path::{Path, PathBuf};

use crate::mcap_log::recover;
use crate::utc_date::{compact_utc, now_unix_s};

use super::ConsoleError;
use super::manifest::{MANIFEST_FILE, MANIFEST_FORMAT, Manifest, ManifestTrial, TrialStatus};

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

/// The session directory of a plan under `root`: `ROOT/<user>/<embodiment>/<task>`.
pub fn session_dir(root: &Path, plan: &SessionPlan) -> PathBuf {
    root.join(&plan.user)
        .join(&plan.embodiment)
        .join(&plan.task)
}

/// Opens the session in `dir`: resumes its manifest (checking it is the same task, embodiment
/// and user) or starts a new one. `.part` logs left by a crash are recovered to
/// `NAME.mcap.interrupted` and entered as interrupted trials. Returns the manifest and what
/// was done, for the operator.
pub fn open_session(
    dir: &Path,
    plan: &SessionPlan,
) -> Result<(Manifest, Vec<String>), ConsoleError> {
    std::fs::create_dir_all(dir).map_err(|source| ConsoleError::CreateSessionDir {
        dir: dir.to_path_buf(),
        source,
    })?;
    let path = dir.join(MANIFEST_FILE);
    let now = compact_utc(now_unix_s());
    let mut said = Vec::new();
    let mut manifest = if path.exists() {
        let mut m = Manifest::load(&path)?;
        for (field, found, asked) in [
            ("task", &m.task, &plan.task),
            ("embodiment", &m.embodiment, &plan.embodiment),
            ("user", &m.user, &plan.user),
        ] {
            if found != asked {
                return Err(ConsoleError::OtherSession {
                    manifest: path,
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
            said.push(
                "the station configuration differs from the session's earlier runs".to_string(),
            );
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
        m
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
    manifest.updated_utc = now;
    manifest.save(&path)?;
    Ok((manifest, said))
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

fn recover_parts(dir: &Path, manifest: &mut Manifest) -> Result<Vec<String>, ConsoleError> {
    let listed = std::fs::read_dir(dir).map_err(|source| ConsoleError::ListSessionDir {
        dir: dir.to_path_buf(),
        source,
    })?;
    let mut parts: Vec<PathBuf> = listed
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.to_string_lossy().ends_with(".mcap.part"))
        .collect();
    parts.sort();
    let mut said = Vec::new();
    for part in parts {
        let name = part
            .file_name()
            .map(|n| n.to_string_lossy().to_string())
            .unwrap_or_default();
        let log = name.trim_end_matches(".part").to_string();
        let Some((practice, index)) = slot_of(&log, &manifest.task) else {
            said.push(format!(
                "left {name} alone: not a trial log of this session"
            ));
            continue;
        };
        let aside = format!("{log}.interrupted");
        let (file, note) = match recover(&part, &dir.join(&aside)) {
            Ok(report) => {
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
        manifest.trials.push(ManifestTrial {
            file,
            practice,
            index,
            status: TrialStatus::Interrupted,
            outcome: None,
            time_s: None,
            progress: None,
            correctness: None,
            score: None,
            notes: vec![note],
        });
    }
    Ok(said)
}

#[cfg(test)]
mod tests {
    use super::*;

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
