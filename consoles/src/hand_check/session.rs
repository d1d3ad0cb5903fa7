//! The hand check as a pure state machine: time is a parameter (seconds since the check
//! started), answers come in, the values to send and the lines to show come out.
//!
//! ```text
//! settling ──▶ moving (joint k) ──▶ asking ──yes──▶ moving (joint k+1) … ──▶ complete
//!    ▲              ▲    ▲             │ repeat          │
//!    │              │    └─────────────┘                 │ no
//!    │              └──────── keep ───── offer_flip ◀────┘
//!    └──────────────────────── flip ──────┘            quit (anywhere) ──▶ quit
//! ```
//!
//! The hand first goes to the neutral pose (every joint at the value nearest the URDF zero
//! inside both its URDF limits and the consumer's range, a little inside both), then each joint
//! in the table's order moves a small step (at most 0.15 rad) one way and back along a cosine
//! (at least 1 s each way) while the others hold still.

use std::f64::consts::PI;

use retarget::HandModel;
use station::policy_output::{PolicyOutput, PolicyOutputConfig};

use crate::error::ConsolesError;
use crate::hand_check::directions::direction_sentence;

/// The largest step a joint is moved, radians.
pub const MAX_STEP_RAD: f64 = 0.15;
/// The shortest time a step may take each way, seconds.
pub const MIN_MOVE_S: f64 = 1.0;
/// How far inside a range the neutral pose stays, radians (less for a narrow range).
const NEUTRAL_MARGIN_RAD: f64 = 0.02;
/// A joint that cannot move this far from neutral within its range cannot be checked.
const MIN_STEP_RAD: f64 = 0.01;

/// How the joints are moved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    /// The step, radians of the URDF joint (≤ [`MAX_STEP_RAD`]).
    pub step_rad: f64,
    /// Seconds each way (≥ [`MIN_MOVE_S`]).
    pub move_s: f64,
    /// Seconds held at the far end.
    pub hold_s: f64,
    /// Seconds to go to (and hold) the neutral pose first; at least `move_s` (the ramp to a
    /// neutral pose moved by a flip takes that long).
    pub settle_s: f64,
}

impl Default for Motion {
    fn default() -> Self {
        Motion {
            step_rad: MAX_STEP_RAD,
            move_s: 1.5,
            hold_s: 0.5,
            settle_s: 2.0,
        }
    }
}

impl Motion {
    /// Check the step and the times; errors name the option and its range.
    pub fn validate(&self) -> Result<(), ConsolesError> {
        let check = |option: &'static str, value: f64, lo: f64, hi: f64, open: bool| {
            let ok =
                value.is_finite() && (if open { value > lo } else { value >= lo }) && value <= hi;
            if ok {
                Ok(())
            } else {
                let allowed = format!("{}{lo}, {hi}]", if open { "(" } else { "[" });
                Err(ConsolesError::Option {
                    option,
                    value,
                    allowed,
                })
            }
        };
        check("--step-rad", self.step_rad, 0.0, MAX_STEP_RAD, true)?;
        check("--move-s", self.move_s, MIN_MOVE_S, 10.0, false)?;
        check("--hold-s", self.hold_s, 0.0, 5.0, false)?;
        check("--settle-s", self.settle_s, 0.0, 30.0, false)
    }
}

/// Where the check is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CheckPhase {
    /// Going to, and holding, the neutral pose.
    Settling,
    /// A joint moving its step and back.
    Moving,
    /// Waiting for the operator's answer about the joint that moved.
    Asking,
    /// The operator saw the wrong direction: flip the sign, or keep it and repeat.
    OfferFlip,
    /// Every joint confirmed.
    Complete,
    /// Quit before every joint was confirmed.
    Quit,
}

impl CheckPhase {
    /// Every phase, for scripts.
    pub const ALL: [CheckPhase; 6] = [
        CheckPhase::Settling,
        CheckPhase::Moving,
        CheckPhase::Asking,
        CheckPhase::OfferFlip,
        CheckPhase::Complete,
        CheckPhase::Quit,
    ];

