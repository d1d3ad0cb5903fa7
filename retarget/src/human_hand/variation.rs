//! Hands that differ from the average in proportion, not only in size.
//!
//! A uniformly scaled copy of one hand is the case a single global scale fits exactly, so it
//! tests neither a retargeter nor a calibration on what real users bring: thumbs and fingers
//! differ in proportion from person to person, the thumb's base sits differently on each palm,
//! and each glove's tip markers sit a few millimetres off the fingertip. A [`HandVariation`]
//! describes one such hand relative to [`HumanHandShape::average`]; [`HandVariation::draw`]
//! draws each factor independently and uniformly within [`VariationRanges`]:
//!
//! | factor | range (the defaults) | acts on |
//! |---|---|---|
//! | thumb length | ±15 % | the thumb's three bones |
//! | index length, middle length | ±10 % each | that finger's three bones |
//! | palm breadth | ±10 % | the `x` of every digit's base (thumb CMC and finger MCPs) |
//! | thumb base | ±5 mm per axis, ±5° of rest splay | the thumb's CMC position and rest direction |
//! | tip markers | ±5 mm per axis, each digit | where the glove reports each fingertip |
//!
//! The tip marker offsets are given in each digit's last-bone frame (`x` across the digit,
//! `y` along it, `z` out of its pad), so a marker moves with its fingertip; they shift only the
//! reported tip keypoint, not the anatomy: a pinch pose still brings the two *fingertips*
//! together, and the glove reports their markers a few millimetres apart, as a real glove does.
//! Every length still scales with [`HumanHandShape::scale`]; the marker offsets do not (they
//! are where a glove's sensor sits, in metres).

use super::noise::SplitMix64;
use super::shape::HumanHandShape;
use crate::finger::Finger;

/// Half-widths of the uniform ranges each factor is drawn from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VariationRanges {
    /// Thumb length, relative (0.15 = ±15 %).
    pub thumb_length: f64,
    /// Index and middle finger lengths, relative, each drawn on its own.
    pub finger_length: f64,
    /// Palm breadth, relative.
    pub palm_breadth: f64,
    /// Thumb base position, metres per axis.
    pub thumb_base_m: f64,
    /// Thumb rest splay, radians.
    pub thumb_splay_rad: f64,
    /// Tip marker offset, metres per axis.
    pub tip_marker_m: f64,
}

impl VariationRanges {
    /// The ranges of the module documentation.
    pub const DEFAULT: VariationRanges = VariationRanges {
        thumb_length: 0.15,
        finger_length: 0.10,
        palm_breadth: 0.10,
        thumb_base_m: 0.005,
        thumb_splay_rad: 5.0 * std::f64::consts::PI / 180.0,
        tip_marker_m: 0.005,
    };
}

impl Default for VariationRanges {
    fn default() -> Self {
        VariationRanges::DEFAULT
    }
}

/// One hand's proportions relative to the average hand (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HandVariation {
    /// Factor on the thumb's bones.
    pub thumb_length: f64,
    /// Factor on the index finger's bones.
    pub index_length: f64,
    /// Factor on the middle finger's bones.
    pub middle_length: f64,
    /// Factor on every digit base's `x` (across the palm).
    pub palm_breadth: f64,
    /// Added to the thumb base's position, metres (at scale 1).
    pub thumb_base_shift_m: [f64; 3],
    /// Added to the thumb's rest splay, radians.
    pub thumb_splay_rad: f64,
    /// Tip marker offsets per digit (indexed by [`Finger::index`]), metres, last-bone frame.
    pub tip_markers_m: [[f64; 3]; 5],
}

impl HandVariation {
    /// No variation: the average hand's proportions, markers on the tips.
    pub const NONE: HandVariation = HandVariation {
        thumb_length: 1.0,
        index_length: 1.0,
        middle_length: 1.0,
        palm_breadth: 1.0,
        thumb_base_shift_m: [0.0; 3],
        thumb_splay_rad: 0.0,
        tip_markers_m: [[0.0; 3]; 5],
    };

    /// A hand drawn from `rng`, each factor independently and uniformly within `ranges`.
    pub fn draw(rng: &mut SplitMix64, ranges: &VariationRanges) -> HandVariation {
        let mut within = |half_width: f64| half_width * (2.0 * rng.next_f64() - 1.0);
        HandVariation {
            thumb_length: 1.0 + within(ranges.thumb_length),
            index_length: 1.0 + within(ranges.finger_length),
            middle_length: 1.0 + within(ranges.finger_length),
            palm_breadth: 1.0 + within(ranges.palm_breadth),
            thumb_base_shift_m: std::array::from_fn(|_| within(ranges.thumb_base_m)),
            thumb_splay_rad: within(ranges.thumb_splay_rad),
            tip_markers_m: std::array::from_fn(|_| {
                std::array::from_fn(|_| within(ranges.tip_marker_m))
            }),
        }
    }

