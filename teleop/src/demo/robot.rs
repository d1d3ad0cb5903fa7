//! The robot a demo drives: the mock hand and mock Franka, or (feature `physics`,
//! `pomdar demo --physics`) the simulated robot in a MuJoCo task scene, whose physics measures
//! the task's progress.

use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use retarget::HandModel;
use scoring::{Mark, TaskSpec};
use serde::Serialize;
use tokio::sync::watch;

use super::DemoError;
use crate::clock::StationClock;
use crate::stand_ins::mock_franka::MockFrankaReport;
use crate::stand_ins::mock_hand::MockHandReport;
use crate::stand_ins::mock_robot::{MockRobot, spawn_mock_robot};
use crate::stand_ins::progress_message::ProgressMessage;
use station::StationConfig;

/// A demo in a simulated task: which task, and the lab's own scene file if not the project's.
#[derive(Debug, Clone)]
pub struct PhysicsTask {
    /// The catalog entry.
    pub task: TaskSpec,
    /// A lab's own MJCF (`None`: the project's scaffold).
    pub scene: Option<PathBuf>,
    /// Keep every measured hand state with its target (tests of tracking).
    pub record_states: bool,
}

/// What the physics measured in a demo.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct PhysicsOutcome {
    /// The task.
    pub task: String,
    /// Its progress at the end, in `unit`.
    pub progress: f64,
    /// Notches, curves, deg, mm or level.
    pub unit: String,
    /// The correctness the progress events give (`scoring::correctness`).
    pub correctness: Option<f64>,
    /// Simulated seconds per wall second spent stepping.
    pub realtime_factor: f64,
    /// Wall time the physics could not keep up with, seconds.
    pub behind_s: f64,
    /// Hand targets the simulated robot received.
    pub hand_targets: u64,
    /// Every progress event.
    #[serde(skip)]
    pub events: Vec<ProgressMessage>,
    /// Measured hand positions with the target in force, at the state rate (with
    /// `record_states`).
    #[serde(skip)]
    pub states: Vec<(Vec<f64>, Vec<f64>)>,
}

/// What the robot's nodes saw.
#[derive(Debug, Clone, Default)]
pub struct RobotReports {
    /// The mock hand's report (the simulated robot's hand target count only).
    pub hand: MockHandReport,
    /// The mock arm's report (the simulated robot's arm target count only).
    pub arm: MockFrankaReport,
    /// The physics' measurements, with `--physics`.
    pub physics: Option<PhysicsOutcome>,
}

/// The robot a demo drives.
pub enum DemoRobot {
    /// The mock hand and Franka.
    Mock(MockRobot),
    /// The simulated robot.
    #[cfg(feature = "physics")]
    Physics(Box<(crate::physics::robot_node::PhysicsRobot, TaskSpec)>),
}

impl DemoRobot {
    /// Start the robot for `station` until `stop`.
    pub fn spawn(
        station: &StationConfig,
        model: &HandModel,
        clock: StationClock,
        stop: &watch::Receiver<bool>,
        physics: Option<&PhysicsTask>,
    ) -> Result<DemoRobot, DemoError> {
        match physics {
            None => Ok(DemoRobot::Mock(spawn_mock_robot(
                station, model, clock, stop,
            )?)),
            #[cfg(feature = "physics")]
            Some(p) => spawn_physics(station, model, clock, stop, p),
            #[cfg(not(feature = "physics"))]
            Some(_) => Err(DemoError::NoPhysics),
        }
    }

    /// The live status line's robot part.
    pub fn status(&self, clock: StationClock) -> String {
        match self {
            DemoRobot::Mock(robot) => mock_status(&robot.hand_report, clock),
            #[cfg(feature = "physics")]
            DemoRobot::Physics(physics) => match physics.0.report.lock() {
                Ok(r) => format!(
                    "hand targets {:>6}  simulated {:>6.1} s  progress {}",
                    r.hand_targets, r.sim_time_s, r.progress_total
                ),
                Err(_) => String::new(),
            },
        }
    }

    /// Targets heard so far: (hand, arm).
    pub fn heard(&self) -> (u64, u64) {
        match self {
            DemoRobot::Mock(robot) => (
                robot.hand_report.lock().map_or(0, |r| r.targets),
                robot.arm_report.lock().map_or(0, |r| r.commands),
            ),
            #[cfg(feature = "physics")]
            DemoRobot::Physics(physics) => physics
                .0
                .report
                .lock()
                .map_or((0, 0), |r| (r.hand_targets, r.arm_targets)),
        }
    }

    /// Waits until the robot has heard `sent` (hand, arm) targets, at most `limit`: what the
    /// station sent last is on its way when the station stops, and a loaded machine can take
    /// longer to deliver it than any fixed pause. A target lost on the way ends the wait at
    /// `limit`.
    pub async fn wait_to_hear(&self, sent: (u64, u64), limit: Duration) {
        let start = tokio::time::Instant::now();
        while start.elapsed() < limit {
            let (hand, arm) = self.heard();
            if hand >= sent.0 && arm >= sent.1 {
                return;
            }
            tokio::time::sleep(Duration::from_millis(10)).await;
        }
    }

