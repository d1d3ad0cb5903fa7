//! [`SimGlove`]: a simulated motion-capture glove, as a pure function of time.
//!
//! At time `t` (seconds) the glove reports, in its own (tracker) frame `G`:
//!
//! ```text
//! T_GH(t) = Trans(w(t)) · T_GH0 · S(t)                wrist pose: the hand frame H in G
//! p_k(t)  = T_GH(t) · x_k(θ(t)) + σ · n_k(seed, t)     keypoints, k = 0 … layout.len() − 1
//! ```
//!
//! - `x_k(θ)`: the hand model's keypoints for the pose `θ(t)`, in the hand frame
//!   ([`HumanHandShape::keypoints`]); `θ(t)` is the periodic motion's pose, or a task
//!   script's ([`SimGlove::with_script`]);
//! - `w(t)`: a task script's wrist offset, glove frame (zero without a script);
//! - `T_GH0`: where the hand sits in the glove frame (`hand_in_glove`; identity by default;
//!   calibration's synthetic users rotate it by up to ±20° per axis);
//! - `S(t)`: an optional slow sway of the wrist about that placement ([`WristSway`]);
//! - `n_k`: independent standard normal 3-vectors from [`SplitMix64::keyed`]`(seed, t bits)`,
//!   so the jitter of a frame depends on the seed and the time only (asking for the same time
//!   twice gives the same frame, as a republished glove frame would), and `σ` the per-axis
//!   standard deviation `jitter_sd_m` (the 3-D displacement has RMS `√3 σ`).
//!
//! The wrist pose is returned without jitter. No I/O, no timing: the station's ROS layer
//! decides when to call [`SimGlove::frame`] and publishes the result.

use std::f64::consts::TAU;

use nalgebra::{Isometry3, Point3, Rotation3, Translation3, UnitQuaternion, Vector3};

use super::glove_script::{GloveScript, ResolvedScript};
use super::hand_kinematics::place_points;
use super::motion::Motion;
use super::noise::SplitMix64;
use super::pose::HumanHandPose;
use super::shape::HumanHandShape;
use crate::error::Error;
use crate::finger::Finger;
use crate::keypoint_layout::KeypointLayout;
use crate::palm_frame::PalmFrame;

/// Largest jitter accepted, metres (per-axis standard deviation).
pub const MAX_JITTER_SD_M: f64 = 0.05;

/// A slow periodic sway of the wrist: translation `aᵢ sin(2π t / T + φᵢ)` along the hand
/// frame's axes and the rotation `R_z(c_z sin(ω t + φ₂)) R_y(c_y sin(ω t + φ₁)) R_x(c_x sin(ω t))`
/// (fixed-axis roll, pitch, yaw), with phases `φᵢ = i · 2π/3` so the axes do not move in step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WristSway {
    /// Translation amplitude along x, y, z of the hand frame, metres.
    pub amplitude_m: [f64; 3],
    /// Rotation amplitude about x, y, z (roll, pitch, yaw), radians.
    pub amplitude_rad: [f64; 3],
    /// Period, seconds.
    pub period_s: f64,
}

impl WristSway {
    /// A gentle sway: ±2 cm, ±1 cm, ±1 cm and ±0.15, ±0.1, ±0.15 rad over 8 s.
    pub const GENTLE: WristSway = WristSway {
        amplitude_m: [0.02, 0.01, 0.01],
        amplitude_rad: [0.15, 0.1, 0.15],
        period_s: 8.0,
    };

    /// The sway's displacement `S(t)` of the hand frame.
    pub fn offset(&self, t_s: f64) -> Isometry3<f64> {
        let w = TAU * t_s / self.period_s;
        let wave = |i: usize| (w + i as f64 * TAU / 3.0).sin();
        let [ax, ay, az] = self.amplitude_m;
        let [rx, ry, rz] = self.amplitude_rad;
        Isometry3::from_parts(
            Translation3::new(ax * wave(0), ay * wave(1), az * wave(2)),
            UnitQuaternion::from_euler_angles(rx * wave(0), ry * wave(1), rz * wave(2)),
        )
    }

    fn validate(&self) -> Result<(), Error> {
        let finite = self
            .amplitude_m
            .iter()
            .chain(&self.amplitude_rad)
            .all(|v| v.is_finite());
        if !(finite && self.period_s.is_finite() && self.period_s > 0.0) {
            return Err(Error::ConfigRange {
                key: "sim_glove.wrist_sway".into(),
                value: format!("{self:?}"),
                allowed: "amplitudes must be finite and the period positive".into(),
            });
        }
        Ok(())
    }
}

