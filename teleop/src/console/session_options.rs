//! What a trial console session is asked to run: the task, the people, the plan, the files,
//! the console's settings, the network, the simulation and the live view. `pomdar trial` and
//! `pomdar study` fill it from their flags.

use std::path::PathBuf;

use retarget::human_hand::MotionKind;

use crate::ros::NetworkOverride;
use crate::score::score_inputs::ScoringFileArgs;
use crate::view::ViewAddress;

/// Default protocol for a robot: (practice, recorded trials).
pub const ROBOT_PROTOCOL: (u32, u32) = (5, 20);
/// The POMDAR human study's protocol: no practice, three trials per task.
pub const HUMAN_PROTOCOL: (u32, u32) = (0, 3);

/// One task's console session, as asked for.
#[derive(Debug, Clone)]
pub struct SessionOptions {
    /// The task ID in the catalog.
    pub task: String,
    /// The embodiment, or `human` for a human-study session.
    pub embodiment: String,
    /// The user wearing the glove (the study's participant).
    pub user: String,
    /// The operator running the session.
    pub operator: String,
    /// Recorded trials (default: the protocol's).
    pub trials: Option<u32>,
    /// Practice trials (default: the protocol's).
    pub practice: Option<u32>,
    /// The sessions directory.
    pub out: PathBuf,
    /// The station configuration file (default: the built-in preset).
    pub config: Option<PathBuf>,
    /// The user's calibration profile.
    pub profile: Option<PathBuf>,
    /// The baseline, catalog and rules.
    pub scoring: ScoringFileArgs,
    /// The countdown, the start gate, the script and the display.
    pub console: ConsoleSettings,
    /// `--domain-id` and `--interface`.
    pub network: NetworkOverride,
    /// `--simulate`: the simulated glove and robot in this process.
    pub simulation: Option<SimulationOptions>,
    /// The simulated hand's size (default: 1, or drawn from a participant's name); checked
    /// even without a simulation.
    pub simulated_hand_scale: Option<f64>,
    /// `--view`: the live view's address.
    pub view: Option<ViewAddress>,
}

/// How the console runs.
#[derive(Debug, Clone)]
pub struct ConsoleSettings {
    /// Countdown before a trial starts, s.
    pub countdown: f64,
    /// The start gate's lowest glove rate, Hz.
    pub min_glove_rate: f64,
    /// The start gate's oldest glove frame, ms.
    pub max_input_age: f64,
    /// Timed operator actions from a file.
    pub script: Option<PathBuf>,
    /// Lines instead of the full-screen console.
    pub plain: bool,
}

/// The simulated glove and robot (`--simulate`).
#[derive(Debug, Clone)]
pub struct SimulationOptions {
    /// The glove's periodic motion.
    pub motion: MotionKind,
    /// A glove task script played instead of the motion.
    pub glove_script: Option<PathBuf>,
    /// The simulated robot in the task's MuJoCo scene instead of the mock robot.
    pub physics: bool,
    /// A lab's own task MJCF (with `physics`).
    pub scene: Option<PathBuf>,
    /// The glove's keypoint noise, mm (default: the glove's own).
    pub glove_jitter_mm: Option<f64>,
}

impl SessionOptions {
    /// Whether this is a human-study session (embodiment `human`).
    pub fn human(&self) -> bool {
        self.embodiment == station::HUMAN_EMBODIMENT
    }

    /// Practice and recorded trials: as asked, else the protocol's defaults.
    pub fn plan_counts(&self) -> (u32, u32) {
        let (practice, trials) = if self.human() {
            HUMAN_PROTOCOL
        } else {
            ROBOT_PROTOCOL
        };
        (
            self.practice.unwrap_or(practice),
            self.trials.unwrap_or(trials),
        )
    }
}
