//! [`HumanHandShape`]: the bone lengths and joint placements of a human hand.
//!
//! All geometry is given for a right hand of scale 1 in the *hand frame* (wrist joint centre
//! at the origin, `+y` from the wrist towards the middle finger, `+z` out of the palm, `+x`
//! towards the thumb side), then multiplied by [`HumanHandShape::scale`]. A left hand is the
//! mirror image `x ↦ −x` of the right hand ([`Handedness`]).
//!
//! Each digit `i` has a base joint centre `b_i` (thumb: CMC; fingers: MCP), three bones
//! `L_i = (L_i1, L_i2, L_i3)` (thumb: metacarpal, proximal phalanx, distal phalanx to the tip;
//! fingers: proximal, middle and distal phalanx to the tip) and a rest direction of its first
//! bone given by three angles (see [`DigitGeometry`]).
//!
//! ## The average hand ([`HumanHandShape::average`])
//!
//! The numbers are the project's own round figures for an average adult hand, chosen to agree
//! with the usual anthropometric ballpark: hand length (wrist crease to middle fingertip)
//! ≈ 18.5 cm (adult men ≈ 19 cm, women ≈ 17.5 cm), hand breadth at the knuckles ≈ 8.5 cm,
//! index and ring fingers about 1 cm shorter than the middle finger, the little fingertip
//! near the ring finger's DIP crease, and phalanx ratios close to 1 : 0.6 : 0.45 (proximal :
//! middle : distal). Lengths are joint centre to joint centre; the last bone ends at the
//! fingertip (the point a glove reports as `tip`).
//!
//! | digit | base `b` (x, y, z) mm | bones mm | rest splay, elevation, pronation |
//! |---|---|---|---|
//! | thumb  | (21, 28, 10) | 43, 31, 26 (metacarpal, proximal, distal) | 25°, 12°, 57° |
//! | index  | (23, 89, 0)  | 41, 24, 20 | 3°, 0, 0 |
//! | middle | (0, 92, 0)   | 45, 27, 21 | 0, 0, 0 |
//! | ring   | (−20, 86, 0) | 42, 26, 21 | −3°, 0, 0 |
//! | little | (−38, 76, 0) | 33, 19, 19 | −7°, 0, 0 |
//!
//! Middle fingertip at rest: `y = 92 + 45 + 27 + 21 = 185 mm`. The forearm point (the lab's
//! 22-point layout, "elbow") lies 250 mm behind the wrist on `−y`. The middle base sits on the
//! `y` axis and the finger bases share `z = 0`, so the palm frame ([`crate::PalmFrame`]) of
//! the generated keypoints has the hand frame's axes.

use serde::{Deserialize, Serialize};

use crate::error::Error;
use crate::finger::Finger;

/// Which hand: a left hand is the right hand mirrored through the `x = 0` plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Handedness {
    /// Right hand: thumb on `+x`, palm facing `+z`.
    #[default]
    Right,
    /// Left hand: thumb on `−x`, palm facing `+z`.
    Left,
}

impl Handedness {
    /// `+1` for a right hand, `−1` for a left hand: the factor applied to `x`.
    pub const fn x_sign(self) -> f64 {
        match self {
            Handedness::Right => 1.0,
            Handedness::Left => -1.0,
        }
    }
}

/// Geometry of one digit at scale 1, right hand, hand frame.
///
/// The first bone's direction at zero joint angles is `R_z(−splay) · R_x(elevation) · ŷ`:
/// `splay_rad` turns it in the palm plane towards the thumb side (`+x`), `elevation_rad`
/// lifts it out of the palm plane towards the palmar side (`+z`). `pronation_rad` turns the
/// digit about its own long axis so that its flexion moves it towards the little finger
/// (`−x`) as well as towards the palm; only the thumb has one.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DigitGeometry {
    /// Base joint centre (thumb CMC, finger MCP) relative to the wrist, metres.
    pub base_m: [f64; 3],
    /// Bone lengths, base to tip, metres.
    pub bones_m: [f64; 3],
    /// Rest direction in the palm plane towards the thumb side, radians.
    pub splay_rad: f64,
    /// Rest direction out of the palm plane towards the palm side, radians.
    pub elevation_rad: f64,
    /// Rest rotation about the digit's long axis, radians.
    pub pronation_rad: f64,
}

