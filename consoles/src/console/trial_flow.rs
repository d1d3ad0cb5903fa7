//! The timed-trial session as a state machine, without I/O: the operator's actions, the
//! station's health and the trial logs' results go in; what the shell must do (engage, start
//! or stop a trial log, log an event, save the manifest, set a file aside, quit) comes out as
//! [`Effect`]s. The POMDAR protocol: the practice trials first, then the recorded ones.
//!
//! A trial: `start` → countdown → running (marks, drops, notes go into its log) → `stop` (or
//! `abort`) → the log is finished, read back and scored → summary → the next trial. `redo`
//! sets a trial aside and runs its slot again; quit or Ctrl-C during a trial aborts it, sets it
//! aside as interrupted, and the session resumes at that slot.

use std::collections::VecDeque;

use scoring::{CorrectnessKind, GRASP_LEVELS, TrialScore};
use serde_json::json;

use super::action::Action;
use super::health::{Health, StartLimits};
use super::manifest::{Manifest, ManifestTrial, TrialStatus};

/// A trial's place in the plan.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Slot {
    /// A practice trial.
    pub practice: bool,
    /// 1-based index among its kind.
    pub index: u32,
}

impl Slot {
    /// `practice 2/5` or `trial 7/20`.
    pub fn label(&self, manifest: &Manifest) -> String {
        if self.practice {
            format!("practice {}/{}", self.index, manifest.practice_planned)
        } else {
            format!("trial {}/{}", self.index, manifest.trials_planned)
        }
    }
}

/// What happens once a trial's log is finished.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AfterLog {
    /// Score it and show the summary.
    Score,
    /// Set it aside (redo) and show the summary of the set-aside trial.
    Redo,
    /// Set it aside as interrupted, then quit.
    InterruptedQuit,
}

/// Where the session is.
#[derive(Debug, Clone, PartialEq)]
pub enum TrialPhase {
    /// Between trials.
    Idle,
    /// Counting down to a trial's start.
    Countdown {
        /// The trial.
        slot: Slot,
        /// When it starts, ns.
        ends_ns: i64,
    },
    /// A trial runs.
    Running {
        /// The trial.
        slot: Slot,
        /// Its log file name.
        file: String,
        /// When it started, ns.
        started_ns: i64,
    },
    /// The trial's log is being finished.
    Finishing {
        /// The trial.
        slot: Slot,
        /// Its log file name.
        file: String,
        /// Trial time, s (start → stop/abort, console clock).
        time_s: f64,
        /// Then.
        after: AfterLog,
    },
    /// Every planned trial is done.
    Complete,
    /// The console is quitting.
    Quitting,
}

/// What the shell must do.
#[derive(Debug, Clone, PartialEq)]
pub enum Effect {
    /// Engage the station.
    Engage,
    /// Disengage the station (clutch out).
    Disengage,
    /// Start a trial log `file` in the session directory.
    StartTrial {
        /// File name.
        file: String,
        /// The trial.
        slot: Slot,
    },
    /// Log a trial event.
    TrialEvent(serde_json::Value),
    /// Finish the trial log.
    StopTrial,
    /// Save the manifest.
    SaveManifest,
    /// Rename `from` to `to` in the session directory (a trial set aside).
    SetAside {
        /// Current file name.
        from: String,
        /// New file name.
        to: String,
    },
    /// Stop the console.
    Quit,
}

/// How many operator messages are kept for the screen.
const MESSAGES_KEPT: usize = 6;

/// The session.
#[derive(Debug, Clone)]
pub struct TrialFlow {
    /// The manifest (saved by the shell on [`Effect::SaveManifest`]).
    pub manifest: Manifest,
    kind: CorrectnessKind,
    countdown_ns: i64,
    limits: StartLimits,
    phase: TrialPhase,
    quit_armed: bool,
    /// Progress marked in the running trial, in the task's unit (grasp: the last level).
    progress: f64,
    drops: u32,
    /// The last trial logged (index in the manifest), for the summary.
    last: Option<usize>,
    messages: VecDeque<String>,
    said: u64,
    /// An engage asked for before the input was fresh: (asked at, last sent), ns.
    engage_pending: Option<(i64, i64)>,
    /// A start asked for while engaging or while the glove rate settles: asked at, ns.
    start_pending: Option<i64>,
}

