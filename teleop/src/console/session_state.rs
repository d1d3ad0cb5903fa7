//! The trial console's session while it runs: its state machine, the station's last health,
//! the setting shown, and the session's files (the manifest, trials set aside, the report once
//! the plan is complete, the summary printed at the end).

use std::collections::BTreeMap;
use std::path::PathBuf;

use station::StationConfig;

use super::health::Health;
use super::manifest::{ManifestFile, TrialStatus};
use super::message_log::MessageLog;
use super::session_error::error_chain;
use super::session_report::write_session_report;
use super::test_pause::test_pause;
use super::trial_flow::{Slot, TrialFlow, TrialPhase};
use super::view::SessionInfo;
use crate::disk_wait::without_holding_the_runtime;
use crate::score::score_inputs::ScoringInputs;
use crate::utc_date::{compact_utc, now_unix_s};

/// The session: its state machine, the station's last health, what is shown all along and
/// the files.
pub(super) struct Session {
    pub(super) flow: TrialFlow,
    pub(super) health: Health,
    pub(super) info: SessionInfo,
    /// The baseline, catalog and rules each trial is scored with.
    pub(super) inputs: ScoringInputs,
    /// The session directory and its manifest.
    pub(super) dir: PathBuf,
    pub(super) manifest_path: PathBuf,
    /// Whether the complete session's report is written.
    pub(super) report_written: bool,
    /// The console's messages, kept in the session directory.
    pub(super) message_log: MessageLog,
    /// The station's configuration (the topics and limits each trial is reviewed with).
    pub(super) config: StationConfig,
}

impl Session {
    /// The trial log's metadata.
    pub(super) fn trial_metadata(&self, slot: &Slot) -> BTreeMap<String, String> {
        let flow = &self.flow;
        BTreeMap::from([
            ("task".to_string(), flow.manifest.task.clone()),
            ("user".to_string(), flow.manifest.user.clone()),
            ("operator".to_string(), flow.manifest.operator.clone()),
            (
                "calibration_profile".to_string(),
                flow.manifest
                    .calibration_profile
                    .clone()
                    .unwrap_or_else(|| "none".into()),
            ),
            ("trial_index".to_string(), slot.index.to_string()),
            ("practice".to_string(), slot.practice.to_string()),
            ("session".to_string(), self.dir.display().to_string()),
            ("source".to_string(), "pomdar trial".to_string()),
        ])
    }

    pub(super) fn save_manifest(&mut self) {
        self.flow.manifest.updated_utc = compact_utc(now_unix_s());
        if let Err(e) = self.flow.manifest.save(&self.manifest_path) {
            self.flow
                .say(format!("error: cannot save the manifest: {e:#}"));
        }
        test_pause("the manifest saved");
    }

    /// A trial set aside: its file renamed.
    pub(super) fn set_aside(&mut self, from: &str, to: &str) {
        if let Err(e) = std::fs::rename(self.dir.join(from), self.dir.join(to)) {
            self.flow
                .say(format!("error: cannot rename {from} to {to}: {e}"));
        }
    }

    /// Writes the session's report once the plan is complete (again after a trial redone).
    pub(super) fn write_report_once_complete(&mut self) {
        if *self.flow.phase() != TrialPhase::Complete {
            // A trial redone after the plan was complete: the report is written again.
            self.report_written = false;
        } else if !self.report_written {
            self.report_written = true;
            test_pause("the session complete: writing its report");
            let written = without_holding_the_runtime(|| {
                write_session_report(&self.dir, &self.flow, &self.inputs)
            });
            match written {
                Ok(path) => self
                    .flow
                    .say(format!("session complete: report in {}", path.display())),
                Err(e) => self.flow.say(format!(
                    "error: cannot write the session report: {}",
                    error_chain(&e)
                )),
            }
        }
    }

    /// The session's state on stdout after the console: trials done, trials not scored,
    /// whether it can be resumed.
    pub(super) fn print_summary(&self) {
        let m = &self.flow.manifest;
        println!(
            "session {}: {} of {} practice and {} of {} recorded trials done; manifest {}",
            self.dir.display(),
            m.done(true),
            m.practice_planned,
            m.done(false),
            m.trials_planned,
            self.manifest_path.display()
        );
        for trial in m.trials.iter().filter(|t| t.status != TrialStatus::Scored) {
            println!("  {}: {:?}", trial.file, trial.status);
        }
        if m.next_slot().is_some() {
            println!("not complete: run the same command again to resume");
        }
    }
}