/// A simulated glove: a hand shape performing a periodic motion or a task script, seen in the
/// glove frame.
#[derive(Debug, Clone, PartialEq)]
pub struct SimGlove {
    shape: HumanHandShape,
    motion: Motion,
    script: Option<ResolvedScript>,
    layout: KeypointLayout,
    hand_in_glove: Isometry3<f64>,
    wrist_sway: Option<WristSway>,
    misalignment: Rotation3<f64>,
    jitter_sd_m: f64,
    seed: u64,
}

impl SimGlove {
    /// A glove with the hand at the glove frame's origin, no sway and no jitter. `Err` for an
    /// invalid shape.
    pub fn new(
        shape: HumanHandShape,
        motion: Motion,
        layout: KeypointLayout,
    ) -> Result<SimGlove, Error> {
        shape.validate()?;
        Ok(SimGlove {
            shape,
            motion,
            script: None,
            layout,
            hand_in_glove: Isometry3::identity(),
            wrist_sway: None,
            misalignment: Rotation3::identity(),
            jitter_sd_m: 0.0,
            seed: 0,
        })
    }

    /// Place the hand frame at `hand_in_glove` in the glove frame.
    pub fn with_hand_in_glove(self, hand_in_glove: Isometry3<f64>) -> SimGlove {
        SimGlove {
            hand_in_glove,
            ..self
        }
    }

    /// Misalign the glove's finger sensors with its palm: every keypoint that is not a palm
    /// landmark (wrist, forearm, digit bases) is reported rotated by `rotation` about the palm
    /// frame's origin, in palm-frame axes. The palm frame the station builds is unchanged and
    /// every fingertip and mid-point vector it reads in that frame is `rotation · v`: the
    /// rotation a user's calibration must undo.
    pub fn with_misalignment(self, rotation: Rotation3<f64>) -> SimGlove {
        SimGlove {
            misalignment: rotation,
            ..self
        }
    }

    /// The glove's finger-to-palm misalignment.
    pub fn misalignment(&self) -> &Rotation3<f64> {
        &self.misalignment
    }

    /// Let the wrist sway about its placement. `Err` for a non-finite amplitude or a period
    /// that is not positive.
    pub fn with_wrist_sway(self, sway: WristSway) -> Result<SimGlove, Error> {
        sway.validate()?;
        Ok(SimGlove {
            wrist_sway: Some(sway),
            ..self
        })
    }

    /// Perform `script` instead of the periodic motion: its hand poses (pinches solved for
    /// this glove's shape) and its wrist path, added in the glove frame to the hand's
    /// placement (and sway). `Err` for an invalid script.
    pub fn with_script(self, script: &GloveScript) -> Result<SimGlove, Error> {
        let resolved = script.resolve(&self.shape)?;
        Ok(SimGlove {
            script: Some(resolved),
            ..self
        })
    }

    /// Add Gaussian jitter of `sd_m` metres per axis to every keypoint, from `seed`. `Err`
    /// unless `0 ≤ sd_m ≤ MAX_JITTER_SD_M`.
    pub fn with_jitter(self, sd_m: f64, seed: u64) -> Result<SimGlove, Error> {
        if !(sd_m.is_finite() && (0.0..=MAX_JITTER_SD_M).contains(&sd_m)) {
            return Err(Error::ConfigRange {
                key: "sim_glove.jitter_sd_m".into(),
                value: sd_m.to_string(),
                allowed: format!("must be in [0, {MAX_JITTER_SD_M}] m"),
            });
        }
        Ok(SimGlove {
            jitter_sd_m: sd_m,
            seed,
            ..self
        })
    }

    /// The hand's shape.
    pub fn shape(&self) -> &HumanHandShape {
        &self.shape
    }

    /// The periodic motion (played unless a task script replaces it).
    pub fn motion(&self) -> &Motion {
        &self.motion
    }

    /// The task script it performs, if any ([`SimGlove::with_script`]).
    pub fn script(&self) -> Option<&ResolvedScript> {
        self.script.as_ref()
    }

    /// Whether the glove sends a frame at `t_s`: always, unless its script has a dropout
    /// there.
    pub fn sends_at(&self, t_s: f64) -> bool {
        self.script.as_ref().is_none_or(|s| s.sends_at(t_s))
    }

    /// The keypoint layout of the frames.
    pub fn layout(&self) -> KeypointLayout {
        self.layout
    }

    /// The hand's placement in the glove frame (without sway or a script's wrist path).
    pub fn hand_in_glove(&self) -> &Isometry3<f64> {
        &self.hand_in_glove
    }