    /// The phase's name in scripts.
    pub fn name(self) -> &'static str {
        match self {
            CheckPhase::Settling => "settling",
            CheckPhase::Moving => "moving",
            CheckPhase::Asking => "asking",
            CheckPhase::OfferFlip => "offer_flip",
            CheckPhase::Complete => "complete",
            CheckPhase::Quit => "quit",
        }
    }

    /// The phase of a name.
    pub fn from_name(name: &str) -> Option<CheckPhase> {
        CheckPhase::ALL.into_iter().find(|p| p.name() == name)
    }

    /// Whether the check has ended.
    pub fn is_over(self) -> bool {
        matches!(self, CheckPhase::Complete | CheckPhase::Quit)
    }
}

/// The operator's answers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Answer {
    /// The joint moved as named.
    Yes,
    /// It moved the other way.
    No,
    /// Move it again.
    Repeat,
    /// (After no) flip its sign and move it again.
    Flip,
    /// (After no) keep its sign and move it again.
    Keep,
    /// Stop; nothing is written unless every joint was confirmed.
    Quit,
}

/// One joint of the table being checked.
#[derive(Debug, Clone, PartialEq)]
pub struct JointCheck {
    /// The station joint.
    pub joint: String,
    /// Its model degree of freedom.
    pub dof: usize,
    /// Confirmed by the operator.
    pub confirmed: bool,
    /// Its sign was flipped during the check.
    pub flipped: bool,
}

/// The check: the table being checked, the joints, where it is.
#[derive(Debug, Clone)]
pub struct HandCheck {
    model: HandModel,
    config: PolicyOutputConfig,
    output: PolicyOutput,
    motion: Motion,
    joints: Vec<JointCheck>,
    neutral: Vec<f64>,
    /// The pose the settling starts from.
    settle_from: Vec<f64>,
    current: usize,
    phase: CheckPhase,
    since_s: f64,
    /// The current joint's step: URDF direction (±1) times its size, radians.
    step: f64,
    lines: Vec<String>,
}

impl HandCheck {
    /// A check of `config`'s table on `model`, starting at `now_s`.
    pub fn new(
        model: HandModel,
        config: PolicyOutputConfig,
        motion: Motion,
        now_s: f64,
    ) -> Result<HandCheck, ConsolesError> {
        motion.validate()?;
        if config.joints.is_empty() {
            return Err(ConsolesError::NoTable);
        }
        let output = PolicyOutput::new(&model, &config)?;
        let joints = config
            .joints
            .iter()
            .zip(output.dofs())
            .map(|(row, dof)| JointCheck {
                joint: row.joint.clone(),
                dof,
                confirmed: false,
                flipped: false,
            })
            .collect();
        let neutral = neutral_pose(&model, &output)?;
        let mut check = HandCheck {
            settle_from: neutral.clone(),
            model,
            config,
            output,
            motion,
            joints,
            neutral,
            current: 0,
            phase: CheckPhase::Settling,
            since_s: now_s,
            step: 0.0,
            lines: Vec::new(),
        };
        check.say(format!(
            "hand check of {}: {} joints; going to the neutral pose ({:.1} s)",
            check.config.consumer,
            check.joints.len(),
            motion.settle_s.max(motion.move_s)
        ));
        Ok(check)
    }

    /// Where the check is.
    pub fn phase(&self) -> CheckPhase {
        self.phase
    }

    /// The joints, in the table's order.
    pub fn joints(&self) -> &[JointCheck] {
        &self.joints
    }

    /// The neutral pose (model order, URDF zeros, radians).
    pub fn neutral(&self) -> &[f64] {
        &self.neutral
    }

    /// The joints not confirmed, in the table's order.
    pub fn unconfirmed(&self) -> Vec<String> {
        self.joints
            .iter()
            .filter(|j| !j.confirmed)
            .map(|j| j.joint.clone())
            .collect()
    }

