//! The simulated robot between physics steps: the scene, the arm slewing toward its target
//! with the mount following, and the task's progress tracker. Driven in real time by the
//! simulated robot node and in simulated time by the lock-step trial.

use nalgebra::Isometry3;
use simulation::progress::{ProgressEvent, ProgressTracker};

use super::engine::PhysicsEngine;
use super::error::PhysicsError;
use super::robot_config::PhysicsRobotConfig;
use crate::stand_ins::mock_franka::slew_pose;
use crate::stand_ins::progress_message::ProgressMessage;

/// The simulation between ticks.
pub struct SimState {
    /// The loaded scene.
    pub engine: PhysicsEngine,
    /// The arm's pose (the mount's), base frame.
    pub arm_pose: Isometry3<f64>,
    /// The arm target in force.
    pub arm_target: Isometry3<f64>,
    /// The task's progress since the last reset.
    pub tracker: Option<ProgressTracker>,
    reset_sim_time_s: f64,
}

impl SimState {
    /// The scene at its initial state, the arm at the configuration's start.
    pub fn new(
        engine: PhysicsEngine,
        config: &PhysicsRobotConfig,
    ) -> Result<SimState, PhysicsError> {
        let mut state = SimState {
            engine,
            arm_pose: config.arm_start,
            arm_target: config.arm_start,
            tracker: None,
            reset_sim_time_s: 0.0,
        };
        state.reset(config)?;
        Ok(state)
    }

    /// Back to the scene's initial state, the arm at its start, progress from zero.
    pub fn reset(&mut self, config: &PhysicsRobotConfig) -> Result<(), PhysicsError> {
        self.engine.reset();
        self.arm_pose = config.arm_start;
        self.arm_target = config.arm_start;
        self.engine.set_mount_pose(&self.arm_pose);
        self.engine.settle();
        self.reset_sim_time_s = self.engine.time_s();
        self.tracker = match &config.progress {
            Some((kind, mapping)) => {
                let initial =
                    self.engine
                        .reading(&mapping.joint)
                        .ok_or_else(|| PhysicsError::Missing {
                            origin: "scene".into(),
                            kind: "progress joint",
                            names: vec![mapping.joint.clone()],
                        })?;
                Some(ProgressTracker::new(kind, mapping, initial).map_err(|e| {
                    PhysicsError::Progress {
                        message: e.to_string(),
                    }
                })?)
            }
            None => None,
        };
        Ok(())
    }

    /// Advance by `dt_s`: the arm slews toward its target, the mount follows, the physics
    /// steps; the progress events of the step.
    pub fn advance(&mut self, dt_s: f64, config: &PhysicsRobotConfig) -> Vec<ProgressEvent> {
        slew_pose(
            &mut self.arm_pose,
            &self.arm_target,
            config.arm_max_speed_m_s * dt_s,
            config.arm_max_rate_rad_s * dt_s,
        );
        self.engine.set_mount_pose(&self.arm_pose);
        self.engine.advance(dt_s);
        let t = self.engine.time_s() - self.reset_sim_time_s;
        match (&mut self.tracker, &config.progress) {
            (Some(tracker), Some((_, mapping))) => match self.engine.reading(&mapping.joint) {
                Some(reading) => tracker.update(reading, t),
                None => Vec::new(),
            },
            _ => Vec::new(),
        }
    }

    /// An event as published.
    pub fn progress_message(
        &self,
        event: &ProgressEvent,
        config: &PhysicsRobotConfig,
    ) -> ProgressMessage {
        let unit = config
            .progress
            .as_ref()
            .map_or("", |(kind, _)| kind.progress_unit());
        let (name, value) = match event {
            ProgressEvent::Progress(v) => ("progress", Some(*v)),
            ProgressEvent::Drop => ("drop", None),
        };
        ProgressMessage {
            task: config.task_id.clone(),
            event: name.to_string(),
            value,
            unit: unit.to_string(),
            total: self.tracker.as_ref().map_or(0.0, ProgressTracker::total),
            sim_time_s: self.engine.time_s() - self.reset_sim_time_s,
        }
    }
}
