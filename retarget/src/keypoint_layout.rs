//! Human hand keypoint layouts, with named indices.
//!
//! | layout | points | order |
//! |---|---|---|
//! | [`KeypointLayout::Lab22`] | 22 | 0 forearm (elbow), 1 wrist, then per digit (thumb, index, middle, ring, little) proximal, medial, distal, tip |
//! | [`KeypointLayout::Lab21`] | 21 | as `Lab22` without the forearm: 0 wrist, 1–4 thumb, … |
//! | [`KeypointLayout::MediaPipe21`] | 21 | 0 wrist; thumb CMC, MCP, IP, tip; then per finger MCP, PIP, DIP, tip |
//!
//! The lab layouts are what the ETH ingress publishes on `/ingress/mano` (despite the name,
//! not MANO/MediaPipe order). Points are metres, in whatever frame the glove reports.
//!
//! Each digit has a chain of four points, base first. The *base* of a digit is the first
//! point of its chain (lab: proximal; MediaPipe: thumb CMC, finger MCP); the palm frame is
//! built from the wrist and the five bases (see [`crate::PalmFrame`]).

use nalgebra::Point3;
use serde::{Deserialize, Serialize};

use crate::finger::Finger;
use crate::palm_frame::PalmLandmarks;

/// A human keypoint layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum KeypointLayout {
    /// The lab's 22-point layout (forearm, wrist, 4 per digit).
    #[serde(rename = "lab22")]
    Lab22,
    /// The lab's 21-point layout (wrist, 4 per digit).
    #[serde(rename = "lab21")]
    Lab21,
    /// MediaPipe / OpenPose 21-point hand.
    #[serde(rename = "mediapipe21")]
    MediaPipe21,
}

/// Named indices of the lab's 22-point layout.
pub mod lab22 {
    /// Forearm (elbow) point.
    pub const FOREARM: usize = 0;
    /// Wrist.
    pub const WRIST: usize = 1;
    /// Thumb proximal, medial, distal, tip.
    pub const THUMB: [usize; 4] = [2, 3, 4, 5];
    /// Index proximal, medial, distal, tip.
    pub const INDEX: [usize; 4] = [6, 7, 8, 9];
    /// Middle proximal, medial, distal, tip.
    pub const MIDDLE: [usize; 4] = [10, 11, 12, 13];
    /// Ring proximal, medial, distal, tip.
    pub const RING: [usize; 4] = [14, 15, 16, 17];
    /// Little proximal, medial, distal, tip.
    pub const LITTLE: [usize; 4] = [18, 19, 20, 21];
}

/// Named indices of the lab's 21-point layout.
pub mod lab21 {
    /// Wrist.
    pub const WRIST: usize = 0;
    /// Thumb proximal, medial, distal, tip.
    pub const THUMB: [usize; 4] = [1, 2, 3, 4];
    /// Index proximal, medial, distal, tip.
    pub const INDEX: [usize; 4] = [5, 6, 7, 8];
    /// Middle proximal, medial, distal, tip.
    pub const MIDDLE: [usize; 4] = [9, 10, 11, 12];
    /// Ring proximal, medial, distal, tip.
    pub const RING: [usize; 4] = [13, 14, 15, 16];
    /// Little proximal, medial, distal, tip.
    pub const LITTLE: [usize; 4] = [17, 18, 19, 20];
}

/// Named indices of MediaPipe's 21-point hand.
pub mod mediapipe21 {
    /// Wrist.
    pub const WRIST: usize = 0;
    /// Thumb CMC, MCP, IP, tip.
    pub const THUMB: [usize; 4] = [1, 2, 3, 4];
    /// Index MCP, PIP, DIP, tip.
    pub const INDEX: [usize; 4] = [5, 6, 7, 8];
    /// Middle MCP, PIP, DIP, tip.
    pub const MIDDLE: [usize; 4] = [9, 10, 11, 12];
    /// Ring MCP, PIP, DIP, tip.
    pub const RING: [usize; 4] = [13, 14, 15, 16];
    /// Pinky MCP, PIP, DIP, tip.
    pub const LITTLE: [usize; 4] = [17, 18, 19, 20];
}

const LAB_JOINTS: [&str; 4] = ["proximal", "medial", "distal", "tip"];
const MEDIAPIPE_THUMB: [&str; 4] = ["cmc", "mcp", "ip", "tip"];
const MEDIAPIPE_FINGER: [&str; 4] = ["mcp", "pip", "dip", "tip"];

impl KeypointLayout {
    /// All layouts.
    pub const ALL: [KeypointLayout; 3] = [
        KeypointLayout::Lab22,
        KeypointLayout::Lab21,
        KeypointLayout::MediaPipe21,
    ];