/// The proportions and size of a human hand.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HumanHandShape {
    /// Uniform size factor applied to every length (1 = the average hand; 0.8–1.25 covers
    /// most adults).
    pub scale: f64,
    /// Right or left hand.
    pub handedness: Handedness,
    /// Per digit, indexed by [`Finger::index`], at scale 1.
    pub digits: [DigitGeometry; 5],
    /// Distance of the forearm (elbow) point behind the wrist at scale 1, metres.
    pub forearm_m: f64,
    /// Thumb pronation added per radian of CMC abduction (opposition turns the thumb pad
    /// towards the fingers), dimensionless.
    pub thumb_pronation_per_abduction: f64,
    /// Where the glove reports each fingertip, relative to the anatomical tip, in the digit's
    /// last-bone frame (`x` across, `y` along, `z` out of the pad), metres, not scaled; indexed
    /// by [`Finger::index`]. Zero for the average hand ([`super::HandVariation`]).
    #[serde(default)]
    pub tip_markers_m: [[f64; 3]; 5],
}

const fn digit(base_mm: [f64; 3], bones_mm: [f64; 3], splay_deg: f64) -> DigitGeometry {
    DigitGeometry {
        base_m: [base_mm[0] * 1e-3, base_mm[1] * 1e-3, base_mm[2] * 1e-3],
        bones_m: [bones_mm[0] * 1e-3, bones_mm[1] * 1e-3, bones_mm[2] * 1e-3],
        splay_rad: splay_deg.to_radians(),
        elevation_rad: 0.0,
        pronation_rad: 0.0,
    }
}

/// Largest tip marker offset per axis, metres.
pub const MAX_TIP_MARKER_M: f64 = 0.02;

/// Realistic adult hand sizes relative to the average hand (checked by
/// [`HumanHandShape::validate`] with some margin).
pub const REALISTIC_SCALE: (f64, f64) = (0.8, 1.25);

impl HumanHandShape {
    /// The average adult right hand (see the module documentation for the numbers).
    pub const fn average() -> HumanHandShape {
        let thumb = DigitGeometry {
            elevation_rad: 12.0f64.to_radians(),
            pronation_rad: 57.0f64.to_radians(),
            ..digit([21.0, 28.0, 10.0], [43.0, 31.0, 26.0], 25.0)
        };
        HumanHandShape {
            scale: 1.0,
            handedness: Handedness::Right,
            digits: [
                thumb,
                digit([23.0, 89.0, 0.0], [41.0, 24.0, 20.0], 3.0),
                digit([0.0, 92.0, 0.0], [45.0, 27.0, 21.0], 0.0),
                digit([-20.0, 86.0, 0.0], [42.0, 26.0, 21.0], -3.0),
                digit([-38.0, 76.0, 0.0], [33.0, 19.0, 19.0], -7.0),
            ],
            forearm_m: 0.25,
            thumb_pronation_per_abduction: 0.5,
            tip_markers_m: [[0.0; 3]; 5],
        }
    }

    /// The same proportions at `scale` times the average size.
    pub const fn scaled(self, scale: f64) -> HumanHandShape {
        HumanHandShape { scale, ..self }
    }

    /// The same hand, mirrored if needed to be `handedness`.
    pub const fn with_handedness(self, handedness: Handedness) -> HumanHandShape {
        HumanHandShape { handedness, ..self }
    }

    /// Geometry of one digit, at scale 1.
    pub const fn digit(&self, finger: Finger) -> &DigitGeometry {
        &self.digits[finger.index()]
    }

    /// Scaled bone lengths of a digit, base to tip, metres.
    pub fn bone_lengths_m(&self, finger: Finger) -> [f64; 3] {
        self.digit(finger).bones_m.map(|l| l * self.scale)
    }

