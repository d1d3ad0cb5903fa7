//! [`GloveScript`]: a scripted glove task, the wrist's path and the hand's poses as keyframes.
//!
//! A periodic [`Motion`](super::Motion) plays hand poses with the wrist in place; a script
//! performs a task once: the wrist moves down to an object, the hand closes, the wrist lifts,
//! carries and lowers it, the hand opens. Keyframe `i` gives a time `tᵢ`, a wrist offset `wᵢ`
//! (metres, glove frame, from the wrist's placement at `t = 0`) and a key pose
//! `Pᵢ = lerp(open, named poseᵢ, closureᵢ)`, and optionally a wrist turn `rᵢ` (a rotation
//! vector, axis × angle, degrees, glove frame, about the wrist itself). Between two keyframes
//! (`tᵢ ≤ t < tᵢ₊₁`):
//!
//! ```text
//! v = (t − tᵢ) / (tᵢ₊₁ − tᵢ),    s = 10v³ − 15v⁴ + 6v⁵          (minimum jerk)
//! wrist(t) = wᵢ + s · (wᵢ₊₁ − wᵢ),    pose(t) = lerp(Pᵢ, Pᵢ₊₁, s)
//! turn(t) = exp(rᵢ + s · (rᵢ₊₁ − rᵢ))
//! ```
//!
//! The turn is applied to the hand's placement at the start, about the wrist: a turn about +z
//! is a twist of the wrist about the vertical, which the station passes to the arm where the
//! task's constraint and the orientation policy allow it (`twist_about_axis` on an axis
//! task). Between two turns about one axis the interpolation is exact.
//!
//! The minimum-jerk profile has zero velocity and acceleration at both ends, so the path
//! passes every keyframe exactly and at rest and is twice continuously differentiable (C²)
//! everywhere; a keyframe equal to the previous one is a hold. Before `t = 0` the first
//! keyframe is held, after the last one the last.
//!
//! ## File format (TOML)
//!
//! ```toml
//! [[keyframes]]
//! t_s = 0.0                   # seconds; the first at 0, then strictly increasing
//! wrist_m = [0.0, 0.0, 0.0]   # offset from the start, glove frame, each within ±1 m
//! pose = "open"               # see ScriptPose
//!
//! [[keyframes]]
//! t_s = 1.5
//! wrist_m = [0.0, 0.0, -0.2]
//! pose = "cylinder_grasp"
//! closure = 0.8               # optional, default 1: 0 open … 1 the named pose
//! wrist_turn_deg = [0.0, 0.0, 30.0]   # optional, default none: 30° about +z (vertical)
//! ```
//!
//! A script may also name dropouts, windows of script time in which the simulated glove
//! sends nothing (a tracker that lost the hand, a cable pulled), to rehearse and test what the
//! station and the operator see then:
//!
//! ```toml
//! [[dropouts]]
//! from_s = 3.0                # seconds of script time, 0 ≤ from_s < to_s
//! to_s = 3.4                  # windows in time order, not overlapping
//! ```
//!
//! Pinch poses depend on the hand's proportions: [`GloveScript::resolve`] solves them for a
//! shape (as [`Motion::new`](super::Motion::new) does, with the same [`PINCH_GAP_M`] gap)
//! and gives the [`ResolvedScript`] that samples the script.

use nalgebra::{UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};

use super::motion::PINCH_GAP_M;
use super::pinch::pinch_pose;
use super::pose::HumanHandPose;
use super::shape::HumanHandShape;
use crate::error::Error;
use crate::finger::Finger;

/// Largest wrist offset per axis accepted, metres.
pub const MAX_WRIST_OFFSET_M: f64 = 1.0;

/// Largest wrist turn per rotation-vector component accepted, degrees.
pub const MAX_WRIST_TURN_DEG: f64 = 180.0;

/// The named hand poses a keyframe can ask for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ScriptPose {
    /// [`HumanHandPose::open`].
    Open,
    /// [`HumanHandPose::open_spread`].
    OpenSpread,
    /// [`HumanHandPose::relaxed`].
    Relaxed,
    /// [`HumanHandPose::fist`].
    Fist,
    /// [`HumanHandPose::cylinder_grasp`].
    CylinderGrasp,
    /// The thumb pinching the index finger.
    PinchIndex,
    /// The thumb pinching the middle finger.
    PinchMiddle,
    /// The thumb pinching the ring finger.
    PinchRing,
    /// The thumb pinching the little finger.
    PinchLittle,
}