/// How long a start waits for the station to be ready, ns.
const START_WAIT_NS: i64 = 10_000_000_000;

/// How long an engage waits for fresh glove input, ns.
const ENGAGE_WAIT_NS: i64 = 10_000_000_000;
/// How often a pending engage is asked of the station again, ns.
const ENGAGE_RESEND_NS: i64 = 200_000_000;

impl TrialFlow {
    /// A session over `manifest` (new or resumed) for a task scored by `kind`.
    pub fn new(
        manifest: Manifest,
        kind: CorrectnessKind,
        countdown_s: f64,
        limits: StartLimits,
    ) -> TrialFlow {
        let phase = if manifest.next_slot().is_none() {
            TrialPhase::Complete
        } else {
            TrialPhase::Idle
        };
        TrialFlow {
            manifest,
            kind,
            countdown_ns: (countdown_s * 1e9).round() as i64,
            limits,
            phase,
            quit_armed: false,
            progress: 0.0,
            drops: 0,
            last: None,
            messages: VecDeque::new(),
            said: 0,
            engage_pending: None,
            start_pending: None,
        }
    }

    /// Where the session is.
    pub fn phase(&self) -> &TrialPhase {
        &self.phase
    }

    /// The last trial logged, for the summary.
    pub fn last_trial(&self) -> Option<&ManifestTrial> {
        self.last.and_then(|i| self.manifest.trials.get(i))
    }

    /// Progress and drops marked in the running trial.
    pub fn marks(&self) -> (f64, u32) {
        (self.progress, self.drops)
    }

    /// The limits a trial start is held to.
    pub fn limits(&self) -> &StartLimits {
        &self.limits
    }

    /// The task's scoring kind.
    pub fn kind(&self) -> &CorrectnessKind {
        &self.kind
    }

    /// Recent messages for the operator, oldest first.
    pub fn messages(&self) -> impl Iterator<Item = &str> {
        self.messages.iter().map(String::as_str)
    }

    /// Adds a message for the operator.
    pub fn say(&mut self, text: impl Into<String>) {
        if self.messages.len() == MESSAGES_KEPT {
            self.messages.pop_front();
        }
        self.messages.push_back(text.into());
        self.said += 1;
    }

    /// How many messages were said so far.
    pub fn said(&self) -> u64 {
        self.said
    }

    fn file_name(&self, slot: Slot) -> String {
        let attempt = self.manifest.attempts(slot.practice, slot.index) + 1;
        let kind = if slot.practice { 'p' } else { 't' };
        let suffix = if attempt > 1 {
            format!("-a{attempt}")
        } else {
            String::new()
        };
        format!(
            "{}-{kind}{:02}{suffix}.mcap",
            self.manifest.task, slot.index
        )
    }

    /// Handles an operator action at `now_ns` with the station's latest `health`.
    pub fn act(&mut self, action: Action, health: &Health, now_ns: i64) -> Vec<Effect> {
        if !matches!(action, Action::Quit) {
            self.quit_armed = false;
        }
        let running = matches!(self.phase, TrialPhase::Running { .. });
        match action {
            Action::ToggleEngage if health.engaged() || self.engage_pending.is_some() => {
                self.disengage()
            }
            Action::ToggleEngage | Action::Engage => self.engage(health, now_ns),
            Action::Disengage => self.disengage(),
            Action::StartStop if running => self.stop(now_ns, AfterLog::Score, None),
            Action::StartStop | Action::Start => self.start(health, now_ns),
            Action::Stop if running => self.stop(now_ns, AfterLog::Score, None),
            Action::Stop => self.refuse("no trial is running"),
            Action::Progress(value) => self.progress(value),
            Action::Unmark => self.unmark(),
            Action::Drop if running => {
                self.drops += 1;
                if matches!(self.kind, CorrectnessKind::Grasp {}) {
                    self.progress = 0.5;
                }
                self.say("drop marked");
                vec![Effect::TrialEvent(json!({"event": "drop"}))]
            }
            Action::Drop => self.refuse("no trial is running: drop not marked"),
            Action::Abort if self.start_pending.is_some() => {
                self.start_pending = None;
                self.refuse("start cancelled")
            }
            Action::Abort => match self.phase {
                TrialPhase::Countdown { .. } => {
                    self.phase = TrialPhase::Idle;
                    self.say("countdown cancelled");
                    vec![]
                }
                TrialPhase::Running { .. } => self.stop(now_ns, AfterLog::Score, Some("operator")),
                _ => self.refuse("no trial is running"),
            },
            Action::Redo => self.redo(now_ns),
            Action::Note(text) => {
                if running {
                    self.say(format!("note logged: {text}"));
                    vec![Effect::TrialEvent(json!({"event": "note", "text": text}))]
                } else {
                    self.manifest.notes.push(text.clone());
                    self.say(format!("note added to the session: {text}"));
                    vec![Effect::SaveManifest]
                }
            }
            Action::PromptProgress | Action::PromptNote => vec![],
            Action::Quit => match self.phase {
                TrialPhase::Running { .. } if !self.quit_armed => {
                    self.quit_armed = true;
                    self.refuse("a trial is running: press q again to abort it and quit (it is redone when the session resumes)")
                }
                _ => self.interrupt(now_ns, "quit"),
            },
            Action::Interrupt => self.interrupt(now_ns, "interrupted"),
        }
    }

