//! A simulated trial in simulated time: the scripted glove, the station core and the physics
//! stepped in lock step, no DDS, no wall clock. The same `station::Station` every live path
//! drives takes the glove's frames and wrist poses, its timer ticks and the arm's pose feedback;
//! its hand commands and arm targets go to the same simulated robot the `pomdar sim` node runs
//! ([`SimState`]). Deterministic: the same script, configuration and scene give the same
//! events, so a lab can try a glove script or a scene change in seconds
//! (`pomdar sim --task G4 --glove-script FILE --lockstep`), and the tests can check a grasp
//! without depending on the machine's load.

use msgs::PoseStamped;
use retarget::HandModel;
use retarget::human_hand::SimGlove;
use station::HandMessages;
use station::convert::isometry_to_pose;
use station::{ControlInput, KeypointFrame, Notice, StationConfig, StationInput, StationOutputs};

use super::error::PhysicsError;
use super::robot_config::PhysicsRobotConfig;
use super::setup::SimulatedTask;
use super::sim_state::SimState;
use crate::stand_ins::mock_hand::joint_state_target;
use crate::stand_ins::progress_message::ProgressMessage;
use crate::station_driver::{
    Engage, OutputSink, TickSchedule, build_station, route, set_engage, steps_per_tick,
};

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

/// What a lock-step trial watches besides the physics: every input the station is stepped with
/// and every output it gives, at their simulated times (a recorder writes them as a live
/// station's log).
pub trait LockstepObserver {
    /// The station is stepped with `input` at `now_ns`.
    fn input(&mut self, now_ns: i64, input: &StationInput);
    /// It answered with `outputs`.
    fn outputs(&mut self, now_ns: i64, outputs: &StationOutputs);
    /// The physics made a progress event.
    fn progress(&mut self, event: &ProgressMessage);
}

/// Whether the progress events so far complete the task.
pub type DoneTest<'a> = &'a dyn Fn(&[ProgressMessage]) -> bool;

/// A lock-step trial's settings.
pub struct LockstepPlay<'a> {
    /// The station's configuration (with the task's arm constraint).
    pub config: &'a StationConfig,
    /// The hand model the station retargets to.
    pub model: &'a HandModel,
    /// The simulated glove.
    pub glove: &'a SimGlove,
    /// The glove's frame rate, Hz.
    pub rate_hz: f64,
    /// The trial's length, simulated seconds.
    pub duration_s: f64,
    /// Stop early once this says the progress events so far complete the task.
    pub until: Option<DoneTest<'a>>,
    /// Watches the station's inputs and outputs.
    pub observer: Option<&'a mut dyn LockstepObserver>,
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
    let play = LockstepPlay {
        config,
        model,
        glove,
        rate_hz,
        duration_s,
        until: None,
        observer: None,
    };
    play_lockstep(play, loaded)
}

/// [`run_lockstep`] with its settings in one place: stopping early when `until` says the task
/// is done (the outcome's time is then the time of that event's step), and an observer.
pub fn play_lockstep(
    mut play: LockstepPlay<'_>,
    loaded: SimulatedTask,
) -> Result<LockstepOutcome, PhysicsError> {
    let config = play.config;
    let model = play.model;
    let arm_start = config
        .arm
        .start_pose_isometry()
        .map_err(|e| PhysicsError::Progress {
            message: format!("arm start pose: {e}"),
        })?;
    let robot = PhysicsRobotConfig::for_station(config, &loaded, arm_start);
    let mut station_config = config.clone();
    set_engage(&mut station_config, Engage::OnFirstFrame);
    // Built as every live path builds it: with the configured calibration profile.
    let (mut station, _) =
        build_station(&station_config, model.clone()).map_err(|e| PhysicsError::Progress {
            message: format!("station: {e}"),
        })?;
    let mut sim = SimState::new(loaded.engine, &robot)?;
    let mut outcome = LockstepOutcome::default();
    let limits: Vec<_> = model.limits().collect();
    let dt = 1.0 / play.rate_hz;
    let mut ticks =
        TickSchedule::starting_at(0, steps_per_tick(play.rate_hz, config.control.rate_hz));
    let steps = (play.duration_s / dt).round() as u64;
    let mut taken = 0;
    for k in 0..steps {
        let t = k as f64 * dt;
        let now_ns = (t * 1e9) as i64;
        let feedback = isometry_to_pose(&sim.arm_pose);
        let mut inputs = vec![StationInput::ArmFeedback(feedback)];
        if play.glove.sends_at(t) {
            let (points, wrist) = play.glove.frame(t);
            inputs.push(StationInput::Wrist(isometry_to_pose(&wrist)));
            inputs.push(StationInput::Keypoints(KeypointFrame {
                points,
                source_ns: now_ns,
            }));
        }
        if ticks.due(k as i64).is_some() {
            inputs.push(StationInput::Control(ControlInput::Tick));
        }
        for input in inputs {
            if let Some(observer) = play.observer.as_deref_mut() {
                observer.input(now_ns, &input);
            }
            let outputs = station.step(input, now_ns);
            if let Some(observer) = play.observer.as_deref_mut() {
                observer.outputs(now_ns, &outputs);
            }
            let mut robot_sink = PhysicsSink {
                sim: &mut sim,
                model,
                limits: &limits,
                outcome: &mut outcome,
            };
            let Ok(()) = route(&outputs, now_ns, &mut robot_sink);
        }
        let before = outcome.events.len();
        for event in sim.advance(dt, &robot) {
            let message = sim.progress_message(&event, &robot);
            if let Some(observer) = play.observer.as_deref_mut() {
                observer.progress(&message);
            }
            outcome.events.push(message);
        }
        taken = k + 1;
        // Asked only when the physics made an event: nothing else changes the answer.
        let new_events = outcome.events.len() > before;
        if new_events && play.until.is_some_and(|until| until(&outcome.events)) {
            break;
        }
    }
    outcome.progress = sim.tracker.as_ref().map_or(0.0, |t| t.total());
    outcome.final_reading = robot
        .progress
        .as_ref()
        .and_then(|(_, mapping)| sim.engine.reading(&mapping.joint));
    outcome.sim_time_s = taken as f64 * dt;
    Ok(outcome)
}

/// The simulated robot as the station's sink: hand commands become the hand's servo targets,
/// arm targets the arm's slew target; both counted in the outcome.
struct PhysicsSink<'a> {
    sim: &'a mut SimState,
    model: &'a HandModel,
    limits: &'a [retarget::Limits],
    outcome: &'a mut LockstepOutcome,
}

impl OutputSink for PhysicsSink<'_> {
    type Error = std::convert::Infallible;

    fn notice(&mut self, _notice: &Notice) -> Result<(), Self::Error> {
        Ok(())
    }

    fn hand(&mut self, _now_ns: i64, hand: &HandMessages, _fresh: bool) -> Result<(), Self::Error> {
        let current = self.sim.engine.hand_targets();
        let targets = joint_state_target(self.model, self.limits, current, &hand.joint_state);
        if targets.is_some_and(|t| self.sim.engine.set_hand_targets(&t).is_ok()) {
            self.outcome.hand_commands += 1;
        }
        Ok(())
    }

    fn arm(&mut self, _now_ns: i64, arm: &PoseStamped) -> Result<(), Self::Error> {
        if let Some(target) = station::convert::pose_to_isometry(&arm.pose) {
            self.sim.arm_target = target;
            self.outcome.arm_targets += 1;
        }
        Ok(())
    }
}
