//! A simulated trial in simulated time: the scripted glove, the station core and the physics
//! stepped in lock step, no DDS, no wall clock. The same `station::Station` every live path
//! drives takes the glove's frames and wrist poses, its timer ticks and the arm's pose feedback;
//! its hand commands and arm targets go to the same simulated robot the `pomdar sim` node runs
//! ([`SimState`]). Deterministic: the same script, configuration and scene give the same
//! events, so a lab can try a glove script or a scene change in seconds
//! (`pomdar sim --task G4 --glove-script FILE --lockstep`), and the tests can check a grasp
//! without depending on the machine's load.

use retarget::HandModel;
use retarget::human_hand::SimGlove;
use station::convert::isometry_to_pose;
use station::{ControlInput, KeypointFrame, StationConfig, StationInput};

use super::error::PhysicsError;
use super::robot_config::PhysicsRobotConfig;
use super::setup::SimulatedTask;
use super::sim_state::SimState;
use crate::sim::mock_hand::joint_state_target;
use crate::sim::progress_message::ProgressMessage;

/// What a lock-step trial produced.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LockstepOutcome {
    /// Every progress event, in order.
    pub events: Vec<ProgressMessage>,
    /// The progress at the end, in the task's unit.
    pub progress: f64,
    /// Hand commands the station sent.
    pub hand_commands: u64,
    /// Arm targets the station sent.
    pub arm_targets: u64,
    /// Simulated time, seconds.
    pub sim_time_s: f64,
    /// The progress source's last reading: the task object's position (m) for a grasp task.
    pub final_reading: Option<simulation::progress::Reading>,
}

/// Play `glove` for `duration_s` through a station built from `config` on `model`, into the
/// simulated robot of `loaded`; the glove's frames come at `config`'s glove rate `rate_hz`,
/// the station's timer at its `control.rate_hz`, the arm's feedback with every frame.
pub fn run_lockstep(
    config: &StationConfig,
    model: &HandModel,
    glove: &SimGlove,
    loaded: SimulatedTask,
    rate_hz: f64,
    duration_s: f64,
) -> Result<LockstepOutcome, PhysicsError> {
    let arm_start = config
        .arm
        .start_pose_isometry()
        .map_err(|e| PhysicsError::Progress {
            message: format!("arm start pose: {e}"),
        })?;
    let robot = PhysicsRobotConfig::for_station(config, &loaded, arm_start);
    let mut station_config = config.clone();
    station_config.control.auto_engage = true;
    // Built as every live path builds it: with the configured calibration profile.
    let (mut station, _) = crate::station_setup::build_station(&station_config, model.clone())
        .map_err(|e| PhysicsError::Progress {
            message: format!("station: {e}"),
        })?;
    let mut sim = SimState::new(loaded.engine, &robot)?;
    let mut outcome = LockstepOutcome::default();
    let limits: Vec<_> = model.limits().collect();
    let dt = 1.0 / rate_hz;
    let tick_every = (rate_hz / config.control.rate_hz).round().max(1.0) as u64;
    let steps = (duration_s / dt).round() as u64;
    for k in 0..steps {
        let t = k as f64 * dt;
        let now_ns = (t * 1e9) as i64;
        let feedback = isometry_to_pose(&sim.arm_pose);
        let mut inputs = vec![StationInput::ArmFeedback(feedback)];
        if glove.sends_at(t) {
            let (points, wrist) = glove.frame(t);
            inputs.push(StationInput::Wrist(isometry_to_pose(&wrist)));
            inputs.push(StationInput::Keypoints(KeypointFrame {
                points,
                source_ns: now_ns,
            }));
        }
        if k % tick_every == 0 {
            inputs.push(StationInput::Control(ControlInput::Tick));
        }
        for input in inputs {
            apply(
                &mut sim,
                (model, &limits),
                station.step(input, now_ns),
                &mut outcome,
            );
        }
        for event in sim.advance(dt, &robot) {
            outcome.events.push(sim.progress_message(&event, &robot));
        }
    }
    outcome.progress = sim.tracker.as_ref().map_or(0.0, |t| t.total());
    outcome.final_reading = robot
        .progress
        .as_ref()
        .and_then(|(_, mapping)| sim.engine.reading(&mapping.joint));
    outcome.sim_time_s = steps as f64 * dt;
    Ok(outcome)
}

/// Hand commands and arm targets from the station to the simulated robot.
fn apply(
    sim: &mut SimState,
    (model, limits): (&HandModel, &[retarget::Limits]),
    outputs: station::StationOutputs,
    outcome: &mut LockstepOutcome,
) {
    if let Some(hand) = outputs.hand {
        let targets =
            joint_state_target(model, limits, sim.engine.hand_targets(), &hand.joint_state);
        if targets.is_some_and(|t| sim.engine.set_hand_targets(&t).is_ok()) {
            outcome.hand_commands += 1;
        }
    }
    if let Some(arm) = outputs
        .arm
        .and_then(|a| station::convert::pose_to_isometry(&a.pose))
    {
        sim.arm_target = arm;
        outcome.arm_targets += 1;
    }
}
