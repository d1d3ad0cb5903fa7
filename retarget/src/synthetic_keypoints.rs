//! Keypoints generated from a robot model's own forward kinematics: the robot "as a human"
//! in any layout. Round-trip tests and the quality report use them, where the true pose is
//! known and the ideal tip error is zero.
//!
//! Wrist, digit bases and fingertips are the model's named frames exactly (so the palm frame
//! of these keypoints is the robot palm frame). The second point of each digit is its mid
//! frame (finger PIP, thumb MCP) where the model names one, and the third the next distinct
//! revolute-joint origin towards the tip (ORCA thumb: the DIP joint), else the midpoint of
//! mid and tip (ORCA fingers, whose distal link is rigid). Without mid frames the two middle
//! points are the last two distinct revolute-joint origins between base and tip, or points on
//! the base–tip segment. The forearm point lies 20 cm behind the wrist along the palm's
//! wrist-to-middle-base axis.

use nalgebra::Point3;

use crate::finger::Finger;
use crate::forward_kinematics::FkState;
use crate::hand_model::{HandModel, JointMotion};
use crate::keypoint_layout::KeypointLayout;

/// Distance under which two chain points count as the same, metres.
const SAME_POINT_M: f64 = 1e-3;

/// Forearm point distance behind the wrist, metres.
const FOREARM_M: f64 = 0.2;

impl HandModel {
    /// The robot's keypoints in `layout` for the pose in `state` (base frame, metres).
    pub fn synthetic_keypoints(&self, state: &FkState, layout: KeypointLayout) -> Vec<Point3<f64>> {
        let mut points = vec![Point3::origin(); layout.len()];
        let wrist = state.position(self.frames.wrist);
        points[layout.wrist()] = wrist;
        for finger in Finger::ALL {
            let base = state.position(self.frames.base(finger));
            let tip_link = self.frames.tip(finger);
            let tip = state.position(tip_link);
            let mut middle: Vec<Point3<f64>> = Vec::new();
            for &ji in &self.chains[tip_link.0] {
                let joint = &self.joints[ji];
                if !matches!(joint.motion, JointMotion::Revolute { .. }) {
                    continue;
                }
                let p = state.position(joint.child);
                let below_base = self.chains[self.frames.base(finger).0].contains(&ji);
                let distinct = (p - base).norm() > SAME_POINT_M
                    && middle
                        .last()
                        .is_none_or(|last| (p - last).norm() > SAME_POINT_M);
                if !below_base && distinct {
                    middle.push(p);
                }
            }
            let (m1, m2) = match (self.frames.mids, &middle[..]) {
                (Some(mids), _) => {
                    let m1 = state.position(mids[finger.index()]);
                    let after = middle
                        .iter()
                        .skip_while(|p| (**p - m1).norm() > SAME_POINT_M)
                        .nth(1)
                        .copied();
                    (m1, after.unwrap_or(m1 + (tip - m1) * 0.5))
                }
                (None, [.., a, b]) => (*a, *b),
                (None, [a]) => (*a, a + (tip - a) * 0.5),
                (None, []) => (base + (tip - base) / 3.0, base + (tip - base) * (2.0 / 3.0)),
            };
            let chain = layout.chain(finger);
            points[chain[0]] = base;
            points[chain[1]] = m1;
            points[chain[2]] = m2;
            points[chain[3]] = tip;
        }
        if let Some(forearm) = layout.forearm() {
            let axis = (state.position(self.frames.base(Finger::Middle)) - wrist).normalize();
            points[forearm] = wrist - axis * FOREARM_M;
        }
        points
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orca_keypoints_use_the_named_frames_and_the_joint_origins() {
        let model = HandModel::orca_v1_right();
        let state = model.forward_new(&model.zero_pose()).unwrap();
        for layout in KeypointLayout::ALL {
            let points = model.synthetic_keypoints(&state, layout);
            assert_eq!(points.len(), layout.len());
            let index = layout.chain(Finger::Index);
            assert_eq!(
                points[index[0]],
                state.position(model.frames().base(Finger::Index))
            );
            let pip = state.position(model.link("index_ip").unwrap());
            assert_eq!(points[index[1]], pip);
            assert_eq!(points[index[2]], pip + (points[index[3]] - pip) * 0.5);
            assert_eq!(
                points[index[3]],
                state.position(model.frames().tip(Finger::Index))
            );
            let thumb = layout.chain(Finger::Thumb);
            assert_eq!(
                points[thumb[1]],
                state.position(model.link("thumb_ip").unwrap())
            );
            assert_eq!(
                points[thumb[2]],
                state.position(model.link("thumb_dp").unwrap())
            );
            // The palm frame of the keypoints is the robot palm frame.
            let human = crate::PalmFrame::from_landmarks(&layout.palm_landmarks(&points)).unwrap();
            let robot = model.palm_frame(&state).unwrap();
            assert!((human.origin - robot.origin).norm() < 1e-12);
        }
    }
}