impl ScriptPose {
    /// All named poses.
    pub const ALL: [ScriptPose; 9] = [
        ScriptPose::Open,
        ScriptPose::OpenSpread,
        ScriptPose::Relaxed,
        ScriptPose::Fist,
        ScriptPose::CylinderGrasp,
        ScriptPose::PinchIndex,
        ScriptPose::PinchMiddle,
        ScriptPose::PinchRing,
        ScriptPose::PinchLittle,
    ];

    /// The finger the thumb pinches, for the pinch poses.
    pub const fn pinched_finger(self) -> Option<Finger> {
        match self {
            ScriptPose::PinchIndex => Some(Finger::Index),
            ScriptPose::PinchMiddle => Some(Finger::Middle),
            ScriptPose::PinchRing => Some(Finger::Ring),
            ScriptPose::PinchLittle => Some(Finger::Little),
            _ => None,
        }
    }

    /// The pose's joint angles for `shape` (pinches solved with a [`PINCH_GAP_M`] gap).
    /// `Err` for an invalid shape.
    pub fn angles(self, shape: &HumanHandShape) -> Result<HumanHandPose, Error> {
        if let Some(finger) = self.pinched_finger() {
            return Ok(pinch_pose(shape, finger, PINCH_GAP_M)?.pose);
        }
        Ok(match self {
            ScriptPose::OpenSpread => HumanHandPose::open_spread(),
            ScriptPose::Relaxed => HumanHandPose::relaxed(),
            ScriptPose::Fist => HumanHandPose::fist(),
            ScriptPose::CylinderGrasp => HumanHandPose::cylinder_grasp(),
            _ => HumanHandPose::open(),
        })
    }
}

/// One keyframe of a [`GloveScript`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScriptKeyframe {
    /// When the keyframe is reached, seconds from the script's start.
    pub t_s: f64,
    /// The wrist's offset from its placement at the start, glove frame, metres.
    pub wrist_m: [f64; 3],
    /// The named hand pose.
    pub pose: ScriptPose,
    /// How far from open towards `pose` the hand is: 0 open, 1 (the default) the named pose.
    #[serde(default = "full_closure")]
    pub closure: f64,
    /// The wrist's turn from its placement at the start: a rotation vector (axis × angle),
    /// degrees, glove frame, about the wrist. Default none.
    #[serde(default, skip_serializing_if = "is_no_turn")]
    pub wrist_turn_deg: [f64; 3],
}

/// Whether a turn is none (so that a script without turns writes no turn).
fn is_no_turn(turn: &[f64; 3]) -> bool {
    *turn == [0.0; 3]
}

/// The default closure: the named pose itself.
const fn full_closure() -> f64 {
    1.0
}

impl ScriptKeyframe {
    /// A keyframe at `t_s` with the wrist offset `wrist_m` and the full `pose`.
    pub const fn new(t_s: f64, wrist_m: [f64; 3], pose: ScriptPose) -> ScriptKeyframe {
        ScriptKeyframe {
            t_s,
            wrist_m,
            pose,
            closure: 1.0,
            wrist_turn_deg: [0.0; 3],
        }
    }
}

/// A scripted glove task: keyframes of the wrist's offset and the hand's pose, played once.
/// See the module documentation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GloveScript {
    /// The keyframes, in time order, the first at `t_s = 0`.
    pub keyframes: Vec<ScriptKeyframe>,
    /// Windows of script time in which the glove sends nothing, in time order.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub dropouts: Vec<ScriptDropout>,
}

/// A window of script time in which the simulated glove sends nothing.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScriptDropout {
    /// Its start, seconds of script time.
    pub from_s: f64,
    /// Its end, seconds (the glove sends again from here).
    pub to_s: f64,
}

