//! The simulated robot (feature `physics`): the hand and the arm's mount in a MuJoCo scene,
//! stepped in real time, on the same topics as the real robot. It follows the station's hand
//! targets (`sensor_msgs/JointState`, by the URDF's names) and arm targets (`PoseStamped`,
//! slewed at the arm's speed limits, as the mock Franka does), and publishes the hand's
//! measured joint states, the arm's pose (the station's arm feedback), the task object's pose
//! and the task's progress as measured by the physics (`std_msgs/String`, one JSON object per
//! event, see [`ProgressMessage`]).
//!
//! Real time: every tick advances the physics by the wall time since the last one (at most
//! [`MAX_CATCH_UP_S`]; a machine too slow for real time falls behind, and the report says by
//! how much).

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use futures::StreamExt;
use msgs::{JointState, PoseStamped, StringMsg};
use retarget::HandModel;
use ros2_client::Publisher;
use tokio::sync::{mpsc, watch};

use super::engine::PhysicsEngine;
use super::error::PhysicsError;
pub use super::robot_config::PhysicsRobotConfig;
use super::setup::SimulatedTask;
use super::sim_state::SimState;
use crate::clock::StationClock;
use crate::ros::{NetworkConfig, QosConfig, RosNode};
use crate::stand_ins::mock_hand::joint_state_target;
pub use crate::stand_ins::progress_message::ProgressMessage;
use station::convert::{header, isometry_to_pose, pose_to_isometry};

/// Longest physics advance in one tick, seconds: beyond it the simulation falls behind rather
/// than taking a huge step.
pub const MAX_CATCH_UP_S: f64 = 0.05;

/// What the operator or a console asks of the simulation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SimControl {
    /// Put the scene back to its initial state (objects, hand, arm) and count progress from
    /// there: a new trial.
    Reset,
}

/// What the simulated robot saw and did (updated live).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PhysicsRobotReport {
    /// Hand targets received.
    pub hand_targets: u64,
    /// Hand targets naming a joint the hand lacks, or not finite.
    pub hand_rejected: u64,
    /// Arm targets received.
    pub arm_targets: u64,
    /// Arm targets that are not a valid pose.
    pub arm_rejected: u64,
    /// Physics time simulated, seconds.
    pub sim_time_s: f64,
    /// Wall time the physics spent stepping, seconds.
    pub step_wall_s: f64,
    /// Wall time not simulated because a tick was longer than [`MAX_CATCH_UP_S`], seconds.
    pub behind_s: f64,
    /// Progress events published since the start (all resets).
    pub events: Vec<ProgressMessage>,
    /// The progress since the last reset.
    pub progress_total: f64,
    /// Resets done.
    pub resets: u64,
    /// Every measured hand state published with its target in force (tests; only when
    /// [`PhysicsRobotOptions::record_states`]).
    pub states: Vec<(Vec<f64>, Vec<f64>)>,
    /// Messages whose publishing failed.
    pub publish_failed: u64,
}

/// Inputs of a run that are not settings.
pub struct PhysicsRobotRun {
    /// The hand model (names of its degrees of freedom, as the station sends them).
    pub model: HandModel,
    /// The loaded scene.
    pub engine: PhysicsEngine,
    /// Network settings.
    pub network: NetworkConfig,
    /// The clock stamping messages.
    pub clock: StationClock,
    /// Live report.
    pub report: Arc<Mutex<PhysicsRobotReport>>,
    /// Resets.
    pub control: mpsc::Receiver<SimControl>,
    /// A copy of every progress event, for a console in the same process.
    pub events: Option<mpsc::UnboundedSender<ProgressMessage>>,
    /// Stop.
    pub shutdown: watch::Receiver<bool>,
    /// Other options.
    pub options: PhysicsRobotOptions,
}

/// Options of a run.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PhysicsRobotOptions {
    /// Keep every published state and its target in the report (grows without bound).
    pub record_states: bool,
}

/// The endpoints of the simulated robot.
struct Endpoints {
    hand_state: Publisher<JointState>,
    arm_pose: Publisher<PoseStamped>,
    object_pose: Publisher<PoseStamped>,
    progress: Publisher<StringMsg>,
}

