//! The palm frame, built the same way from human keypoints and from the robot model.
//!
//! From the wrist point `w` and the five digit bases `b_thumb … b_little` (metres, any frame):
//!
//! - origin `c = ½ (b_thumb + b_little)`;
//! - `y = normalise(b_middle − w)` (towards the fingers);
//! - `x = normalise(d − (d·y) y)` with `d = b_index − b_ring` (across the knuckles, towards the
//!   index side);
//! - `z = x × y`.
//!
//! For a right hand `z` points out of the palm (palmar side); for a left hand the same
//! construction points it out of the back. Human and robot frames are built identically, so
//! key vectors expressed in them compare directly. The robot's landmarks are its named frames
//! (wrist on the wrist flexion axis, thumb base at the thumb's first joint, finger bases at
//! their abduction joints), all rigid with the palm, so the robot palm frame is fixed to the
//! palm link.

use nalgebra::{Matrix3, Point3, Rotation3, Vector3};

use crate::error::Error;
use crate::finger::Finger;
use crate::forward_kinematics::FkState;
use crate::hand_model::HandModel;

/// Shortest axis (before normalisation) accepted when building a palm frame, metres.
/// A real palm measures 40–100 mm along these axes; 2 mm means the points have collapsed.
pub const MIN_PALM_AXIS_M: f64 = 0.002;

/// The points a palm frame is built from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PalmLandmarks {
    /// Wrist point.
    pub wrist: Point3<f64>,
    /// Digit bases, indexed by [`Finger::index`].
    pub bases: [Point3<f64>; 5],
}

/// A right-handed orthonormal frame attached to the palm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PalmFrame {
    /// Origin, in the frame the landmarks were given in (metres).
    pub origin: Point3<f64>,
    /// Columns are the palm's x, y, z axes in that frame.
    pub rotation: Rotation3<f64>,
}

impl PalmFrame {
    /// Build the palm frame from its landmarks; `Err(CollapsedPalm)` when an axis is shorter
    /// than [`MIN_PALM_AXIS_M`] or a landmark is not finite.
    pub fn from_landmarks(landmarks: &PalmLandmarks) -> Result<PalmFrame, Error> {
        let base = |f: Finger| landmarks.bases[f.index()];
        let collapsed = |reason: String| Err(Error::CollapsedPalm { reason });
        let y_raw = base(Finger::Middle) - landmarks.wrist;
        let y_len = y_raw.norm();
        if !y_len.is_finite() || y_len < MIN_PALM_AXIS_M {
            return collapsed(format!(
                "wrist to middle base is {:.2} mm (needs ≥ {} mm)",
                y_len * 1e3,
                MIN_PALM_AXIS_M * 1e3
            ));
        }
        let y = y_raw / y_len;
        let d = base(Finger::Index) - base(Finger::Ring);
        let x_raw = d - y * d.dot(&y);
        let x_len = x_raw.norm();
        if !x_len.is_finite() || x_len < MIN_PALM_AXIS_M {
            return collapsed(format!(
                "index base to ring base, across the palm, is {:.2} mm (needs ≥ {} mm)",
                x_len * 1e3,
                MIN_PALM_AXIS_M * 1e3
            ));
        }
        let x = x_raw / x_len;
        let z = x.cross(&y);
        let origin = Point3::from((base(Finger::Thumb).coords + base(Finger::Little).coords) * 0.5);
        if !origin.coords.iter().all(|v| v.is_finite()) {
            return collapsed("a thumb or little base is not finite".into());
        }
        Ok(PalmFrame {
            origin,
            rotation: Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[x, y, z])),
        })
    }

    /// Coordinates of point `p` in the palm frame.
    pub fn point_to_palm(&self, p: &Point3<f64>) -> Vector3<f64> {
        self.rotation.inverse_transform_vector(&(p - self.origin))
    }

    /// Components of free vector `v` in the palm frame.
    pub fn vector_to_palm(&self, v: &Vector3<f64>) -> Vector3<f64> {
        self.rotation.inverse_transform_vector(v)
    }
}