    /// Per-axis jitter standard deviation, metres.
    pub fn jitter_sd_m(&self) -> f64 {
        self.jitter_sd_m
    }

    /// The hand pose (joint angles) at `t_s`.
    pub fn pose_at(&self, t_s: f64) -> HumanHandPose {
        match &self.script {
            Some(script) => script.pose(t_s),
            None => self.motion.sample(t_s),
        }
    }

    /// The pose of the hand frame (the wrist) in the glove frame at `t_s`.
    pub fn wrist_pose(&self, t_s: f64) -> Isometry3<f64> {
        let placed = match &self.wrist_sway {
            Some(sway) => self.hand_in_glove * sway.offset(t_s),
            None => self.hand_in_glove,
        };
        match &self.script {
            Some(script) => Isometry3::from_parts(
                Translation3::from(placed.translation.vector + script.wrist_offset(t_s)),
                script.wrist_turn(t_s) * placed.rotation,
            ),
            None => placed,
        }
    }

    /// The glove's frame at `t_s`: the keypoints in the glove frame (layout order, metres,
    /// jittered) and the wrist pose (not jittered).
    pub fn frame(&self, t_s: f64) -> (Vec<Point3<f64>>, Isometry3<f64>) {
        let wrist = self.wrist_pose(t_s);
        let pose = self.pose_at(t_s);
        let mut hand = self.shape.keypoints(&pose, self.layout);
        if self.misalignment != Rotation3::identity() {
            misalign(&mut hand, self.layout, &self.misalignment);
        }
        let mut points = place_points(&hand, &wrist);
        if self.jitter_sd_m > 0.0 {
            let mut noise = SplitMix64::keyed(self.seed, t_s.to_bits());
            for p in &mut points {
                let n = Vector3::new(
                    noise.next_gaussian(),
                    noise.next_gaussian(),
                    noise.next_gaussian(),
                );
                *p += n * self.jitter_sd_m;
            }
        }
        (points, wrist)
    }
}