    /// Check that the shape can be posed: scale in [0.5, 2] and finite, positive lengths,
    /// finite angles. Errors name the field.
    pub fn validate(&self) -> Result<(), Error> {
        let bad = |key: String, value: f64, allowed: &str| Error::ConfigRange {
            key,
            value: value.to_string(),
            allowed: allowed.into(),
        };
        if !(self.scale.is_finite() && (0.5..=2.0).contains(&self.scale)) {
            return Err(bad(
                "human_hand.scale".into(),
                self.scale,
                "must be in [0.5, 2] (realistic adults: 0.8–1.25)",
            ));
        }
        if !(self.forearm_m.is_finite() && self.forearm_m > 0.0) {
            return Err(bad(
                "human_hand.forearm_m".into(),
                self.forearm_m,
                "must be positive",
            ));
        }
        if !self.thumb_pronation_per_abduction.is_finite() {
            return Err(bad(
                "human_hand.thumb_pronation_per_abduction".into(),
                self.thumb_pronation_per_abduction,
                "must be finite",
            ));
        }
        for finger in Finger::ALL {
            let d = self.digit(finger);
            for (k, &l) in d.bones_m.iter().enumerate() {
                if !(l.is_finite() && l > 0.0 && l < 0.2) {
                    return Err(bad(
                        format!("human_hand.{finger}.bones_m[{k}]"),
                        l,
                        "must be in (0, 0.2) m",
                    ));
                }
            }
            let marker = self.tip_markers_m[finger.index()];
            if !marker
                .iter()
                .all(|m| m.is_finite() && m.abs() <= MAX_TIP_MARKER_M)
            {
                let worst = marker.iter().fold(0.0f64, |a, m| a.max(m.abs()));
                return Err(bad(
                    format!("human_hand.{finger}.tip_markers_m"),
                    worst,
                    "must be finite and within ±0.02 m per axis",
                ));
            }
            let angles = [d.splay_rad, d.elevation_rad, d.pronation_rad];
            for (&v, name) in d.base_m.iter().chain(&angles).zip([
                "base_m[0]",
                "base_m[1]",
                "base_m[2]",
                "splay_rad",
                "elevation_rad",
                "pronation_rad",
            ]) {
                if !v.is_finite() {
                    return Err(bad(
                        format!("human_hand.{finger}.{name}"),
                        v,
                        "must be finite",
                    ));
                }
            }
        }
        Ok(())
    }
}

impl Default for HumanHandShape {
    fn default() -> Self {
        HumanHandShape::average()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn average_hand_has_adult_proportions() {
        let hand = HumanHandShape::average();
        hand.validate().unwrap();
        let length =
            |f: Finger| hand.digit(f).base_m[1] + hand.bone_lengths_m(f).iter().sum::<f64>();
        let middle = length(Finger::Middle);
        assert!((0.175..0.195).contains(&middle), "hand length {middle}");
        for f in [Finger::Index, Finger::Ring] {
            let shorter = middle - length(f);
            assert!(
                (0.005..0.015).contains(&shorter),
                "{f} shorter by {shorter}"
            );
        }
        let breadth = hand.digit(Finger::Index).base_m[0] - hand.digit(Finger::Little).base_m[0];
        assert!((0.05..0.07).contains(&breadth), "MCP span {breadth}");
    }

    #[test]
    fn scaling_scales_bones_and_validation_names_the_field() {
        let hand = HumanHandShape::average().scaled(1.2);
        let a = HumanHandShape::average().bone_lengths_m(Finger::Ring);
        let b = hand.bone_lengths_m(Finger::Ring);
        for k in 0..3 {
            assert!((b[k] - 1.2 * a[k]).abs() < 1e-15);
        }
        let err = HumanHandShape::average()
            .scaled(0.1)
            .validate()
            .unwrap_err();
        assert!(err.to_string().contains("human_hand.scale"), "{err}");
        let mut bad = HumanHandShape::average();
        bad.digits[3].bones_m[1] = -0.01;
        let err = bad.validate().unwrap_err().to_string();
        assert!(err.contains("human_hand.ring.bones_m[1]"), "{err}");
        let mut bad = HumanHandShape::average();
        bad.digits[0].pronation_rad = f64::NAN;
        assert!(
            bad.validate()
                .unwrap_err()
                .to_string()
                .contains("thumb.pronation_rad")
        );
    }
}
