//! Recorded hand motion: one trial's keypoint frames, and their checks.

use nalgebra::Point3;
use retarget::KeypointLayout;

use crate::skip::SkipReason;

/// One recorded trial's hand motion.
#[derive(Debug, Clone, PartialEq)]
pub struct TrialMotion {
    /// Participant label.
    pub participant: String,
    /// Task label (the figures colour by it).
    pub task: String,
    /// Trial label, e.g. the file name.
    pub trial: String,
    /// Keypoint layout of every frame.
    pub layout: KeypointLayout,
    /// Frames in time order.
    pub frames: Vec<MotionFrame>,
}

/// One frame of keypoints.
#[derive(Debug, Clone, PartialEq)]
pub struct MotionFrame {
    /// Seconds since the trial started.
    pub t_s: f64,
    /// Keypoints in the layout's order, metres, in any fixed frame.
    pub points: Vec<Point3<f64>>,
}

impl TrialMotion {
    /// `Err` with the first problem: no frames, a wrong point count, a non-finite time or
    /// point, or times that do not strictly increase.
    pub fn check(&self) -> Result<(), SkipReason> {
        if self.frames.is_empty() {
            return Err(SkipReason::NoFrames);
        }
        let mut previous_s = None;
        for (frame, f) in self.frames.iter().enumerate() {
            if f.points.len() != self.layout.len() {
                return Err(SkipReason::WrongPointCount {
                    frame,
                    found: f.points.len(),
                    expected: self.layout.len(),
                    layout: self.layout.name(),
                });
            }
            if !f.t_s.is_finite() {
                return Err(SkipReason::NonFiniteTime { frame, t_s: f.t_s });
            }
            if let Some(point) = f
                .points
                .iter()
                .position(|p| !p.iter().all(|v| v.is_finite()))
            {
                let name = self.layout.point_name(point).unwrap_or_default();
                return Err(SkipReason::NonFinitePoint { frame, point, name });
            }
            if let Some(previous_s) = previous_s
                && f.t_s <= previous_s
            {
                return Err(SkipReason::TimeNotIncreasing {
                    frame,
                    previous_s,
                    t_s: f.t_s,
                });
            }
            previous_s = Some(f.t_s);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn trial(times: &[f64]) -> TrialMotion {
        TrialMotion {
            participant: "P1".into(),
            task: "grasp".into(),
            trial: "t1.mcap".into(),
            layout: KeypointLayout::Lab21,
            frames: (times.iter())
                .map(|&t_s| MotionFrame {
                    t_s,
                    points: vec![Point3::origin(); 21],
                })
                .collect(),
        }
    }

    #[test]
    fn each_problem_is_found_and_located() {
        assert_eq!(trial(&[0.0, 0.01]).check(), Ok(()));
        assert_eq!(trial(&[]).check(), Err(SkipReason::NoFrames));
        let err = trial(&[0.0, 0.01, 0.01]).check().unwrap_err();
        assert_eq!(
            err.to_string(),
            "frame 2 is at 0.01 s, not after the previous frame at 0.01 s (times must strictly increase)"
        );
        assert!(matches!(
            trial(&[0.0, f64::NAN]).check(),
            Err(SkipReason::NonFiniteTime { frame: 1, .. })
        ));
        let mut t = trial(&[0.0, 0.01]);
        t.frames[1].points[8].y = f64::INFINITY;
        assert_eq!(
            t.check().unwrap_err().to_string(),
            "frame 1, point 8 (index_tip) is not finite"
        );
        let mut t = trial(&[0.0, 0.01]);
        t.frames[0].points.pop();
        assert_eq!(
            t.check().unwrap_err().to_string(),
            "frame 0 has 20 points but layout lab21 has 21"
        );
    }
}