    /// `joint 5 of 17: index_abd`.
    pub fn progress(&self) -> String {
        match self.joints.get(self.current) {
            Some(j) if !self.phase.is_over() => format!(
                "joint {} of {}: {}",
                self.current + 1,
                self.joints.len(),
                j.joint
            ),
            _ => format!(
                "{} of {} joints confirmed",
                self.joints.len() - self.unconfirmed().len(),
                self.joints.len()
            ),
        }
    }

    /// The lines to show since the last call.
    pub fn take_lines(&mut self) -> Vec<String> {
        std::mem::take(&mut self.lines)
    }

    fn say(&mut self, line: String) {
        self.lines.push(line);
    }

    /// Advance the motion to `now_s`: settling ends in the current joint's move, a finished
    /// move asks the operator.
    pub fn tick(&mut self, now_s: f64) {
        let elapsed = now_s - self.since_s;
        match self.phase {
            // At least the ramp's time (after a flip the neutral pose may have moved).
            CheckPhase::Settling if elapsed >= self.motion.settle_s.max(self.motion.move_s) => {
                self.start_move(now_s);
            }
            CheckPhase::Moving if elapsed >= 2.0 * self.motion.move_s + self.motion.hold_s => {
                self.phase = CheckPhase::Asking;
                self.since_s = now_s;
                let joint = self.joints[self.current].joint.clone();
                self.say(format!(
                    "{}: did {joint} move as named? yes / no / repeat / quit",
                    self.progress()
                ));
            }
            _ => {}
        }
    }

    fn start_move(&mut self, now_s: f64) {
        let joint = &self.joints[self.current];
        let (lo, hi) = self
            .output
            .urdf_range(&self.model, self.current)
            .unwrap_or((0.0, 0.0));
        let at = self.neutral[joint.dof];
        let (up, down) = (hi - at, at - lo);
        let size = self.motion.step_rad;
        self.step = if up >= size || (up >= down && down < size) {
            size.min(up)
        } else {
            -size.min(down)
        };
        self.phase = CheckPhase::Moving;
        self.since_s = now_s;
        let line = format!(
            "{}: watch: {} ({:+.2} rad over {:.1} s, then back)",
            self.progress(),
            direction_sentence(&joint.joint, self.step),
            self.step,
            self.motion.move_s
        );
        self.say(line);
    }

    /// The operator's answer at `now_s`.
    pub fn answer(&mut self, answer: Answer, now_s: f64) {
        match (self.phase, answer) {
            (phase, Answer::Quit) if !phase.is_over() => {
                self.phase = CheckPhase::Quit;
                let open = self.unconfirmed();
                self.say(format!("quit: not confirmed: {}", open.join(", ")));
            }
            (CheckPhase::Asking, Answer::Yes) => {
                self.joints[self.current].confirmed = true;
                self.say(format!("{}: confirmed", self.progress()));
                if let Some(next) = self.joints.iter().position(|j| !j.confirmed) {
                    self.current = next;
                    self.start_move(now_s);
                } else {
                    self.phase = CheckPhase::Complete;
                    self.say(format!("all {} joints confirmed", self.joints.len()));
                }
            }
            (CheckPhase::Asking, Answer::No) => {
                self.phase = CheckPhase::OfferFlip;
                let joint = self.joints[self.current].joint.clone();
                self.say(format!(
                    "{joint} moved the other way: flip (flip its sign and move it again) / keep (move it again as it is) / quit"
                ));
            }
            (CheckPhase::Asking | CheckPhase::OfferFlip, Answer::Repeat | Answer::Keep) => {
                self.start_move(now_s);
            }
            (CheckPhase::OfferFlip, Answer::Flip) => self.flip(now_s),
            (phase, answer) => self.say(format!(
                "'{}' does nothing while {}",
                answer_word(answer),
                phase.name()
            )),
        }
    }

