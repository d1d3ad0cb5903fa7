//! Forward kinematics of the human hand model: angles → keypoints in the hand frame, and the
//! placement of those keypoints in a world (glove) frame.
//!
//! ## Geometry
//!
//! Hand frame: wrist joint centre at the origin, `+y` towards the middle finger, `+z` out of
//! the palm, `+x` towards the thumb of a right hand (a left hand is mirrored, `x ↦ −x`).
//! `R_x, R_y, R_z` are right-handed rotations about the frame's axes, `ŷ = (0, 1, 0)`, `s`
//! the hand's scale. For digit `i` with base `b`, bones `L₁, L₂, L₃` and rest angles
//! (splay `σ`, elevation `ε₀`, pronation `γ₀`) from [`HumanHandShape`]:
//!
//! ```text
//! R₁ = R_z(−(σ + δ)) · R_x(ε₀ + ε) · R_y(−(γ₀ + γ))        base joint (thumb CMC, finger MCP)
//! R₂ = R₁ · R_x(φ₂)                                        thumb MCP, finger PIP
//! R₃ = R₂ · R_x(φ₃)                                        thumb IP,  finger DIP
//! p₀ = s·b,  p₁ = p₀ + s·L₁·R₁ŷ,  p₂ = p₁ + s·L₂·R₂ŷ,  p₃ = p₂ + s·L₃·R₃ŷ  (tip)
//! ```
//!
//! with the pose's angles mapped as
//!
//! | digit | δ (towards `+x`) | ε (towards `+z`) | γ | φ₂ | φ₃ |
//! |---|---|---|---|---|---|
//! | thumb | −CMC flexion | CMC abduction | k · CMC abduction | MCP flexion | IP flexion |
//! | index, middle | +MCP abduction | MCP flexion | 0 | PIP flexion | DIP flexion |
//! | ring, little | −MCP abduction | MCP flexion | 0 | PIP flexion | DIP flexion |
//!
//! (`k` = [`HumanHandShape::thumb_pronation_per_abduction`]). So MCP abduction turns a finger
//! in the palm plane and flexion then curls it in its own, turned plane; every flexion turns
//! `ŷ` towards the digit's local `+z` (for fingers the palm side). Bones are rigid: the
//! distance between consecutive chain points is exactly `s·Lₖ` for every pose.
//!
//! ## Keypoints
//!
//! The chain `p₀ … p₃` of each digit fills the layout's four points of that digit: lab
//! proximal / medial / distal / tip = MediaPipe CMC, MCP, IP, tip (thumb) or MCP, PIP, DIP,
//! tip (fingers). The wrist point is the origin; the lab's 22-point layout adds the forearm
//! (elbow) point at `(0, −s·forearm_m, 0)`, behind the wrist.

use nalgebra::{Isometry3, Point3, Rotation3, Vector3};

use super::pose::HumanHandPose;
use super::shape::HumanHandShape;
use crate::finger::Finger;
use crate::keypoint_layout::KeypointLayout;

/// The four chain points (base, second, third, tip) of each digit, indexed by
/// [`Finger::index`], in the hand frame, metres.
pub type DigitChains = [[Point3<f64>; 4]; 5];

/// Base-joint and hinge angles of one digit in the form the geometry uses:
/// `(δ, ε, γ, φ₂, φ₃)` of the module documentation.
fn digit_angles(shape: &HumanHandShape, pose: &HumanHandPose, finger: Finger) -> [f64; 5] {
    match pose.finger(finger) {
        None => {
            let t = &pose.thumb;
            [
                -t.cmc_flexion_rad,
                t.cmc_abduction_rad,
                shape.thumb_pronation_per_abduction * t.cmc_abduction_rad,
                t.mcp_flexion_rad,
                t.ip_flexion_rad,
            ]
        }
        Some(f) => {
            let towards_thumb = match finger {
                Finger::Ring | Finger::Little => -1.0,
                _ => 1.0,
            };
            [
                towards_thumb * f.mcp_abduction_rad,
                f.mcp_flexion_rad,
                0.0,
                f.pip_flexion_rad,
                f.dip_flexion_rad,
            ]
        }
    }
}

impl HumanHandShape {
    /// The four chain points of every digit for `pose`, in the hand frame (mirrored for a left
    /// hand), metres.
    pub fn digit_chains(&self, pose: &HumanHandPose) -> DigitChains {
        self.chains_with_tip_offsets(pose, &[[0.0; 3]; 5])
    }

    /// The chains with each tip moved by its offset in its digit's last-bone frame.
    fn chains_with_tip_offsets(
        &self,
        pose: &HumanHandPose,
        tip_offsets: &[[f64; 3]; 5],
    ) -> DigitChains {
        let rx = |a: f64| Rotation3::from_axis_angle(&Vector3::x_axis(), a);
        let ry = |a: f64| Rotation3::from_axis_angle(&Vector3::y_axis(), a);
        let rz = |a: f64| Rotation3::from_axis_angle(&Vector3::z_axis(), a);
        let s = self.scale;
        let mirror = Vector3::new(self.handedness.x_sign(), 1.0, 1.0);
        Finger::ALL.map(|finger| {
            let g = self.digit(finger);
            let [delta, eps, gamma, phi2, phi3] = digit_angles(self, pose, finger);
            let r1 = rz(-(g.splay_rad + delta))
                * rx(g.elevation_rad + eps)
                * ry(-(g.pronation_rad + gamma));
            let r2 = r1 * rx(phi2);
            let r3 = r2 * rx(phi3);
            let p0 = Point3::from(Vector3::from(g.base_m) * s);
            let p1 = p0 + r1 * Vector3::y() * (s * g.bones_m[0]);
            let p2 = p1 + r2 * Vector3::y() * (s * g.bones_m[1]);
            let p3 = p2
                + r3 * Vector3::y() * (s * g.bones_m[2])
                + r3 * Vector3::from(tip_offsets[finger.index()]);
            [p0, p1, p2, p3].map(|p| Point3::from(p.coords.component_mul(&mirror)))
        })
    }