impl Endpoints {
    /// The robot's publishers on `config`'s topics.
    fn open(node: &mut RosNode, config: &PhysicsRobotConfig) -> Result<Endpoints, PhysicsError> {
        Ok(Endpoints {
            hand_state: node.publisher(&config.hand_state_topic, QosConfig::best_effort(10))?,
            arm_pose: node.publisher(&config.arm_feedback_topic, QosConfig::best_effort(10))?,
            object_pose: node.publisher(&config.object_topic, QosConfig::best_effort(10))?,
            progress: node.publisher(&config.progress_topic, QosConfig::reliable(100))?,
        })
    }
}

/// One tick's times, seconds: the physics advanced `dt`, stepping took `stepped` of wall time,
/// `elapsed` of wall time passed since the last tick.
#[derive(Debug, Clone, Copy)]
struct TickTiming {
    dt: f64,
    stepped: f64,
    elapsed: f64,
}

/// A tick's times, progress and events into the report; `false` when its lock is poisoned
/// (the run stops).
fn account_tick(
    report: &Mutex<PhysicsRobotReport>,
    sim: &SimState,
    timing: TickTiming,
    messages: &[ProgressMessage],
) -> bool {
    let Ok(mut r) = report.lock() else {
        return false;
    };
    r.sim_time_s += timing.dt;
    r.step_wall_s += timing.stepped;
    r.behind_s += timing.elapsed - timing.dt;
    if let Some(tracker) = &sim.tracker {
        r.progress_total = tracker.total();
    }
    r.events.extend(messages.iter().cloned());
    true
}

/// Run the simulated robot until `shutdown`.
pub async fn run_physics_robot(
    config: PhysicsRobotConfig,
    run: PhysicsRobotRun,
) -> Result<(), PhysicsError> {
    let PhysicsRobotRun {
        model,
        engine,
        network,
        clock,
        report,
        mut control,
        events: events_tx,
        mut shutdown,
        options,
    } = run;
    let mut node = RosNode::join(&network, "/", "pomdar_sim_robot")?;
    let hand_sub =
        node.subscription::<JointState>(&config.hand_targets_topic, QosConfig::reliable(50))?;
    let arm_sub =
        node.subscription::<PoseStamped>(&config.arm_target_topic, QosConfig::reliable(50))?;
    let out = Endpoints::open(&mut node, &config)?;
    let mut hand_targets = Box::pin(hand_sub.async_stream());
    let mut arm_targets = Box::pin(arm_sub.async_stream());
    let mut sim = SimState::new(engine, &config)?;
    let mut hand_target = sim.engine.hand_positions();
    let limits: Vec<_> = model.limits().collect();
    let mut ticks = tokio::time::interval(Duration::from_secs_f64(config.tick_s));
    let publish_every = (1.0 / (config.state_rate_hz * config.tick_s))
        .round()
        .max(1.0) as u64;
    let mut last_tick = Instant::now();
    let mut tick_count = 0u64;
    loop {
        tokio::select! {
            _ = shutdown.changed() => if *shutdown.borrow() { break },
            Some(request) = control.recv() => match request {
                SimControl::Reset => {
                    sim.reset(&config)?;
                    hand_target = sim.engine.hand_positions();
                    if let Ok(mut r) = report.lock() { r.resets += 1; r.progress_total = 0.0; }
                }
            },
            Some(Ok((message, _))) = hand_targets.next() => {
                let accepted = joint_state_target(&model, &limits, &hand_target, &message)
                    .filter(|next| sim.engine.set_hand_targets(next).is_ok());
                let Ok(mut r) = report.lock() else { break };
                r.hand_targets += 1;
                match accepted { Some(next) => hand_target = next, None => r.hand_rejected += 1 }
            }
            Some(Ok((message, _))) = arm_targets.next() => {
                let Ok(mut r) = report.lock() else { break };
                r.arm_targets += 1;
                match pose_to_isometry(&message.pose) {
                    Some(pose) => sim.arm_target = pose,
                    None => r.arm_rejected += 1,
                }
            }
            _ = ticks.tick() => {
                let now = Instant::now();
                let elapsed = now.duration_since(last_tick).as_secs_f64();
                last_tick = now;
                let dt = elapsed.min(MAX_CATCH_UP_S);
                let events = sim.advance(dt, &config);
                let stepped = now.elapsed().as_secs_f64();
                tick_count += 1;
                let messages: Vec<ProgressMessage> =
                    events.iter().map(|e| sim.progress_message(e, &config)).collect();
                let timing = TickTiming { dt, stepped, elapsed };
                if !account_tick(&report, &sim, timing, &messages) { break }
                if let Some(tx) = &events_tx {
                    for message in &messages { tx.send(message.clone()).ok(); }
                }
                let failed = publish_progress(&out, &messages).await
                    + if tick_count.is_multiple_of(publish_every) {
                        let states = publish_states(&out, &sim, &model, &config, &clock).await;
                        if options.record_states
                            && let Ok(mut r) = report.lock()
                        {
                            r.states.push((sim.engine.hand_positions(), hand_target.clone()));
                        }
                        states
                    } else { 0 };
                if failed > 0 {
                    let Ok(mut r) = report.lock() else { break };
                    r.publish_failed += failed;
                }
            }
        }
    }
    Ok(())
}