    /// Stop (after `stop` was sent) and collect the reports.
    pub async fn finish(self) -> Result<RobotReports, DemoError> {
        match self {
            DemoRobot::Mock(robot) => {
                super::join("mock hand task", robot.hand).await?;
                super::join("mock arm task", robot.arm).await?;
                Ok(RobotReports {
                    hand: lock_clone(&robot.hand_report),
                    arm: lock_clone(&robot.arm_report),
                    physics: None,
                })
            }
            #[cfg(feature = "physics")]
            DemoRobot::Physics(physics) => {
                let (robot, task) = *physics;
                super::join("simulated robot task", robot.task).await?;
                Ok(physics_reports(&lock_clone(&robot.report), &task))
            }
        }
    }
}

#[cfg(feature = "physics")]
fn spawn_physics(
    station: &StationConfig,
    model: &HandModel,
    clock: StationClock,
    stop: &watch::Receiver<bool>,
    physics: &PhysicsTask,
) -> Result<DemoRobot, DemoError> {
    use crate::physics::robot_node::{PhysicsRobotOptions, spawn_physics_robot};
    use crate::physics::setup::{ProjectScene, SceneSource, load_task};
    let source = match &physics.scene {
        Some(path) => SceneSource::LabFile(path),
        None => SceneSource::Project(ProjectScene::for_station(station)),
    };
    let arm_start = station
        .arm
        .start_pose_isometry()
        .map_err(|source| crate::stand_ins::SimError::ArmStartPose { source })?;
    let loaded = load_task(&physics.task, model, source, arm_start)?;
    let options = PhysicsRobotOptions {
        record_states: physics.record_states,
    };
    let robot = spawn_physics_robot(station, model, loaded, clock, stop, options, None)?;
    Ok(DemoRobot::Physics(Box::new((robot, physics.task.clone()))))
}

/// The reports of a simulated robot run of `task`.
#[cfg(feature = "physics")]
fn physics_reports(
    r: &crate::physics::robot_node::PhysicsRobotReport,
    task: &TaskSpec,
) -> RobotReports {
    let correctness = physics_correctness(task, &r.events).ok();
    let physics = PhysicsOutcome {
        task: task.id.clone(),
        progress: r.progress_total,
        unit: task.correctness.progress_unit().to_string(),
        correctness,
        realtime_factor: if r.step_wall_s > 0.0 {
            r.sim_time_s / r.step_wall_s
        } else {
            0.0
        },
        behind_s: r.behind_s,
        hand_targets: r.hand_targets,
        events: r.events.clone(),
        states: r.states.clone(),
    };
    RobotReports {
        hand: MockHandReport {
            targets: r.hand_targets,
            ..MockHandReport::default()
        },
        arm: MockFrankaReport {
            commands: r.arm_targets,
            ..MockFrankaReport::default()
        },
        physics: Some(physics),
    }
}

/// The correctness of `task` from the physics' progress events, each made the mark the
/// operator's key would make at its simulated time.
pub fn physics_correctness(task: &TaskSpec, events: &[ProgressMessage]) -> Result<f64, String> {
    let marks: Vec<(i64, Mark)> = events
        .iter()
        .map(|e| ((e.sim_time_s * 1e9) as i64, progress_mark(e)))
        .collect();
    scoring::correctness(&task.correctness, &marks, None).map(|c| c.value)
}

/// The mark a progress event makes in a trial (as the operator's key would).
pub fn progress_mark(event: &ProgressMessage) -> Mark {
    match event.value {
        Some(v) if event.event == "progress" => Mark::Progress(v),
        _ => Mark::Drop,
    }
}

/// The mock hand's joint targets in the last second and its latency.
fn mock_status(report: &Arc<Mutex<MockHandReport>>, clock: StationClock) -> String {
    let Ok(report) = report.lock() else {
        return String::new();
    };
    let recent = report
        .receive_times_ns
        .iter()
        .filter(|&&t| clock.now_ns() - t < 1_000_000_000)
        .count();
    format!(
        "joint targets {recent:>4}/s  latency p50 {:>6} ms  p99 {:>6} ms  total {}",
        fmt_ms(report.latency.percentile(0.5)),
        fmt_ms(report.latency.percentile(0.99)),
        report.targets
    )
}

fn fmt_ms(value: Option<f64>) -> String {
    value.map_or("-".into(), |v| format!("{v:.2}"))
}

fn lock_clone<T: Clone + Default>(shared: &Arc<Mutex<T>>) -> T {
    shared.lock().map(|r| r.clone()).unwrap_or_default()
}