/// `Err` unless every dropout is a finite window `0 ≤ from_s < to_s`, after the one before.
fn check_dropouts(dropouts: &[ScriptDropout]) -> Result<(), Error> {
    let mut previous_end = 0.0;
    for (index, d) in dropouts.iter().enumerate() {
        let ok = d.from_s.is_finite()
            && d.to_s.is_finite()
            && d.from_s >= previous_end
            && d.to_s > d.from_s;
        if !ok {
            return Err(Error::ConfigRange {
                key: format!("dropouts[{index}]"),
                value: format!("from_s = {}, to_s = {}", d.from_s, d.to_s),
                allowed: format!(
                    "finite, from_s < to_s, from_s at least {previous_end} s (0, or the end of the dropout before)"
                ),
            });
        }
        previous_end = d.to_s;
    }
    Ok(())
}

/// A [`ConfigRange`](Error::ConfigRange) error for field `field` of keyframe `index`.
fn keyframe_error(index: usize, field: &str, value: String, allowed: String) -> Error {
    Error::ConfigRange {
        key: format!("keyframes[{index}].{field}"),
        value,
        allowed,
    }
}

/// `Err` unless keyframe `index`'s time is 0 (the first) or after `previous_t_s`.
fn check_time(index: usize, t_s: f64, previous_t_s: Option<f64>) -> Result<(), Error> {
    let (ok, allowed) = match previous_t_s {
        None => (
            t_s == 0.0,
            "must be 0 (the script starts at t = 0 s)".to_string(),
        ),
        Some(previous) => (
            t_s.is_finite() && t_s > previous,
            format!(
                "must be finite and greater than keyframes[{}].t_s = {previous} s (times strictly increasing)",
                index - 1
            ),
        ),
    };
    if ok {
        Ok(())
    } else {
        Err(keyframe_error(index, "t_s", t_s.to_string(), allowed))
    }
}

/// `Err` unless keyframe `index`'s wrist offset, turn and closure are within their ranges.
fn check_values(index: usize, keyframe: &ScriptKeyframe) -> Result<(), Error> {
    check_components(
        index,
        "wrist_m",
        &keyframe.wrist_m,
        MAX_WRIST_OFFSET_M,
        " m",
    )?;
    check_components(
        index,
        "wrist_turn_deg",
        &keyframe.wrist_turn_deg,
        MAX_WRIST_TURN_DEG,
        "°",
    )?;
    if !(0.0..=1.0).contains(&keyframe.closure) {
        return Err(keyframe_error(
            index,
            "closure",
            keyframe.closure.to_string(),
            "must be in [0, 1] (0 open, 1 the named pose)".into(),
        ));
    }
    Ok(())
}

/// `Err` naming keyframe `index`'s `field` unless every component is finite and within
/// ±`max` (`unit` in the message).
fn check_components(
    index: usize,
    field: &str,
    values: &[f64; 3],
    max: f64,
    unit: &str,
) -> Result<(), Error> {
    if values.iter().all(|v| v.is_finite() && v.abs() <= max) {
        return Ok(());
    }
    Err(keyframe_error(
        index,
        field,
        format!("{values:?}"),
        format!("every component must be finite and within ±{max}{unit}"),
    ))
}

impl GloveScript {
    /// Parse and validate a script written in TOML (see the module documentation).
    pub fn from_toml_str(text: &str) -> Result<GloveScript, Error> {
        let script: GloveScript = toml::from_str(text).map_err(|e| Error::Syntax {
            reason: e.to_string().trim_end().to_string(),
        })?;
        script.validate()?;
        Ok(script)
    }

    /// Check the keyframes: at least one, the first at `t_s = 0`, times finite and strictly
    /// increasing, wrist offsets finite and within ±[`MAX_WRIST_OFFSET_M`], closures in
    /// `[0, 1]`. The error names the keyframe's field (`keyframes[2].t_s`).
    pub fn validate(&self) -> Result<(), Error> {
        if self.keyframes.is_empty() {
            return Err(Error::ConfigRange {
                key: "keyframes".into(),
                value: "[]".into(),
                allowed: "at least one keyframe, the first at t_s = 0".into(),
            });
        }
        let mut previous_t_s = None;
        for (index, keyframe) in self.keyframes.iter().enumerate() {
            check_time(index, keyframe.t_s, previous_t_s)?;
            check_values(index, keyframe)?;
            previous_t_s = Some(keyframe.t_s);
        }
        check_dropouts(&self.dropouts)
    }