    /// `shape` with these proportions (its scale and handedness kept).
    pub fn apply(&self, shape: HumanHandShape) -> HumanHandShape {
        let mut varied = shape;
        for finger in Finger::ALL {
            let digit = &mut varied.digits[finger.index()];
            let length = match finger {
                Finger::Thumb => self.thumb_length,
                Finger::Index => self.index_length,
                Finger::Middle => self.middle_length,
                Finger::Ring | Finger::Little => 1.0,
            };
            digit.bones_m = digit.bones_m.map(|l| l * length);
            digit.base_m[0] *= self.palm_breadth;
            if finger == Finger::Thumb {
                for (base, shift) in digit.base_m.iter_mut().zip(self.thumb_base_shift_m) {
                    *base += shift;
                }
                digit.splay_rad += self.thumb_splay_rad;
            }
        }
        varied.tip_markers_m = self.tip_markers_m;
        varied
    }

    /// A short description for file names and tables: the digit factors in percent.
    pub fn label(&self) -> String {
        let percent = |f: f64| ((f - 1.0) * 100.0).round() as i64;
        format!(
            "thumb{:+}-index{:+}-middle{:+}-palm{:+}",
            percent(self.thumb_length),
            percent(self.index_length),
            percent(self.middle_length),
            percent(self.palm_breadth)
        )
    }
}

impl Default for HandVariation {
    fn default() -> Self {
        HandVariation::NONE
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::KeypointLayout;
    use crate::human_hand::{HumanHandPose, pinch_pose};

    #[test]
    fn draws_stay_within_their_ranges_and_reach_their_ends() {
        let ranges = VariationRanges::DEFAULT;
        let mut rng = SplitMix64::new(3);
        let hands: Vec<_> = (0..400)
            .map(|_| HandVariation::draw(&mut rng, &ranges))
            .collect();
        let thumbs: Vec<f64> = hands.iter().map(|h| h.thumb_length).collect();
        assert!(thumbs.iter().all(|t| (0.85..=1.15).contains(t)));
        assert!(thumbs.iter().any(|&t| t < 0.87) && thumbs.iter().any(|&t| t > 1.13));
        let markers = hands.iter().flat_map(|h| h.tip_markers_m.iter().flatten());
        assert!(markers.clone().all(|m| m.abs() <= 0.005));
        assert!(markers.clone().any(|&m| m > 0.0045) && markers.clone().any(|&m| m < -0.0045));
        for h in &hands {
            assert!((0.9..=1.1).contains(&h.index_length));
            assert!((0.9..=1.1).contains(&h.palm_breadth));
            h.apply(HumanHandShape::average()).validate().unwrap();
        }
    }

    #[test]
    fn a_varied_hand_has_its_factors_and_reports_its_markers_off_the_tips() {
        let variation = HandVariation {
            thumb_length: 1.15,
            index_length: 0.9,
            palm_breadth: 1.1,
            tip_markers_m: [
                [0.0, 0.0, -0.004],
                [0.003, 0.0, 0.0],
                [0.0; 3],
                [0.0; 3],
                [0.0; 3],
            ],
            ..HandVariation::NONE
        };
        let average = HumanHandShape::average().scaled(1.1);
        let varied = variation.apply(average);
        let thumb = |s: &HumanHandShape| s.bone_lengths_m(Finger::Thumb)[1];
        assert!((thumb(&varied) - 1.15 * thumb(&average)).abs() < 1e-15);
        let index = |s: &HumanHandShape| s.bone_lengths_m(Finger::Index)[2];
        assert!((index(&varied) - 0.9 * index(&average)).abs() < 1e-15);
        assert!(
            (varied.digit(Finger::Little).base_m[0]
                - 1.1 * average.digit(Finger::Little).base_m[0])
                .abs()
                < 1e-15
        );
        // The marker moves the reported tip by its offset's length; the anatomy is unchanged.
        let pose = HumanHandPose::open();
        let layout = KeypointLayout::Lab21;
        let tip = layout.chain(Finger::Thumb)[3];
        let with_markers = varied.keypoints(&pose, layout);
        let mut bare = varied;
        bare.tip_markers_m = [[0.0; 3]; 5];
        let without = bare.keypoints(&pose, layout);
        assert!(((with_markers[tip] - without[tip]).norm() - 0.004).abs() < 1e-12);
        assert_eq!(varied.digit_chains(&pose), bare.digit_chains(&pose));
        // A pinch still closes the fingertips of the varied hand.
        let pinch = pinch_pose(&varied, Finger::Index, 0.0).unwrap();
        assert!(varied.thumb_gap_m(&pinch.pose, Finger::Index) < 1e-4);
    }
}
