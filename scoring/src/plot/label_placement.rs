//! Point labels that avoid each other: try positions around the point in a fixed order and
//! take the first whose box stays inside the plot and clear of everything already placed.

use super::primitives::{Anchor, Point, Text};
use super::stroke_font::{FONT_SLACK, cap_height, text_width};

/// An axis-aligned box in pixels (y down).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rect {
    /// Left edge.
    pub left: f64,
    /// Right edge.
    pub right: f64,
    /// Top edge.
    pub top: f64,
    /// Bottom edge.
    pub bottom: f64,
}

impl Rect {
    /// The box `half_w` by `half_h` either side of `center`.
    pub fn around(center: Point, half_w: f64, half_h: f64) -> Self {
        Self {
            left: center.x - half_w,
            right: center.x + half_w,
            top: center.y - half_h,
            bottom: center.y + half_h,
        }
    }

    /// Width in pixels.
    pub fn width(&self) -> f64 {
        self.right - self.left
    }

    /// Height in pixels.
    pub fn height(&self) -> f64 {
        self.bottom - self.top
    }

    /// Area shared with `other`, in square pixels.
    pub fn overlap_area(&self, other: &Rect) -> f64 {
        let w = self.right.min(other.right) - self.left.max(other.left);
        let h = self.bottom.min(other.bottom) - self.top.max(other.top);
        w.max(0.0) * h.max(0.0)
    }
}

/// Distance from the point to the label's near edge.
const GAP_PX: f64 = 11.0;

/// The box text of `width` covers when anchored at `at` (baseline) with `anchor`.
fn text_box(at: Point, anchor: Anchor, width: f64, size_px: f64) -> Rect {
    let left = match anchor {
        Anchor::Start => at.x,
        Anchor::Middle => at.x - width / 2.0,
        Anchor::End => at.x - width,
    };
    Rect {
        left,
        right: left + width,
        top: at.y - cap_height(size_px) - 2.0,
        bottom: at.y + 0.25 * size_px,
    }
}

/// A label for the point at `point`, placed right, left, above or below it (in that order
/// of preference, above before below) so that it stays inside `area` and clear of
/// `obstacles`; when no spot is free, the one covering the least. Returns the text and its
/// box.
pub fn place_label(
    content: String,
    point: Point,
    size_px: f64,
    area: Rect,
    obstacles: &[Rect],
) -> (Text, Rect) {
    let cap = cap_height(size_px);
    let width = FONT_SLACK * text_width(&content, size_px);
    let candidates = [
        (GAP_PX, -GAP_PX / 2.0, Anchor::Start),
        (GAP_PX, GAP_PX / 2.0 + cap, Anchor::Start),
        (-GAP_PX, -GAP_PX / 2.0, Anchor::End),
        (-GAP_PX, GAP_PX / 2.0 + cap, Anchor::End),
        (0.0, -GAP_PX - 2.0, Anchor::Middle),
        (0.0, GAP_PX + 2.0 + cap, Anchor::Middle),
    ];
    let placed = candidates.map(|(dx, dy, anchor)| {
        let at = Point::new(point.x + dx, point.y + dy);
        (at, anchor, text_box(at, anchor, width, size_px))
    });
    // Cost of a spot: area covering obstacles, plus area outside the plot counted ten times.
    let cost = |rect: &Rect| -> f64 {
        let covered: f64 = obstacles.iter().map(|o| rect.overlap_area(o)).sum();
        covered + 10.0 * (rect.width() * rect.height() - rect.overlap_area(&area))
    };
    let mut best = (placed[0], cost(&placed[0].2));
    for candidate in &placed[1..] {
        if best.1 <= 0.0 {
            break;
        }
        let c = cost(&candidate.2);
        if c < best.1 {
            best = (*candidate, c);
        }
    }
    let (at, anchor, rect) = best.0;
    (Text::new(content, at, anchor, size_px), rect)
}

#[cfg(test)]
mod tests {
    use super::*;

    const AREA: Rect = Rect {
        left: 0.0,
        right: 400.0,
        top: 0.0,
        bottom: 300.0,
    };

    #[test]
    fn a_lone_label_goes_right_of_its_point() {
        let (text, rect) = place_label("Orca_5".into(), Point::new(100.0, 100.0), 14.0, AREA, &[]);
        assert_eq!(text.anchor, Anchor::Start);
        assert!(rect.left > 100.0 && rect.bottom < 100.0 + 14.0);
    }

    #[test]
    fn labels_move_left_at_the_right_edge_and_around_others() {
        let (text, _) = place_label(
            "Orca_full".into(),
            Point::new(390.0, 100.0),
            14.0,
            AREA,
            &[],
        );
        assert_eq!(text.anchor, Anchor::End);
        let (_, first) = place_label("Orca_3".into(), Point::new(100.0, 100.0), 14.0, AREA, &[]);
        let (_, second) = place_label(
            "Orca_5".into(),
            Point::new(110.0, 102.0),
            14.0,
            AREA,
            &[first],
        );
        assert_eq!(first.overlap_area(&second), 0.0, "{first:?} {second:?}");
    }

    #[test]
    fn without_a_free_spot_the_least_covered_one_wins() {
        let point = Point::new(200.0, 150.0);
        // Everything but a strip below the point is blocked.
        let blocks = [
            Rect {
                left: 0.0,
                right: 400.0,
                top: 0.0,
                bottom: 150.0,
            },
            Rect {
                left: 0.0,
                right: 190.0,
                top: 150.0,
                bottom: 300.0,
            },
            Rect {
                left: 210.0,
                right: 400.0,
                top: 150.0,
                bottom: 300.0,
            },
        ];
        let (text, rect) = place_label("G".into(), point, 14.0, AREA, &blocks);
        assert_eq!(text.anchor, Anchor::Middle);
        assert!(rect.top > point.y, "{rect:?}");
    }
}