    /// The time of the last keyframe, seconds: when the script ends (and holds).
    pub fn duration_s(&self) -> f64 {
        self.keyframes.last().map_or(0.0, |k| k.t_s)
    }

    /// The script ready to sample for a hand of `shape`: validated, and every key pose turned
    /// into joint angles (pinches solved for the shape). `Err` for an invalid script or shape.
    pub fn resolve(&self, shape: &HumanHandShape) -> Result<ResolvedScript, Error> {
        self.validate()?;
        let open = HumanHandPose::open();
        let mut poses = Vec::with_capacity(self.keyframes.len());
        for keyframe in &self.keyframes {
            let named = keyframe.pose.angles(shape)?;
            poses.push(HumanHandPose::lerp(&open, &named, keyframe.closure));
        }
        Ok(ResolvedScript {
            times_s: self.keyframes.iter().map(|k| k.t_s).collect(),
            wrists_m: self
                .keyframes
                .iter()
                .map(|k| Vector3::from(k.wrist_m))
                .collect(),
            turns_rad: self
                .keyframes
                .iter()
                .map(|k| Vector3::from(k.wrist_turn_deg.map(f64::to_radians)))
                .collect(),
            poses,
            dropouts: self.dropouts.clone(),
        })
    }
}

/// The script's state at one time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScriptSample {
    /// The wrist's offset from its placement at the start, glove frame, metres.
    pub wrist_m: Vector3<f64>,
    /// The wrist's turn from its placement at the start, glove frame, about the wrist.
    pub wrist_turn: UnitQuaternion<f64>,
    /// The hand's joint angles.
    pub pose: HumanHandPose,
}

/// A validated [`GloveScript`] with its key poses as joint angles for one hand shape; samples
/// the script at any time (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct ResolvedScript {
    times_s: Vec<f64>,
    wrists_m: Vec<Vector3<f64>>,
    turns_rad: Vec<Vector3<f64>>,
    poses: Vec<HumanHandPose>,
    dropouts: Vec<ScriptDropout>,
}

/// The minimum-jerk profile `10v³ − 15v⁴ + 6v⁵`: 0 → 1 with zero velocity and acceleration at
/// both ends.
fn minimum_jerk(v: f64) -> f64 {
    v * v * v * (10.0 + v * (-15.0 + 6.0 * v))
}

impl ResolvedScript {
    /// The time of the last keyframe, seconds.
    pub fn duration_s(&self) -> f64 {
        self.times_s.last().copied().unwrap_or(0.0)
    }

    /// The keyframes around `t_s` and the profile's progress between them: `(i, j, s)` with
    /// the state `lerp(keyframe i, keyframe j, s)`; `i == j` outside the script's span.
    fn segment(&self, t_s: f64) -> (usize, usize, f64) {
        let next = self.times_s.partition_point(|&t| t <= t_s);
        let last = self.times_s.len().saturating_sub(1);
        match next {
            0 => (0, 0, 0.0),
            n if n > last => (last, last, 0.0),
            n => {
                let (t0, t1) = (self.times_s[n - 1], self.times_s[n]);
                (n - 1, n, minimum_jerk((t_s - t0) / (t1 - t0)))
            }
        }
    }

    /// The wrist's offset from its start at `t_s`, glove frame, metres.
    pub fn wrist_offset(&self, t_s: f64) -> Vector3<f64> {
        let (i, j, s) = self.segment(t_s);
        self.wrists_m[i] + (self.wrists_m[j] - self.wrists_m[i]) * s
    }

    /// The wrist's turn from its start at `t_s`, glove frame, about the wrist.
    pub fn wrist_turn(&self, t_s: f64) -> UnitQuaternion<f64> {
        let (i, j, s) = self.segment(t_s);
        UnitQuaternion::from_scaled_axis(
            self.turns_rad[i] + (self.turns_rad[j] - self.turns_rad[i]) * s,
        )
    }

    /// The hand's joint angles at `t_s`.
    pub fn pose(&self, t_s: f64) -> HumanHandPose {
        let (i, j, s) = self.segment(t_s);
        HumanHandPose::lerp(&self.poses[i], &self.poses[j], s)
    }