    /// Flip the current joint's sign, go to the new neutral pose, move it again.
    fn flip(&mut self, now_s: f64) {
        let mut config = self.config.clone();
        let row = &mut config.joints[self.current];
        row.sign = -row.sign;
        let rebuilt = PolicyOutput::new(&self.model, &config)
            .map_err(ConsolesError::from)
            .and_then(|output| Ok((neutral_pose(&self.model, &output)?, output)));
        match rebuilt {
            Ok((neutral, output)) => {
                self.settle_from = self.pose(now_s);
                self.config = config;
                self.output = output;
                self.neutral = neutral;
                let joint = &mut self.joints[self.current];
                joint.flipped = !joint.flipped;
                let line = format!("{}: sign flipped; moving it again", self.progress());
                self.say(line);
                self.phase = CheckPhase::Settling;
                self.since_s = now_s;
            }
            Err(e) => self.say(format!("cannot flip: {e}")),
        }
    }

    /// The pose commanded at `now_s` (model order, URDF, radians).
    pub fn pose(&self, now_s: f64) -> Vec<f64> {
        let t = now_s - self.since_s;
        let ease = |s: f64| (1.0 - (PI * s.clamp(0.0, 1.0)).cos()) / 2.0;
        match self.phase {
            CheckPhase::Settling => {
                let s = ease(t / self.motion.move_s);
                self.settle_from
                    .iter()
                    .zip(&self.neutral)
                    .map(|(a, b)| a + s * (b - a))
                    .collect()
            }
            CheckPhase::Moving => {
                let m = &self.motion;
                let s = if t < m.move_s + m.hold_s {
                    ease(t / m.move_s)
                } else {
                    1.0 - ease((t - m.move_s - m.hold_s) / m.move_s)
                };
                let mut q = self.neutral.clone();
                q[self.joints[self.current].dof] += s * self.step;
                q
            }
            _ => self.neutral.clone(),
        }
    }

    /// The values to send at `now_s`, through the table (as checked so far).
    pub fn command(&self, now_s: f64) -> Vec<f32> {
        self.output.values(&self.pose(now_s))
    }

    /// The table to write: every row verified (flipped signs and a note on them), who and
    /// when; an error naming the joints not confirmed.
    pub fn verified_table(&self, by: &str, at: &str) -> Result<PolicyOutputConfig, ConsolesError> {
        let open = self.unconfirmed();
        if !open.is_empty() {
            return Err(ConsolesError::Unconfirmed { joints: open });
        }
        let mut config = self.config.clone();
        for (row, joint) in config.joints.iter_mut().zip(&self.joints) {
            row.verified = true;
            if joint.flipped {
                let note = format!("sign flipped by pomdar hand-check ({by}, {at})");
                row.note = if row.note.is_empty() {
                    note
                } else {
                    format!("{}; {note}", row.note)
                };
            }
        }
        config.verified_by = by.to_string();
        config.verified_at = at.to_string();
        Ok(config)
    }
}

/// The word of an answer (scripts and stdin).
pub fn answer_word(answer: Answer) -> &'static str {
    match answer {
        Answer::Yes => "yes",
        Answer::No => "no",
        Answer::Repeat => "repeat",
        Answer::Flip => "flip",
        Answer::Keep => "keep",
        Answer::Quit => "quit",
    }
}

/// Each joint at the value nearest 0 inside its URDF limits and the consumer's range (a margin
/// inside both); an error for a joint the table leaves no room to move.
pub fn neutral_pose(model: &HandModel, output: &PolicyOutput) -> Result<Vec<f64>, ConsolesError> {
    let mut q = model.zero_pose();
    for (slot, dof) in output.dofs().into_iter().enumerate() {
        let (lo, hi) = output.urdf_range(model, slot).unwrap_or((0.0, 0.0));
        let joint = model.dof_names().nth(dof).unwrap_or("?").to_string();
        if hi - lo < 2.0 * MIN_STEP_RAD {
            return Err(ConsolesError::NoRoom { joint, lo, hi });
        }
        let margin = NEUTRAL_MARGIN_RAD.min((hi - lo) / 4.0);
        q[dof] = 0.0f64.clamp(lo + margin, hi - margin);
    }
    Ok(q)
}
