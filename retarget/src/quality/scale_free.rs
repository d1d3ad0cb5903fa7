//! Tip error after each digit's own least-squares scale (see [`super`]): a digit the robot
//! cannot reach where the glove puts it shrinks only its own scale, not the targets of the
//! others.

use super::FrameSample;
use crate::finger::Finger;

/// One digit's own scale and the errors left after it.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct OwnScale {
    /// `s_i = Σ_t r·h / Σ_t h·h` over the frames with a finite command; `None` without any
    /// (or when every human tip sits on the palm origin).
    pub scale: Option<f64>,
    /// `‖r − s_i·h‖` per such frame, millimetres; empty when `scale` is `None`.
    pub errors_mm: Vec<f64>,
}

/// The own scale of `digit` and its errors.
pub(super) fn own_scale(samples: &[FrameSample], digit: Finger) -> OwnScale {
    let i = digit.index();
    let pairs: Vec<_> = samples
        .iter()
        .filter_map(|s| s.robot_tips.map(|r| (r[i], s.human_tips[i])))
        .collect();
    let (rh, hh) = pairs.iter().fold((0.0, 0.0), |(rh, hh), (r, h)| {
        (rh + r.dot(h), hh + h.dot(h))
    });
    if hh <= 0.0 || !rh.is_finite() {
        return OwnScale {
            scale: None,
            errors_mm: Vec::new(),
        };
    }
    let scale = rh / hh;
    OwnScale {
        scale: Some(scale),
        errors_mm: pairs
            .iter()
            .map(|(r, h)| (r - h * scale).norm() * 1e3)
            .collect(),
    }
}
