//! The pose the hand is commanded to: each pose's joint targets, the pose being commanded,
//! its resend every [`RESEND_S`] as a `sensor_msgs/JointState`, and the sends that could not
//! be published.

use std::time::Duration;

use calibration::PoseSet;
use msgs::JointState;
use retarget::HandModel;
use station::convert::header;

use crate::calibrate::CalibrateError;

/// How often the commanded pose is re-sent, seconds.
const RESEND_S: f64 = 0.1;

/// Each pose's joint targets, in capture order.
pub(super) fn pose_targets(model: &HandModel) -> Result<Vec<Vec<f64>>, CalibrateError> {
    let pose_set = PoseSet::orca_v1();
    pose_set
        .poses
        .iter()
        .map(|p| p.joint_vector(model))
        .collect::<Result<_, _>>()
        .map_err(|source| CalibrateError::PoseTargets { source })
}

/// The pose the hand is sent to, re-sent every [`RESEND_S`].
pub(super) struct HandCommand {
    /// Each pose's joint targets.
    targets: Vec<Vec<f64>>,
    /// The hand's joint names.
    names: Vec<String>,
    /// The pose being commanded.
    pub(super) current: Option<usize>,
    /// Sends of a pose that could not be published.
    pub(super) not_sent: u64,
    /// When to re-send it.
    pub(super) resend: tokio::time::Interval,
}

impl HandCommand {
    pub(super) fn new(targets: Vec<Vec<f64>>, names: Vec<String>) -> HandCommand {
        HandCommand {
            targets,
            names,
            current: None,
            not_sent: 0,
            resend: tokio::time::interval(Duration::from_secs_f64(RESEND_S)),
        }
    }

    /// The hand is sent to pose `k` from now on, starting at once.
    pub(super) fn command(&mut self, k: usize) {
        self.current = Some(k);
        self.resend.reset_immediately();
    }

    /// The hand is sent to no pose any more (the fit has started).
    pub(super) fn stop(&mut self) {
        self.current = None;
    }

    /// The message sending the hand to pose `k`, stamped `now`.
    pub(super) fn message(&self, k: usize, now: i64) -> JointState {
        JointState {
            header: header(now, ""),
            name: self.names.clone(),
            position: self.targets[k].clone(),
            velocity: Vec::new(),
            effort: Vec::new(),
        }
    }

    /// A send's result: a failure is counted, and returned when it is the first (the console
    /// says it once).
    pub(super) fn sent<E>(&mut self, sent: Result<(), E>) -> Option<E> {
        let Err(e) = sent else {
            return None;
        };
        self.not_sent += 1;
        (self.not_sent == 1).then_some(e)
    }
}