    fn engage(&mut self, health: &Health, now_ns: i64) -> Vec<Effect> {
        if !self.limits.drives_robot {
            return self.refuse("a human study drives no robot: nothing to engage");
        }
        if health.engaged() {
            return vec![];
        }
        let fresh = health
            .input_age_at(now_ns)
            .is_some_and(|age| age <= self.limits.max_input_age_ms);
        if !fresh {
            self.say("engage: waiting for fresh glove input (up to 10 s; e cancels)");
        }
        self.engage_pending = Some((now_ns, now_ns));
        vec![Effect::Engage]
    }

    fn disengage(&mut self) -> Vec<Effect> {
        self.engage_pending = None;
        vec![Effect::Disengage]
    }

    /// A pending engage: asked again until the station engages, given up after 10 s.
    fn pending_engage(&mut self, health: &Health, now_ns: i64) -> Vec<Effect> {
        let Some((asked, sent)) = self.engage_pending else {
            return vec![];
        };
        if health.engaged() {
            self.engage_pending = None;
            self.say("engaged");
            return vec![];
        }
        if now_ns - asked > ENGAGE_WAIT_NS {
            self.engage_pending = None;
            return self.refuse("engage given up: no fresh glove input for 10 s");
        }
        if now_ns - sent < ENGAGE_RESEND_NS {
            return vec![];
        }
        self.engage_pending = Some((asked, now_ns));
        vec![Effect::Engage]
    }

    fn refuse(&mut self, why: &str) -> Vec<Effect> {
        self.say(why.to_string());
        vec![]
    }

    fn start(&mut self, health: &Health, now_ns: i64) -> Vec<Effect> {
        match self.phase {
            TrialPhase::Idle => {}
            TrialPhase::Complete => return self.refuse("the session is complete: press q to quit"),
            _ => return self.refuse("a trial is already under way"),
        }
        let Some((practice, index)) = self.manifest.next_slot() else {
            self.phase = TrialPhase::Complete;
            return vec![];
        };
        if let Some(why) = health.refuse_start(&self.limits, now_ns) {
            let engaging = health.engaged() || self.engage_pending.is_some();
            if self.limits.drives_robot && !engaging {
                return self.refuse(&format!("cannot start: {why}"));
            }
            // Engaging, or the glove rate still settling: start once the station is ready.
            if self.start_pending.is_none() {
                self.start_pending = Some(now_ns);
                self.say(format!(
                    "start: waiting for the station ({why}); up to 10 s, a cancels"
                ));
            }
            return vec![];
        }
        self.start_pending = None;
        if health.hand_listeners == Some(0) {
            self.say("warning: no robot hand is listening to the joint targets (the trial is logged all the same)");
        }
        self.phase = TrialPhase::Countdown {
            slot: Slot { practice, index },
            ends_ns: now_ns + self.countdown_ns,
        };
        vec![]
    }

