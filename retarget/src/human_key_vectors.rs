//! Human side of the energy: validated keypoints → fingertips in the human palm frame, mapped
//! through the calibration transform, plus the raw thumb-to-fingertip distances that drive the
//! pinch blend.

use nalgebra::{Point3, Vector3};

use crate::calibration_transform::CalibrationTransform;
use crate::error::Error;
use crate::finger::Finger;
use crate::keypoint_layout::KeypointLayout;
use crate::palm_frame::PalmFrame;

/// One frame of human input, reduced to what the energy uses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HumanKeyVectors {
    /// Fingertips in the human palm frame, after the calibration transform (each digit's
    /// length factor about its base, then `scale · R`), metres (index by
    /// [`Finger::index`]). Palm-to-tip key vectors are these; tip-to-tip ones their
    /// differences.
    pub tips: [Vector3<f64>; 5],
    /// Each digit's second keypoint (finger PIP, thumb MCP), same frame and map as `tips`.
    pub mids: [Vector3<f64>; 5],
    /// Thumb-tip to fingertip distances (index, middle, ring, little), metres, as the glove
    /// measured them (no calibration applied).
    pub pinch_distances_m: [f64; 4],
}

impl HumanKeyVectors {
    /// Each digit's tip and mid point a share `t[digit]` (0..=1) of the way toward `other`'s;
    /// the pinch distances stay this frame's.
    pub fn toward(&self, other: &HumanKeyVectors, t: [f64; 5]) -> HumanKeyVectors {
        let lerp = |a: &[Vector3<f64>; 5], b: &[Vector3<f64>; 5]| {
            std::array::from_fn(|i| a[i] + t[i] * (b[i] - a[i]))
        };
        HumanKeyVectors {
            tips: lerp(&self.tips, &other.tips),
            mids: lerp(&self.mids, &other.mids),
            pinch_distances_m: self.pinch_distances_m,
        }
    }
}

/// Check a frame of keypoints against its layout: count and finiteness.
pub fn validate_keypoints(layout: KeypointLayout, points: &[Point3<f64>]) -> Result<(), Error> {
    if points.len() != layout.len() {
        return Err(Error::KeypointCount {
            layout: layout.name(),
            expected: layout.len(),
            got: points.len(),
        });
    }
    if let Some(index) = points
        .iter()
        .position(|p| !p.coords.iter().all(|c| c.is_finite()))
    {
        return Err(Error::NonFiniteKeypoint {
            index,
            name: layout.point_name(index).unwrap_or_default(),
        });
    }
    Ok(())
}

/// Reduce a frame of keypoints to the energy's human key vectors.
pub fn human_key_vectors(
    layout: KeypointLayout,
    points: &[Point3<f64>],
    transform: &CalibrationTransform,
) -> Result<HumanKeyVectors, Error> {
    validate_keypoints(layout, points)?;
    let palm = PalmFrame::from_landmarks(&layout.palm_landmarks(points))?;
    let map = transform.matrix();
    let in_palm = |i: usize| palm.point_to_palm(&points[i]);
    let bases = Finger::ALL.map(|f| in_palm(layout.chain(f)[0]));
    let mapped = |f: Finger, i: usize| {
        map * transform.lengthen_digit(f.index(), &bases[f.index()], &in_palm(i))
    };
    let tips = Finger::ALL.map(|f| mapped(f, layout.tip(f)));
    let mids = Finger::ALL.map(|f| mapped(f, layout.chain(f)[1]));
    let thumb = points[layout.tip(Finger::Thumb)];
    let pinch_distances_m = Finger::OPPOSING.map(|f| (points[layout.tip(f)] - thumb).norm());
    Ok(HumanKeyVectors {
        tips,
        mids,
        pinch_distances_m,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat_hand(layout: KeypointLayout) -> Vec<Point3<f64>> {
        // Wrist at the origin, digits fanned along +y, 2 cm apart in x; chain points 3 cm apart.
        let mut points = vec![Point3::origin(); layout.len()];
        if let Some(f) = layout.forearm() {
            points[f] = Point3::new(0.0, -0.25, 0.0);
        }
        for finger in Finger::ALL {
            let x = 0.04 - 0.02 * finger.index() as f64;
            for (k, &i) in layout.chain(finger).iter().enumerate() {
                points[i] = Point3::new(x, 0.08 + 0.03 * k as f64, 0.0);
            }
        }
        points
    }

    #[test]
    fn tips_are_expressed_in_the_palm_frame_and_scaled() {
        let points = flat_hand(KeypointLayout::Lab22);
        let transform = CalibrationTransform {
            scale: 2.0,
            ..CalibrationTransform::IDENTITY
        };
        let h = human_key_vectors(KeypointLayout::Lab22, &points, &transform).unwrap();
        // Palm origin: midpoint of thumb base (0.04, 0.08) and little base (-0.04, 0.08).
        let middle = h.tips[Finger::Middle.index()];
        assert!(
            (middle - Vector3::new(0.0, 0.18, 0.0)).norm() < 1e-12,
            "{middle}"
        );
        assert!((h.pinch_distances_m[0] - 0.02).abs() < 1e-12, "unscaled");
    }

    #[test]
    fn bad_frames_are_rejected_with_a_reason() {
        let mut points = flat_hand(KeypointLayout::Lab21);
        let err = human_key_vectors(
            KeypointLayout::Lab22,
            &points,
            &CalibrationTransform::IDENTITY,
        )
        .unwrap_err();
        assert_eq!(
            err.to_string(),
            "keypoints: layout lab22 has 22 points, got 21"
        );
        points[8].y = f64::NAN;
        let err = human_key_vectors(
            KeypointLayout::Lab21,
            &points,
            &CalibrationTransform::IDENTITY,
        )
        .unwrap_err();
        assert_eq!(
            err.to_string(),
            "keypoints: point 8 (index_tip) is not finite"
        );
        let collapsed = vec![Point3::new(0.1, 0.1, 0.1); 21];
        let err = human_key_vectors(
            KeypointLayout::MediaPipe21,
            &collapsed,
            &CalibrationTransform::IDENTITY,
        )
        .unwrap_err();
        assert!(err.to_string().contains("collapsed palm frame"), "{err}");
    }
}