    /// Keypoints of `pose` in `layout`, in the hand frame (wrist at the origin), metres; each
    /// tip where the glove reports it ([`HumanHandShape::tip_markers_m`]).
    pub fn keypoints(&self, pose: &HumanHandPose, layout: KeypointLayout) -> Vec<Point3<f64>> {
        let chains = self.chains_with_tip_offsets(pose, &self.tip_markers_m);
        let mut points = vec![Point3::origin(); layout.len()];
        if let Some(forearm) = layout.forearm() {
            points[forearm] = Point3::new(0.0, -self.scale * self.forearm_m, 0.0);
        }
        for finger in Finger::ALL {
            for (&i, p) in layout.chain(finger).iter().zip(chains[finger.index()]) {
                points[i] = p;
            }
        }
        points
    }

    /// Keypoints of `pose` in `layout`, placed in a world frame: `hand_in_world` is the pose of
    /// the hand frame (the wrist) in that frame.
    pub fn keypoints_in(
        &self,
        pose: &HumanHandPose,
        layout: KeypointLayout,
        hand_in_world: &Isometry3<f64>,
    ) -> Vec<Point3<f64>> {
        place_points(&self.keypoints(pose, layout), hand_in_world)
    }

    /// Distance from the thumb tip to the tip of `finger` (anatomical tips, not the glove's
    /// markers), metres.
    pub fn thumb_gap_m(&self, pose: &HumanHandPose, finger: Finger) -> f64 {
        let chains = self.digit_chains(pose);
        (chains[Finger::Thumb.index()][3] - chains[finger.index()][3]).norm()
    }
}

/// Map points given in a frame `H` into the world frame, where `h_in_world` is the pose of `H`
/// in the world: `p_world = h_in_world · p_H`.
pub fn place_points(points: &[Point3<f64>], h_in_world: &Isometry3<f64>) -> Vec<Point3<f64>> {
    points.iter().map(|p| h_in_world * p).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::human_hand::shape::Handedness;

    #[test]
    fn open_hand_has_straight_fingers_along_y() {
        let shape = HumanHandShape::average();
        let chains = shape.digit_chains(&HumanHandPose::open());
        let middle = chains[Finger::Middle.index()];
        assert!(
            (middle[3] - Point3::new(0.0, 0.185, 0.0)).norm() < 1e-12,
            "{}",
            middle[3]
        );
        for finger in Finger::OPPOSING {
            let c = chains[finger.index()];
            assert!(
                c.iter().all(|p| p.z.abs() < 1e-12),
                "{finger} leaves the palm plane"
            );
        }
    }

    #[test]
    fn flexion_curls_towards_the_palm_and_abduction_spreads() {
        let shape = HumanHandShape::average();
        let mut pose = HumanHandPose::open();
        pose.fingers[0].mcp_flexion_rad = std::f64::consts::FRAC_PI_2;
        let index = shape.digit_chains(&pose)[Finger::Index.index()];
        let bone = index[1] - index[0];
        assert!(
            (bone - Vector3::new(0.0, 0.0, 0.041)).norm() < 2e-3,
            "{bone}"
        );

        let spread = shape.digit_chains(&HumanHandPose::open_spread());
        let open = shape.digit_chains(&HumanHandPose::open());
        assert!(spread[Finger::Index.index()][3].x > open[Finger::Index.index()][3].x + 0.02);
        assert!(spread[Finger::Little.index()][3].x < open[Finger::Little.index()][3].x - 0.02);
        assert!(spread[Finger::Thumb.index()][3].x > open[Finger::Thumb.index()][3].x);
    }

    #[test]
    fn left_hand_is_the_mirror_image() {
        let right = HumanHandShape::average();
        let left = right.with_handedness(Handedness::Left);
        let pose = HumanHandPose::cylinder_grasp();
        let (r, l) = (
            right.keypoints(&pose, KeypointLayout::Lab22),
            left.keypoints(&pose, KeypointLayout::Lab22),
        );
        for (a, b) in r.iter().zip(&l) {
            assert!((Point3::new(-a.x, a.y, a.z) - b).norm() < 1e-15);
        }
    }

    #[test]
    fn placement_applies_the_isometry() {
        let shape = HumanHandShape::average();
        let pose = HumanHandPose::relaxed();
        let iso = Isometry3::new(Vector3::new(0.1, -0.2, 0.3), Vector3::new(0.2, 0.5, -0.1));
        let local = shape.keypoints(&pose, KeypointLayout::Lab21);
        let world = shape.keypoints_in(&pose, KeypointLayout::Lab21, &iso);
        assert!(
            (world[0] - Point3::new(0.1, -0.2, 0.3)).norm() < 1e-15,
            "wrist"
        );
        for (a, b) in local.iter().zip(&world) {
            assert!((iso.inverse_transform_point(b) - a).norm() < 1e-14);
        }
    }
}
