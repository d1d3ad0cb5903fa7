//! A plausible moving hand: the simulated glove's task-like motion with a wide wrist sway, so
//! the station engages, retargets and drives the arm (into its step caps and workspace box).

use nalgebra::{Isometry3, Point3};
use retarget::KeypointLayout;
use retarget::human_hand::{HumanHandShape, Motion, MotionKind, SimGlove, WristSway};

/// The sway of the wrist: wide and quick enough to reach the arm's step caps (0.25 m/s at
/// 25 Hz) and the default workspace box's faces.
const SWAY: WristSway = WristSway {
    amplitude_m: [0.25, 0.15, 0.2],
    amplitude_rad: [0.4, 0.3, 0.5],
    period_s: 5.0,
};

/// A simulated glove.
#[derive(Debug, Clone)]
pub struct PlausibleHand {
    glove: SimGlove,
}

impl PlausibleHand {
    /// A hand in `layout` doing the motion `kind` (one cycle in `period_s`).
    pub fn new(
        layout: KeypointLayout,
        kind: MotionKind,
        period_s: f64,
    ) -> Result<PlausibleHand, retarget::Error> {
        let shape = HumanHandShape::average();
        let motion = Motion::new(kind, period_s, &shape)?;
        let glove = SimGlove::new(shape, motion, layout)?.with_wrist_sway(SWAY)?;
        Ok(PlausibleHand { glove })
    }

    /// The keypoints (glove frame, metres) and the wrist pose at `t_s` seconds of the hand's
    /// own time.
    pub fn frame(&self, t_s: f64) -> (Vec<Point3<f64>>, Isometry3<f64>) {
        self.glove.frame(t_s)
    }
}