    /// Configuration name (`lab22`, `lab21`, `mediapipe21`).
    pub const fn name(self) -> &'static str {
        match self {
            KeypointLayout::Lab22 => "lab22",
            KeypointLayout::Lab21 => "lab21",
            KeypointLayout::MediaPipe21 => "mediapipe21",
        }
    }

    /// Number of points.
    pub const fn len(self) -> usize {
        match self {
            KeypointLayout::Lab22 => 22,
            KeypointLayout::Lab21 | KeypointLayout::MediaPipe21 => 21,
        }
    }

    /// Never true: every layout has points (for clippy's `len` convention).
    pub const fn is_empty(self) -> bool {
        false
    }

    /// Index of the wrist point.
    pub const fn wrist(self) -> usize {
        match self {
            KeypointLayout::Lab22 => lab22::WRIST,
            KeypointLayout::Lab21 => lab21::WRIST,
            KeypointLayout::MediaPipe21 => mediapipe21::WRIST,
        }
    }

    /// Index of the forearm point, where the layout has one.
    pub const fn forearm(self) -> Option<usize> {
        match self {
            KeypointLayout::Lab22 => Some(lab22::FOREARM),
            KeypointLayout::Lab21 | KeypointLayout::MediaPipe21 => None,
        }
    }

    /// The four points of a digit, base first, tip last.
    pub const fn chain(self, finger: Finger) -> [usize; 4] {
        let first = self.wrist() + 1 + 4 * finger.index();
        [first, first + 1, first + 2, first + 3]
    }

    /// The base point of a digit (first point of its chain).
    pub const fn base(self, finger: Finger) -> usize {
        self.chain(finger)[0]
    }

    /// The tip point of a digit.
    pub const fn tip(self, finger: Finger) -> usize {
        self.chain(finger)[3]
    }

    /// Name of point `index` (`index_tip`, `thumb_cmc`, `forearm`), or `None` past the end.
    pub fn point_name(self, index: usize) -> Option<String> {
        if index >= self.len() {
            return None;
        }
        if Some(index) == self.forearm() {
            return Some("forearm".into());
        }
        if index == self.wrist() {
            return Some("wrist".into());
        }
        let offset = index - self.wrist() - 1;
        let finger = Finger::ALL[offset / 4];
        let joint = match (self, finger) {
            (KeypointLayout::MediaPipe21, Finger::Thumb) => MEDIAPIPE_THUMB[offset % 4],
            (KeypointLayout::MediaPipe21, _) => MEDIAPIPE_FINGER[offset % 4],
            _ => LAB_JOINTS[offset % 4],
        };
        Some(format!("{finger}_{joint}"))
    }

    /// Index of the point called `name`.
    pub fn index_of(self, name: &str) -> Option<usize> {
        (0..self.len()).find(|&i| self.point_name(i).as_deref() == Some(name))
    }

    /// The palm landmarks (wrist and five bases) of a frame of points in this layout.
    /// `points` must have [`KeypointLayout::len`] entries (checked by the caller).
    pub fn palm_landmarks(self, points: &[Point3<f64>]) -> PalmLandmarks {
        PalmLandmarks {
            wrist: points[self.wrist()],
            bases: Finger::ALL.map(|f| points[self.base(f)]),
        }
    }
}

impl std::fmt::Display for KeypointLayout {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chains_match_the_named_constants() {
        let cases = [
            (
                KeypointLayout::Lab22,
                [
                    lab22::THUMB,
                    lab22::INDEX,
                    lab22::MIDDLE,
                    lab22::RING,
                    lab22::LITTLE,
                ],
            ),
            (
                KeypointLayout::Lab21,
                [
                    lab21::THUMB,
                    lab21::INDEX,
                    lab21::MIDDLE,
                    lab21::RING,
                    lab21::LITTLE,
                ],
            ),
            (
                KeypointLayout::MediaPipe21,
                [
                    mediapipe21::THUMB,
                    mediapipe21::INDEX,
                    mediapipe21::MIDDLE,
                    mediapipe21::RING,
                    mediapipe21::LITTLE,
                ],
            ),
        ];
        for (layout, chains) in cases {
            for finger in Finger::ALL {
                assert_eq!(
                    layout.chain(finger),
                    chains[finger.index()],
                    "{layout} {finger}"
                );
            }
            assert_eq!(layout.tip(Finger::Little), layout.len() - 1, "{layout}");
        }
        assert_eq!(KeypointLayout::Lab22.wrist(), lab22::WRIST);
        assert_eq!(KeypointLayout::Lab22.forearm(), Some(lab22::FOREARM));
    }

    #[test]
    fn every_point_has_a_unique_name_that_maps_back() {
        for layout in KeypointLayout::ALL {
            let names: Vec<String> = (0..layout.len())
                .filter_map(|i| layout.point_name(i))
                .collect();
            assert_eq!(names.len(), layout.len());
            for (i, name) in names.iter().enumerate() {
                assert_eq!(layout.index_of(name), Some(i), "{layout} {name}");
            }
            assert_eq!(layout.point_name(layout.len()), None);
        }
        assert_eq!(
            KeypointLayout::MediaPipe21.point_name(1).as_deref(),
            Some("thumb_cmc")
        );
        assert_eq!(
            KeypointLayout::MediaPipe21.point_name(6).as_deref(),
            Some("index_pip")
        );
        assert_eq!(
            KeypointLayout::Lab22.point_name(21).as_deref(),
            Some("little_tip")
        );
        assert_eq!(
            KeypointLayout::Lab21.point_name(1).as_deref(),
            Some("thumb_proximal")
        );
    }

    #[test]
    fn layouts_deserialize_from_their_names() {
        #[derive(Deserialize)]
        struct Wrapper {
            layout: KeypointLayout,
        }
        for layout in KeypointLayout::ALL {
            let w: Wrapper = toml::from_str(&format!("layout = \"{layout}\"")).unwrap();
            assert_eq!(w.layout, layout);
        }
    }
}