    /// Advances time: the countdown ends into a running trial.
    pub fn tick(&mut self, health: &Health, now_ns: i64) -> Vec<Effect> {
        let mut effects = self.pending_engage(health, now_ns);
        if let (Some(asked), TrialPhase::Idle) = (self.start_pending, &self.phase) {
            match health.refuse_start(&self.limits, now_ns) {
                None => effects.extend(self.start(health, now_ns)),
                Some(why) if now_ns - asked > START_WAIT_NS => {
                    self.start_pending = None;
                    effects.extend(self.refuse(&format!("cannot start: {why}")));
                }
                Some(_) => {}
            }
        }
        let TrialPhase::Countdown { slot, ends_ns } = self.phase else {
            return effects;
        };
        if now_ns < ends_ns {
            return effects;
        }
        if let Some(why) = health.refuse_start(&self.limits, now_ns) {
            self.phase = TrialPhase::Idle;
            effects.extend(self.refuse(&format!("countdown cancelled: {why}")));
            return effects;
        }
        let file = self.file_name(slot);
        self.phase = TrialPhase::Running {
            slot,
            file: file.clone(),
            started_ns: now_ns,
        };
        self.progress = 0.0;
        self.drops = 0;
        effects.push(Effect::StartTrial { file, slot });
        effects
    }

    /// The station could not create the trial's log.
    pub fn trial_start_failed(&mut self, error: &str) -> Vec<Effect> {
        if matches!(self.phase, TrialPhase::Running { .. }) {
            self.phase = TrialPhase::Idle;
        }
        self.refuse(&format!("the trial log could not be created: {error}"))
    }

    fn stop(&mut self, now_ns: i64, after: AfterLog, abort: Option<&str>) -> Vec<Effect> {
        let TrialPhase::Running {
            slot,
            file,
            started_ns,
        } = self.phase.clone()
        else {
            return vec![];
        };
        self.phase = TrialPhase::Finishing {
            slot,
            file,
            time_s: (now_ns - started_ns) as f64 * 1e-9,
            after,
        };
        let mut effects = Vec::new();
        if let Some(reason) = abort {
            effects.push(Effect::TrialEvent(
                json!({"event": "abort", "reason": reason}),
            ));
        }
        effects.push(Effect::StopTrial);
        effects
    }

    fn redo(&mut self, now_ns: i64) -> Vec<Effect> {
        match self.phase {
            TrialPhase::Running { .. } => self.stop(now_ns, AfterLog::Redo, Some("redo")),
            TrialPhase::Idle | TrialPhase::Complete => {
                let Some(i) = self.last else {
                    return self.refuse("no trial to redo yet");
                };
                let trial = &mut self.manifest.trials[i];
                if trial.status != TrialStatus::Scored && trial.status != TrialStatus::Unscorable {
                    return self.refuse("the last trial is already set aside");
                }
                let from = trial.file.clone();
                let to = format!("{from}.redone");
                trial.file = to.clone();
                trial.status = TrialStatus::Redone;
                self.phase = TrialPhase::Idle;
                self.say(format!("{from} set aside as {to}: it runs again"));
                vec![Effect::SetAside { from, to }, Effect::SaveManifest]
            }
            _ => self.refuse("nothing to redo now"),
        }
    }

    fn interrupt(&mut self, now_ns: i64, reason: &str) -> Vec<Effect> {
        match self.phase {
            TrialPhase::Running { .. } => {
                self.stop(now_ns, AfterLog::InterruptedQuit, Some(reason))
            }
            TrialPhase::Finishing { ref mut after, .. } => {
                // Quit once the log is finished.
                if *after == AfterLog::Score {
                    *after = AfterLog::InterruptedQuit;
                }
                vec![]
            }
            _ => {
                self.phase = TrialPhase::Quitting;
                vec![Effect::Quit]
            }
        }
    }

