//! The stroke font: text metrics for layout, and glyph polylines in pixels for the PNG
//! backend (tiny-skia draws no text).
//!
//! The metrics also stand in for the SVG viewer's sans-serif face when the charts lay out
//! labels: capitals are 0.72 em tall and letters advance about 0.6 em, close to common
//! sans-serif faces, and the charts leave slack for the difference.

use super::glyphs::{Glyph, MISSING, glyph};
use super::primitives::{Anchor, Point, Text};

/// Cap height as a fraction of the font size.
pub const CAP_HEIGHT_EM: f64 = 0.72;
/// Grid units from the baseline to the top of a capital.
const CAP_UNITS: f64 = 12.0;
/// How much wider than the stroke font's metrics a viewer's sans-serif face may set text:
/// layouts multiply measured widths by this so SVG text does not collide or clip.
pub const FONT_SLACK: f64 = 1.15;
/// Gap between letters in grid units.
const LETTER_GAP_UNITS: f64 = 3.0;

fn glyph_or_missing(c: char) -> Glyph {
    glyph(c).unwrap_or(MISSING)
}

/// Pixels per grid unit at font size `size_px`.
fn unit_px(size_px: f64) -> f64 {
    size_px * CAP_HEIGHT_EM / CAP_UNITS
}

/// Height of a capital letter above the baseline, in pixels.
pub fn cap_height(size_px: f64) -> f64 {
    size_px * CAP_HEIGHT_EM
}

/// Width of `text` set at `size_px`, in pixels.
pub fn text_width(text: &str, size_px: f64) -> f64 {
    let units: f64 = text
        .chars()
        .map(|c| f64::from(glyph_or_missing(c).width) + LETTER_GAP_UNITS)
        .sum();
    (units - LETTER_GAP_UNITS).max(0.0) * unit_px(size_px)
}

/// Stroke width of the glyph lines in pixels.
pub fn stroke_width(size_px: f64, bold: bool) -> f64 {
    let ratio = if bold { 0.125 } else { 0.085 };
    (size_px * ratio).max(1.0)
}

/// The glyph polylines of `text` in pixels: anchored, on its baseline, rotated about its
/// anchor point.
pub fn polylines(text: &Text) -> Vec<Vec<Point>> {
    let unit = unit_px(text.size_px);
    let width = text_width(&text.content, text.size_px);
    let start = match text.anchor {
        Anchor::Start => 0.0,
        Anchor::Middle => -width / 2.0,
        Anchor::End => -width,
    };
    let (sin, cos) = text.rotate_deg.to_radians().sin_cos();
    let place = |dx: f64, dy: f64| {
        // (dx, dy) is the offset from the anchor in unrotated pixels, y down.
        Point::new(
            text.at.x + dx * cos - dy * sin,
            text.at.y + dx * sin + dy * cos,
        )
    };
    let mut lines = Vec::new();
    let mut pen_units = 0.0;
    for c in text.content.chars() {
        let glyph = glyph_or_missing(c);
        for stroke in glyph.strokes {
            lines.push(
                stroke
                    .iter()
                    .map(|&(gx, gy)| {
                        place(
                            start + (pen_units + f64::from(gx)) * unit,
                            -f64::from(gy) * unit,
                        )
                    })
                    .collect(),
            );
        }
        pen_units += f64::from(glyph.width) + LETTER_GAP_UNITS;
    }
    lines
}