    /// Whether the glove sends at `t_s` (outside every dropout).
    pub fn sends_at(&self, t_s: f64) -> bool {
        !self
            .dropouts
            .iter()
            .any(|d| (d.from_s..d.to_s).contains(&t_s))
    }

    /// The wrist offset and the hand pose at `t_s`.
    pub fn sample(&self, t_s: f64) -> ScriptSample {
        ScriptSample {
            wrist_m: self.wrist_offset(t_s),
            wrist_turn: self.wrist_turn(t_s),
            pose: self.pose(t_s),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const EXAMPLE: &str = r#"
[[keyframes]]
t_s = 0.0
wrist_m = [0.0, 0.0, 0.0]
pose = "open"

[[keyframes]]
t_s = 2.0
wrist_m = [0.0, 0.0, -0.25]
pose = "open"

[[keyframes]]
t_s = 3.5
wrist_m = [0.0, 0.0, -0.25]
pose = "cylinder_grasp"

[[keyframes]]
t_s = 5.0
wrist_m = [0.0, 0.18, -0.15]
pose = "pinch_index"
closure = 0.5
"#;

    fn example() -> ResolvedScript {
        GloveScript::from_toml_str(EXAMPLE)
            .unwrap()
            .resolve(&HumanHandShape::average())
            .unwrap()
    }

    /// The key of a `ConfigRange` error (panics for another error).
    fn error_key(result: Result<GloveScript, Error>) -> String {
        match result {
            Err(Error::ConfigRange { key, allowed, .. }) => {
                assert!(!allowed.is_empty());
                key
            }
            other => panic!("expected a ConfigRange error, got {other:?}"),
        }
    }

    #[test]
    fn keyframes_are_hit_exactly() {
        let script = GloveScript::from_toml_str(EXAMPLE).unwrap();
        let resolved = example();
        let shape = HumanHandShape::average();
        for keyframe in &script.keyframes {
            let sample = resolved.sample(keyframe.t_s);
            assert_eq!(sample.wrist_m, Vector3::from(keyframe.wrist_m));
            let named = keyframe.pose.angles(&shape).unwrap();
            let expected = HumanHandPose::lerp(&HumanHandPose::open(), &named, keyframe.closure);
            assert!(sample.pose.max_difference_rad(&expected) < 1e-15);
        }
        assert_eq!(resolved.duration_s(), 5.0);
        assert_eq!(script.duration_s(), 5.0);
    }

    #[test]
    fn between_keyframes_the_path_is_smooth_and_starts_and_stops_at_rest() {
        let resolved = example();
        // Halfway through the approach: the minimum-jerk profile is at one half.
        assert!((resolved.wrist_offset(1.0).z + 0.125).abs() < 1e-12);
        // Monotonic on the way down, at rest at both ends (speed ~ v² near them).
        let z = |t: f64| resolved.wrist_offset(t).z;
        let steps: Vec<f64> = (0..=200).map(|k| z(k as f64 * 0.01)).collect();
        assert!(steps.windows(2).all(|w| w[1] <= w[0]));
        let h = 1e-4;
        assert!((z(h) - z(0.0)).abs() / h < 1e-5, "starts at rest");
        assert!((z(2.0) - z(2.0 - h)).abs() / h < 1e-5, "arrives at rest");
        // Largest speed, at the middle: 15/8 · 0.25 m / 2 s.
        let peak = (z(1.0 + h) - z(1.0 - h)).abs() / (2.0 * h);
        assert!((peak - 15.0 / 8.0 * 0.125).abs() < 1e-6, "{peak}");
        // The pose moves continuously into the grasp.
        let a = resolved.pose(2.75);
        let b = resolved.pose(2.75 + 1e-3);
        assert!(a.max_difference_rad(&b) < 1e-2);
        assert!(a.max_difference_rad(&HumanHandPose::open()) > 0.1);
    }

    #[test]
    fn dropouts_silence_the_glove_in_their_windows_and_bad_ones_name_their_index() {
        let text = format!(
            "{EXAMPLE}\n[[dropouts]]\nfrom_s = 1.0\nto_s = 1.4\n\n[[dropouts]]\nfrom_s = 3.0\nto_s = 3.2\n"
        );
        let script = GloveScript::from_toml_str(&text).unwrap();
        let resolved = script.resolve(&HumanHandShape::average()).unwrap();
        let sends: Vec<bool> = [0.99, 1.0, 1.39, 1.4, 3.1, 3.2]
            .map(|t| resolved.sends_at(t))
            .to_vec();
        assert_eq!(sends, [true, false, false, true, false, true]);
        assert!(example().sends_at(1.2), "no dropouts: always sends");
        for (from, to, index) in [(1.0, 1.0, 0), (-1.0, 0.5, 0), (1.0, 2.0, 1)] {
            let mut bad = script.clone();
            bad.dropouts[0] = ScriptDropout {
                from_s: from,
                to_s: to,
            };
            if index == 1 {
                bad.dropouts[1] = ScriptDropout {
                    from_s: 1.5,
                    to_s: 1.8,
                };
            }
            let error = bad.validate().unwrap_err().to_string();
            assert!(error.contains(&format!("dropouts[{index}]")), "{error}");
        }
    }

    #[test]
    fn a_wrist_turn_about_one_axis_is_hit_at_its_keyframes_and_smooth_between() {
        let text = concat!(
            "[[keyframes]]\nt_s = 0.0\nwrist_m = [0.0, 0.0, 0.0]\npose = \"open\"\n",
            "[[keyframes]]\nt_s = 1.0\nwrist_m = [0.0, 0.0, 0.0]\npose = \"open\"\n",
            "wrist_turn_deg = [0.0, 0.0, 40.0]\n",
            "[[keyframes]]\nt_s = 2.0\nwrist_m = [0.0, 0.0, 0.0]\npose = \"open\"\n",
            "wrist_turn_deg = [0.0, 0.0, -20.0]\n",
        );
        let script = GloveScript::from_toml_str(text).unwrap();
        assert_eq!(
            script.keyframes[0].wrist_turn_deg, [0.0; 3],
            "default: none"
        );
        let resolved = script.resolve(&HumanHandShape::average()).unwrap();
        let yaw_deg = |t: f64| {
            let q = resolved.wrist_turn(t);
            q.scaled_axis().z.to_degrees()
        };
        assert!(yaw_deg(0.0).abs() < 1e-12);
        assert!((yaw_deg(1.0) - 40.0).abs() < 1e-9);
        assert!(
            (yaw_deg(1.5) - 10.0).abs() < 1e-9,
            "half way by minimum jerk"
        );
        assert!((yaw_deg(2.0) + 20.0).abs() < 1e-9);
        assert!((yaw_deg(9.0) + 20.0).abs() < 1e-9, "held after the end");
        let axis = resolved.wrist_turn(1.3).axis().unwrap();
        assert!((axis.z.abs() - 1.0).abs() < 1e-12, "about +z only");
        let monotone = (0..=100).map(|k| yaw_deg(1.0 + f64::from(k) / 100.0));
        let values: Vec<f64> = monotone.collect();
        assert!(values.windows(2).all(|w| w[1] <= w[0] + 1e-12));
    }

    #[test]
    fn after_the_last_keyframe_it_holds_and_before_the_first_too() {
        let resolved = example();
        let end = resolved.sample(5.0);
        for t in [5.0 + 1e-9, 6.0, 1e6, f64::INFINITY] {
            assert_eq!(resolved.sample(t), end, "t = {t}");
        }
        assert_eq!(resolved.sample(-3.0), resolved.sample(0.0));
        assert_eq!(resolved.wrist_offset(-3.0), Vector3::zeros());
    }

    #[test]
    fn a_single_keyframe_is_a_still_hand() {
        let script = GloveScript {
            keyframes: vec![ScriptKeyframe::new(0.0, [0.0, 0.1, 0.0], ScriptPose::Fist)],
            dropouts: Vec::new(),
        };
        let resolved = script.resolve(&HumanHandShape::average()).unwrap();
        assert_eq!(resolved.duration_s(), 0.0);
        assert_eq!(resolved.wrist_offset(4.0), Vector3::new(0.0, 0.1, 0.0));
        assert_eq!(resolved.pose(4.0), HumanHandPose::fist());
    }

    #[test]
    fn pinches_are_solved_for_the_shape_and_closure_blends_from_open() {
        let shape = HumanHandShape::average().scaled(1.1);
        let expected = pinch_pose(&shape, Finger::Middle, PINCH_GAP_M)
            .unwrap()
            .pose;
        assert_eq!(ScriptPose::PinchMiddle.angles(&shape).unwrap(), expected);
        let resolved = example();
        let half = HumanHandPose::lerp(
            &HumanHandPose::open(),
            &ScriptPose::PinchIndex
                .angles(&HumanHandShape::average())
                .unwrap(),
            0.5,
        );
        assert!(resolved.pose(5.0).max_difference_rad(&half) < 1e-15);
        for pose in ScriptPose::ALL {
            assert!(pose.angles(&shape).unwrap().within_ranges(), "{pose:?}");
        }
    }

    #[test]
    fn validation_errors_name_the_keyframe_field() {
        let script = |keyframes: Vec<ScriptKeyframe>| GloveScript {
            keyframes,
            dropouts: Vec::new(),
        };
        let check = |s: GloveScript| s.validate().map(|()| s);
        let open = |t: f64| ScriptKeyframe::new(t, [0.0; 3], ScriptPose::Open);
        assert_eq!(error_key(check(script(vec![]))), "keyframes");
        assert_eq!(
            error_key(check(script(vec![open(0.5)]))),
            "keyframes[0].t_s"
        );
        assert_eq!(
            error_key(check(script(vec![open(0.0), open(1.0), open(1.0)]))),
            "keyframes[2].t_s"
        );
        assert_eq!(
            error_key(check(script(vec![open(0.0), open(f64::NAN)]))),
            "keyframes[1].t_s"
        );
        let mut far = open(1.0);
        far.wrist_m = [0.0, -1.2, 0.0];
        assert_eq!(
            error_key(check(script(vec![open(0.0), far]))),
            "keyframes[1].wrist_m"
        );
        far.wrist_m = [f64::INFINITY, 0.0, 0.0];
        assert_eq!(
            error_key(check(script(vec![open(0.0), far]))),
            "keyframes[1].wrist_m"
        );
        let mut turned = open(1.0);
        turned.wrist_turn_deg = [0.0, 0.0, 200.0];
        assert_eq!(
            error_key(check(script(vec![open(0.0), turned]))),
            "keyframes[1].wrist_turn_deg"
        );
        let mut over = open(1.0);
        over.closure = 1.5;
        assert_eq!(
            error_key(check(script(vec![open(0.0), over]))),
            "keyframes[1].closure"
        );
        let message = check(script(vec![open(0.0), open(2.0), open(1.0)]))
            .unwrap_err()
            .to_string();
        assert!(
            message.contains("keyframes[2].t_s") && message.contains("keyframes[1].t_s = 2"),
            "{message}"
        );
    }

    #[test]
    fn the_toml_format_is_strict_and_closure_defaults_to_one() {
        let script = GloveScript::from_toml_str(EXAMPLE).unwrap();
        assert_eq!(script.keyframes[1].closure, 1.0);
        assert_eq!(script.keyframes[3].pose, ScriptPose::PinchIndex);
        let round_trip = toml::to_string(&script).unwrap();
        assert_eq!(GloveScript::from_toml_str(&round_trip).unwrap(), script);
        for bad in [
            "[[keyframes]]\nt_s = 0.0\nwrist_m = [0.0, 0.0, 0.0]\npose = \"open\"\nspeed = 1.0\n",
            "[[keyframes]]\nt_s = 0.0\nwrist_m = [0.0, 0.0, 0.0]\npose = \"wave\"\n",
            "[[keyframes]]\nt_s = 0.0\npose = \"open\"\n",
            "name = \"x\"\n[[keyframes]]\nt_s = 0.0\nwrist_m = [0.0, 0.0, 0.0]\npose = \"open\"\n",
        ] {
            let err = GloveScript::from_toml_str(bad).unwrap_err();
            assert!(matches!(err, Error::Syntax { .. }), "{bad}: {err:?}");
        }
        assert!(
            GloveScript::from_toml_str("").is_err(),
            "keyframes is required"
        );
    }
}