/// Publish progress events; the number that failed.
async fn publish_progress(out: &Endpoints, messages: &[ProgressMessage]) -> u64 {
    let mut failed = 0;
    for message in messages {
        let data = serde_json::to_string(message).unwrap_or_default();
        if out
            .progress
            .async_publish(StringMsg { data })
            .await
            .is_err()
        {
            failed += 1;
        }
    }
    failed
}

/// Publish the hand's state, the arm's pose and the object's pose; the number that failed.
async fn publish_states(
    out: &Endpoints,
    sim: &SimState,
    model: &HandModel,
    config: &PhysicsRobotConfig,
    clock: &StationClock,
) -> u64 {
    let stamp = clock.now_ns();
    let hand = JointState {
        header: header(stamp, ""),
        name: model.ros_dof_names().to_vec(),
        position: sim.engine.hand_positions(),
        velocity: sim.engine.hand_velocities(),
        effort: vec![],
    };
    let mut failed = u64::from(out.hand_state.async_publish(hand).await.is_err());
    let arm = PoseStamped {
        header: header(stamp, &config.frame_id),
        pose: isometry_to_pose(&sim.arm_pose),
    };
    failed += u64::from(out.arm_pose.async_publish(arm).await.is_err());
    let object = config
        .object_body
        .as_deref()
        .and_then(|body| sim.engine.body_pose(body));
    if let Some(pose) = object {
        let message = PoseStamped {
            header: header(stamp, &config.frame_id),
            pose: isometry_to_pose(&pose),
        };
        failed += u64::from(out.object_pose.async_publish(message).await.is_err());
    }
    failed
}

/// A simulated robot running in this process.
#[derive(Debug)]
pub struct PhysicsRobot {
    /// Its task.
    pub task: tokio::task::JoinHandle<Result<(), PhysicsError>>,
    /// What it saw (live).
    pub report: Arc<Mutex<PhysicsRobotReport>>,
    /// Resets.
    pub control: mpsc::Sender<SimControl>,
}

/// Start the simulated robot for `loaded` on `station`'s network and topics, the arm at the
/// station's start pose, until `shutdown`; progress events are also sent to `events`.
pub fn spawn_physics_robot(
    station: &station::StationConfig,
    model: &HandModel,
    loaded: SimulatedTask,
    clock: StationClock,
    shutdown: &watch::Receiver<bool>,
    options: PhysicsRobotOptions,
    events: Option<mpsc::UnboundedSender<ProgressMessage>>,
) -> Result<PhysicsRobot, PhysicsError> {
    let arm_start = station
        .arm
        .start_pose_isometry()
        .map_err(|e| PhysicsError::Progress {
            message: format!("arm start pose: {e}"),
        })?;
    let config = PhysicsRobotConfig::for_station(station, &loaded, arm_start);
    let report = Arc::new(Mutex::new(PhysicsRobotReport::default()));
    let (control, control_rx) = mpsc::channel(8);
    let run = PhysicsRobotRun {
        model: model.clone(),
        engine: loaded.engine,
        network: station.network.clone(),
        clock,
        report: report.clone(),
        control: control_rx,
        events,
        shutdown: shutdown.clone(),
        options,
    };
    let task = tokio::spawn(run_physics_robot(config, run));
    Ok(PhysicsRobot {
        task,
        report,
        control,
    })
}