    fn progress(&mut self, value: Option<f64>) -> Vec<Effect> {
        if !matches!(self.phase, TrialPhase::Running { .. }) {
            return self.refuse("no trial is running: progress not marked");
        }
        let counted = matches!(
            self.kind,
            CorrectnessKind::Notches { .. } | CorrectnessKind::Curves { .. }
        );
        let unit = self.kind.progress_unit();
        if value.is_some_and(|v| !v.is_finite()) {
            return self.refuse(&format!("not a number of {unit}: progress not marked"));
        }
        let value = match (value, counted) {
            (None, true) => 1.0,
            (None, false) => {
                return self.refuse(&format!(
                    "this task takes a value in {unit}: press p and type it"
                ));
            }
            (Some(v), true) if v.fract() != 0.0 => {
                return self.refuse(&format!("{v} is not a whole number of {unit}"));
            }
            (Some(v), _) if matches!(self.kind, CorrectnessKind::Grasp {}) => {
                if !GRASP_LEVELS.contains(&v) {
                    return self.refuse(&format!(
                        "grasp level {v}: allowed 0 (not lifted), 0.5 (lifted, dropped), 1 (relocated)"
                    ));
                }
                v
            }
            (Some(v), _) => v,
        };
        if matches!(self.kind, CorrectnessKind::Grasp {}) {
            self.progress = value;
        } else {
            self.progress += value;
        }
        self.say(format!(
            "progress {value:+} {unit} (now {} {unit})",
            self.progress
        ));
        vec![Effect::TrialEvent(
            json!({"event": "progress", "value": value}),
        )]
    }

    fn unmark(&mut self) -> Vec<Effect> {
        if !matches!(self.phase, TrialPhase::Running { .. }) {
            return self.refuse("no trial is running");
        }
        if !matches!(
            self.kind,
            CorrectnessKind::Notches { .. } | CorrectnessKind::Curves { .. }
        ) {
            return self.refuse("unmark takes back a notch or curve; this task takes values (p)");
        }
        if self.progress < 1.0 {
            return self.refuse("nothing to take back");
        }
        self.progress -= 1.0;
        self.say(format!("one {} taken back", self.kind.progress_unit()));
        vec![Effect::TrialEvent(
            json!({"event": "progress", "value": -1.0}),
        )]
    }

    /// The trial's log is finished (`Ok`: read back and scored; `Err`: why it cannot be).
    pub fn trial_logged(&mut self, result: Result<TrialScore, String>) -> Vec<Effect> {
        let TrialPhase::Finishing {
            slot,
            file,
            time_s,
            after,
        } = self.phase.clone()
        else {
            return vec![];
        };
        if let Err(reason) = &result {
            self.say(format!("{file} cannot be scored: {reason}; it runs again"));
        }
        let mut trial = logged_trial(&file, slot, Some(time_s), result);
        let mut effects = Vec::new();
        let aside = match after {
            AfterLog::Score => None,
            AfterLog::Redo => Some((TrialStatus::Redone, "redone")),
            AfterLog::InterruptedQuit => Some((TrialStatus::Interrupted, "interrupted")),
        };
        if let Some((status, suffix)) = aside {
            let to = format!("{file}.{suffix}");
            effects.push(Effect::SetAside {
                from: file.clone(),
                to: to.clone(),
            });
            trial.file = to;
            trial.status = status;
        }
        self.manifest.trials.push(trial);
        self.last = Some(self.manifest.trials.len() - 1);
        effects.push(Effect::SaveManifest);
        self.phase = if after == AfterLog::InterruptedQuit {
            effects.push(Effect::Quit);
            TrialPhase::Quitting
        } else if self.manifest.next_slot().is_none() {
            TrialPhase::Complete
        } else {
            TrialPhase::Idle
        };
        effects
    }
}

/// A finished trial log's manifest entry: scored (`Ok`: its outcome, time, progress,
/// correctness and score) or not scorable (`Err`: the reason kept in its notes, `time_s` as
/// the console timed it, if known).
pub fn logged_trial(
    file: &str,
    slot: Slot,
    time_s: Option<f64>,
    result: Result<TrialScore, String>,
) -> ManifestTrial {
    let mut trial = ManifestTrial {
        file: file.to_string(),
        practice: slot.practice,
        index: slot.index,
        status: TrialStatus::Scored,
        outcome: None,
        time_s,
        progress: None,
        correctness: None,
        score: None,
        notes: vec![],
    };
    match result {
        Ok(score) => {
            trial.outcome = Some(score.outcome.name().to_string());
            trial.time_s = Some(score.time_s);
            trial.progress = Some(score.progress);
            trial.correctness = Some(score.correctness);
            trial.score = score.score;
            trial.notes = score.notes;
        }
        Err(reason) => {
            trial.status = TrialStatus::Unscorable;
            trial.notes.push(reason);
        }
    }
    trial
}

#[cfg(test)]
#[path = "trial_flow_tests.rs"]
mod tests;