/// Splits `text` at spaces into lines no wider than `max_width_px` where possible (a single
/// word wider than that gets a line of its own).
pub fn wrap(text: &str, size_px: f64, max_width_px: f64) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut current = String::new();
    for word in text.split(' ').filter(|w| !w.is_empty()) {
        let candidate = if current.is_empty() {
            word.to_owned()
        } else {
            format!("{current} {word}")
        };
        if current.is_empty() || text_width(&candidate, size_px) <= max_width_px {
            current = candidate;
        } else {
            lines.push(std::mem::replace(&mut current, word.to_owned()));
        }
    }
    if !current.is_empty() {
        lines.push(current);
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    const NEEDED: &str =
        "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz.,-+\u{b1}()%:/_ ";

    #[test]
    fn the_font_has_every_character_the_figures_need() {
        let missing: String = NEEDED.chars().filter(|&c| glyph(c).is_none()).collect();
        assert!(missing.is_empty(), "no glyph for {missing:?}");
    }

    #[test]
    fn glyphs_stay_on_their_grid() {
        for c in NEEDED.chars() {
            let g = glyph(c).unwrap();
            for &(x, y) in g.strokes.iter().flat_map(|s| s.iter()) {
                assert!(
                    (-1..=g.width + 1).contains(&x),
                    "{c:?}: x {x} outside 0..={}",
                    g.width
                );
                assert!((-4..=13).contains(&y), "{c:?}: y {y} outside -4..=13");
            }
            if c != ' ' {
                assert!(!g.strokes.is_empty(), "{c:?} has no strokes");
                assert!(
                    g.strokes.iter().all(|s| s.len() >= 2),
                    "{c:?} has a one-point stroke"
                );
            }
        }
    }

    #[test]
    fn width_grows_with_text_and_size() {
        assert_eq!(text_width("", 16.0), 0.0);
        let one = text_width("V1", 16.0);
        assert!(one > 0.0);
        assert!(text_width("V1 V2", 16.0) > 2.0 * one);
        assert!((text_width("V1", 32.0) - 2.0 * one).abs() < 1e-9);
        // About 0.6 em per letter, like a sans-serif face.
        let per_letter = text_width("abcdefghij", 10.0) / 10.0;
        assert!(
            (4.5..=7.0).contains(&per_letter),
            "{per_letter} px per letter at 10 px"
        );
    }

    #[test]
    fn anchors_place_the_text_around_its_point() {
        let mut text = Text::new("H1", Point::new(100.0, 50.0), Anchor::End, 20.0);
        let xs = |t: &Text| -> (f64, f64) {
            let pts: Vec<Point> = polylines(t).into_iter().flatten().collect();
            let min = pts.iter().map(|p| p.x).fold(f64::INFINITY, f64::min);
            let max = pts.iter().map(|p| p.x).fold(f64::NEG_INFINITY, f64::max);
            (min, max)
        };
        let (_, max) = xs(&text);
        assert!((max - 100.0).abs() < 1e-9, "end anchor ends at {max}");
        text.anchor = Anchor::Start;
        let (min, _) = xs(&text);
        assert!((min - 100.0).abs() < 1e-9, "start anchor starts at {min}");
        // Capitals sit on the baseline and rise one cap height.
        let ys: Vec<f64> = polylines(&text)
            .into_iter()
            .flatten()
            .map(|p| p.y)
            .collect();
        let top = ys.iter().copied().fold(f64::INFINITY, f64::min);
        let bottom = ys.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        assert!((bottom - 50.0).abs() < 1e-9);
        assert!((50.0 - top - cap_height(20.0)).abs() < 1e-9);
    }

    #[test]
    fn rotation_by_minus_90_reads_upwards() {
        let mut text = Text::new("I", Point::new(10.0, 100.0), Anchor::Start, 20.0);
        text.rotate_deg = -90.0;
        let pts: Vec<Point> = polylines(&text).into_iter().flatten().collect();
        // The letter's height now points left (towards smaller x), its width upwards.
        assert!(pts.iter().all(|p| p.x <= 10.0 + 1e-9));
        assert!(pts.iter().all(|p| p.y <= 100.0 + 1e-9));
        assert!(pts.iter().any(|p| p.x < 10.0 - cap_height(20.0) + 1e-6));
    }

    #[test]
    fn wrap_breaks_at_spaces_within_the_width() {
        let lines = wrap("Orca_3 not attempted: H2, H3, H4", 13.0, 120.0);
        assert!(lines.len() >= 2, "{lines:?}");
        assert_eq!(lines.join(" "), "Orca_3 not attempted: H2, H3, H4");
        for line in &lines[..lines.len() - 1] {
            assert!(text_width(line, 13.0) <= 120.0, "{line:?}");
        }
        assert_eq!(wrap("", 13.0, 100.0), Vec::<String>::new());
    }
}