/// Rotate the non-landmark keypoints about the palm origin by `rotation` in palm axes (see
/// [`SimGlove::with_misalignment`]). A frame whose palm cannot be built is left as it is.
pub fn misalign(points: &mut [Point3<f64>], layout: KeypointLayout, rotation: &Rotation3<f64>) {
    let Ok(palm) = PalmFrame::from_landmarks(&layout.palm_landmarks(points)) else {
        return;
    };
    let about_origin = palm.rotation * rotation * palm.rotation.inverse();
    let landmark = |i: usize| {
        i == layout.wrist()
            || Some(i) == layout.forearm()
            || Finger::ALL.iter().any(|&f| layout.chain(f)[0] == i)
    };
    for (i, p) in points.iter_mut().enumerate() {
        if !landmark(i) {
            *p = palm.origin + about_origin * (*p - palm.origin);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::human_hand::glove_script::{GloveScript, ScriptKeyframe, ScriptPose};
    use crate::human_hand::motion::MotionKind;

    fn glove() -> SimGlove {
        let shape = HumanHandShape::average();
        let motion = Motion::new(MotionKind::OpenClose, 4.0, &shape).unwrap();
        SimGlove::new(shape, motion, KeypointLayout::Lab22).unwrap()
    }

    #[test]
    fn without_jitter_the_frame_is_the_placed_model() {
        let iso = Isometry3::new(Vector3::new(0.3, 0.1, -0.2), Vector3::new(0.0, 0.3, 0.2));
        let g = glove().with_hand_in_glove(iso);
        let (points, wrist) = g.frame(1.3);
        assert_eq!(wrist, iso);
        let expected = g.shape().keypoints_in(&g.pose_at(1.3), g.layout(), &iso);
        assert_eq!(points, expected);
    }

    #[test]
    fn sway_moves_the_wrist_smoothly_and_periodically() {
        let g = glove().with_wrist_sway(WristSway::GENTLE).unwrap();
        let a = g.wrist_pose(1.0);
        let b = g.wrist_pose(1.0 + WristSway::GENTLE.period_s);
        assert!((a.translation.vector - b.translation.vector).norm() < 1e-12);
        assert!(a.rotation.angle_to(&b.rotation) < 1e-9);
        let c = g.wrist_pose(1.01);
        assert!((a.translation.vector - c.translation.vector).norm() < 1e-3);
        assert!(a.translation.vector.norm() > 1e-3, "it moves");
        let (points, wrist) = g.frame(1.0);
        assert!(
            (points[KeypointLayout::Lab22.wrist()] - Point3::from(wrist.translation.vector)).norm()
                < 1e-15
        );
    }

    #[test]
    fn misalignment_rotates_every_key_vector_in_the_palm_frame() {
        let rotation = Rotation3::from_euler_angles(0.2, -0.3, 0.25);
        let plain = glove();
        let turned = glove().with_misalignment(rotation);
        let layout = plain.layout();
        let (a, _) = plain.frame(0.7);
        let (b, _) = turned.frame(0.7);
        let palm_a = PalmFrame::from_landmarks(&layout.palm_landmarks(&a)).unwrap();
        let palm_b = PalmFrame::from_landmarks(&layout.palm_landmarks(&b)).unwrap();
        assert_eq!(palm_a, palm_b, "the palm frame is unchanged");
        for finger in Finger::ALL {
            for &i in &layout.chain(finger)[1..] {
                let expected = rotation * palm_a.point_to_palm(&a[i]);
                assert!((palm_b.point_to_palm(&b[i]) - expected).norm() < 1e-12);
            }
        }
    }

    /// The test glove placed off the origin and turned, playing a script of `keyframes`.
    fn placed_with_script(keyframes: Vec<ScriptKeyframe>) -> (SimGlove, Isometry3<f64>) {
        let script = GloveScript {
            keyframes,
            dropouts: Vec::new(),
        };
        let placement = Isometry3::new(Vector3::new(0.1, 0.2, 0.3), Vector3::new(0.0, 0.0, 0.4));
        let g = glove()
            .with_hand_in_glove(placement)
            .with_script(&script)
            .unwrap();
        (g, placement)
    }

    #[test]
    fn a_script_moves_the_wrist_and_the_hand_along_its_keyframes() {
        let (g, placement) = placed_with_script(vec![
            ScriptKeyframe::new(0.0, [0.0; 3], ScriptPose::Open),
            ScriptKeyframe::new(2.0, [0.0, 0.0, -0.25], ScriptPose::Open),
            ScriptKeyframe::new(3.0, [0.0, 0.18, -0.25], ScriptPose::CylinderGrasp),
        ]);
        let offset = |t: f64| g.wrist_pose(t).translation.vector - placement.translation.vector;
        assert_eq!(offset(0.0), Vector3::zeros());
        assert!((offset(2.0) - Vector3::new(0.0, 0.0, -0.25)).norm() < 1e-15);
        assert!((offset(1.0) - Vector3::new(0.0, 0.0, -0.125)).norm() < 1e-12);
        assert!(
            (offset(9.0) - Vector3::new(0.0, 0.18, -0.25)).norm() < 1e-15,
            "holds"
        );
        assert_eq!(
            g.wrist_pose(2.5).rotation,
            placement.rotation,
            "translation only"
        );
        assert_eq!(g.pose_at(9.0), HumanHandPose::cylinder_grasp());
        let (points, wrist) = g.frame(2.5);
        let expected = g.shape().keypoints_in(&g.pose_at(2.5), g.layout(), &wrist);
        assert_eq!(points, expected);
        assert!(g.script().is_some() && glove().script().is_none());
        let bad = GloveScript {
            keyframes: vec![],
            dropouts: Vec::new(),
        };
        assert!(glove().with_script(&bad).is_err());
    }

    #[test]
    fn a_scripted_wrist_turn_turns_the_hand_about_the_wrist_in_place() {
        let mut turned = ScriptKeyframe::new(1.0, [0.0; 3], ScriptPose::Open);
        turned.wrist_turn_deg = [0.0, 0.0, 30.0];
        let (g, placement) = placed_with_script(vec![
            ScriptKeyframe::new(0.0, [0.0; 3], ScriptPose::Open),
            turned,
        ]);
        let wrist = g.wrist_pose(5.0);
        assert!((wrist.translation.vector - placement.translation.vector).norm() < 1e-15);
        let turn = wrist.rotation * placement.rotation.inverse();
        assert!((turn.angle() - 30f64.to_radians()).abs() < 1e-12);
        assert!((turn.axis().unwrap().z - 1.0).abs() < 1e-12, "about +z");
        let (points, at) = g.frame(5.0);
        let expected = g.shape().keypoints_in(&g.pose_at(5.0), g.layout(), &at);
        assert_eq!(points, expected, "the keypoints turn with the wrist");
    }

    #[test]
    fn bad_settings_are_errors() {
        assert!(glove().with_jitter(-1.0, 0).is_err());
        assert!(glove().with_jitter(f64::INFINITY, 0).is_err());
        let sway = WristSway {
            period_s: 0.0,
            ..WristSway::GENTLE
        };
        assert!(glove().with_wrist_sway(sway).is_err());
    }
}