impl HandModel {
    /// The robot's palm landmarks for the pose in `state`.
    pub fn palm_landmarks(&self, state: &FkState) -> PalmLandmarks {
        PalmLandmarks {
            wrist: state.position(self.frames.wrist),
            bases: self.frames.bases.map(|b| state.position(b)),
        }
    }

    /// The robot's palm frame for the pose in `state`, in the model's base frame.
    pub fn palm_frame(&self, state: &FkState) -> Result<PalmFrame, Error> {
        PalmFrame::from_landmarks(&self.palm_landmarks(state))
    }

    /// Reject models whose named frames do not span a palm frame at the zero pose.
    pub(crate) fn check_palm_frame(&self) -> Result<(), Error> {
        let state = self.forward_new(&self.zero_pose())?;
        match self.palm_frame(&state) {
            Err(Error::CollapsedPalm { reason }) => Err(Error::DegeneratePalm { reason }),
            other => other.map(|_| ()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn landmarks() -> PalmLandmarks {
        PalmLandmarks {
            wrist: Point3::new(0.0, 0.0, 0.0),
            bases: [
                Point3::new(0.03, 0.03, 0.0),
                Point3::new(0.025, 0.09, 0.0),
                Point3::new(0.0, 0.09, 0.0),
                Point3::new(-0.02, 0.085, 0.0),
                Point3::new(-0.04, 0.075, 0.0),
            ],
        }
    }

    #[test]
    fn frame_follows_the_documented_construction() {
        let frame = PalmFrame::from_landmarks(&landmarks()).unwrap();
        let r = frame.rotation.matrix();
        assert!(
            (r.column(1) - Vector3::y()).norm() < 1e-12,
            "y towards the middle base"
        );
        assert!(
            (r.column(0) - Vector3::x()).norm() < 1e-12,
            "x across the knuckles"
        );
        assert!((r.column(2) - Vector3::z()).norm() < 1e-12, "z = x × y");
        assert!((frame.origin - Point3::new(-0.005, 0.0525, 0.0)).norm() < 1e-12);
        let p = frame.point_to_palm(&Point3::new(0.0, 0.1, 0.0));
        assert!((p - Vector3::new(0.005, 0.0475, 0.0)).norm() < 1e-12);
    }

    #[test]
    fn collapsed_points_are_rejected_with_the_axis_named() {
        let mut l = landmarks();
        l.bases[Finger::Middle.index()] = l.wrist;
        let err = PalmFrame::from_landmarks(&l).unwrap_err().to_string();
        assert!(err.contains("wrist to middle base"), "{err}");

        let mut l = landmarks();
        l.bases[Finger::Ring.index()] =
            l.bases[Finger::Index.index()] + Vector3::new(0.0, 1e-4, 0.0);
        let err = PalmFrame::from_landmarks(&l).unwrap_err().to_string();
        assert!(err.contains("across the palm"), "{err}");

        let mut l = landmarks();
        l.wrist.x = f64::NAN;
        assert!(PalmFrame::from_landmarks(&l).is_err());
    }

    #[test]
    fn orca_palm_frame_is_rigid_with_the_palm_link() {
        let model = HandModel::orca_v1_right();
        let palm = model.frames().palm;
        let rest = model.forward_new(&model.zero_pose()).unwrap();
        let mut q = model.zero_pose();
        q[model.dof_index("wrist").unwrap()] = 0.5;
        q[model.dof_index("index_mcp").unwrap()] = 1.0;
        let bent = model.forward_new(&q).unwrap();
        let in_palm_link = |state: &FkState| {
            let frame = model.palm_frame(state).unwrap();
            let link = state.pose(palm);
            (
                link.inverse_transform_point(&frame.origin),
                link.rotation.inverse()
                    * nalgebra::UnitQuaternion::from_rotation_matrix(&frame.rotation),
            )
        };
        let (o1, r1) = in_palm_link(&rest);
        let (o2, r2) = in_palm_link(&bent);
        assert!((o1 - o2).norm() < 1e-12);
        assert!(r1.angle_to(&r2) < 1e-12);
    }
}
