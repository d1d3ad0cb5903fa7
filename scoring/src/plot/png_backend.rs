//! PNG raster via tiny-skia: antialiased fills and round-capped strokes; text as the stroke
//! font's polylines.

use tiny_skia::{FillRule, LineCap, LineJoin, Paint, Path, PathBuilder, Pixmap, Stroke, Transform};

use super::PlotError;
use super::primitives::{Drawing, Point, Primitive, Rgba, Style, Text};
use super::stroke_font;

/// The drawing as PNG bytes (8-bit RGBA).
pub fn render(drawing: &Drawing) -> Result<Vec<u8>, PlotError> {
    let (w, h) = (drawing.width_px, drawing.height_px);
    let mut pixmap = Pixmap::new(w, h).ok_or_else(|| PlotError::Raster {
        reason: format!("cannot make a {w}x{h} px canvas"),
    })?;
    let bg = drawing.background;
    pixmap.fill(tiny_skia::Color::from_rgba8(bg.r, bg.g, bg.b, bg.a));
    for item in &drawing.items {
        match item {
            Primitive::Path {
                points,
                closed,
                style,
                ..
            } => {
                if let Some(path) = polyline_path(std::iter::once(points.as_slice()), *closed) {
                    let style = if *closed {
                        *style
                    } else {
                        Style {
                            fill: None,
                            ..*style
                        }
                    };
                    paint_path(&mut pixmap, &path, &style);
                }
            }
            Primitive::Circle {
                center,
                radius,
                style,
                ..
            } => {
                if let Some(path) =
                    PathBuilder::from_circle(center.x as f32, center.y as f32, *radius as f32)
                {
                    paint_path(&mut pixmap, &path, style);
                }
            }
            Primitive::Text(text) => draw_text(&mut pixmap, text),
        }
    }
    pixmap.encode_png().map_err(|e| PlotError::Raster {
        reason: format!("PNG encoding failed: {e}"),
    })
}

/// One path of all `lines`; `None` when nothing drawable remains.
fn polyline_path<'a>(lines: impl Iterator<Item = &'a [Point]>, closed: bool) -> Option<Path> {
    let mut builder = PathBuilder::new();
    for line in lines {
        let mut points = line.iter().filter(|p| p.x.is_finite() && p.y.is_finite());
        let Some(first) = points.next() else { continue };
        builder.move_to(first.x as f32, first.y as f32);
        for p in points {
            builder.line_to(p.x as f32, p.y as f32);
        }
        if closed {
            builder.close();
        }
    }
    builder.finish()
}

fn paint_of(color: Rgba) -> Paint<'static> {
    let mut paint = Paint::default();
    paint.set_color_rgba8(color.r, color.g, color.b, color.a);
    paint.anti_alias = true;
    paint
}

fn round_stroke(width_px: f64) -> Stroke {
    Stroke {
        width: width_px as f32,
        line_cap: LineCap::Round,
        line_join: LineJoin::Round,
        ..Stroke::default()
    }
}

fn paint_path(pixmap: &mut Pixmap, path: &Path, style: &Style) {
    if let Some(fill) = style.fill {
        pixmap.fill_path(
            path,
            &paint_of(fill),
            FillRule::Winding,
            Transform::identity(),
            None,
        );
    }
    if let Some((color, width)) = style.stroke {
        pixmap.stroke_path(
            path,
            &paint_of(color),
            &round_stroke(width),
            Transform::identity(),
            None,
        );
    }
}

fn draw_text(pixmap: &mut Pixmap, text: &Text) {
    let lines = stroke_font::polylines(text);
    let Some(path) = polyline_path(lines.iter().map(Vec::as_slice), false) else {
        return;
    };
    let width = stroke_font::stroke_width(text.size_px, text.bold);
    if text.halo {
        let halo = round_stroke(2.0 * width + 2.0);
        pixmap.stroke_path(
            &path,
            &paint_of(Rgba::WHITE),
            &halo,
            Transform::identity(),
            None,
        );
    }
    pixmap.stroke_path(
        &path,
        &paint_of(text.color),
        &round_stroke(width),
        Transform::identity(),
        None,
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::primitives::Anchor;

    fn decode(png: &[u8]) -> Pixmap {
        Pixmap::decode_png(png).unwrap()
    }

    fn pixel(pixmap: &Pixmap, x: u32, y: u32) -> (u8, u8, u8, u8) {
        let c = pixmap.pixel(x, y).unwrap().demultiply();
        (c.red(), c.green(), c.blue(), c.alpha())
    }

    #[test]
    fn an_empty_drawing_is_a_white_canvas_of_its_size() {
        let png = render(&Drawing::new(40, 30, "empty")).unwrap();
        let pixmap = decode(&png);
        assert_eq!((pixmap.width(), pixmap.height()), (40, 30));
        assert!(
            pixmap
                .pixels()
                .iter()
                .all(|p| p.red() == 255 && p.alpha() == 255)
        );
    }

    #[test]
    fn shapes_land_where_they_are_described() {
        let mut drawing = Drawing::new(60, 60, "shapes");
        let square = vec![
            Point::new(5.0, 5.0),
            Point::new(25.0, 5.0),
            Point::new(25.0, 25.0),
            Point::new(5.0, 25.0),
        ];
        drawing.path(square, true, Style::filled(Rgba::rgb(200, 0, 0)), None);
        drawing.circle(
            Point::new(45.0, 45.0),
            8.0,
            Style::filled(Rgba::rgb(0, 0, 200)),
            None,
        );
        let pixmap = decode(&render(&drawing).unwrap());
        assert_eq!(pixel(&pixmap, 15, 15), (200, 0, 0, 255));
        assert_eq!(pixel(&pixmap, 45, 45), (0, 0, 200, 255));
        assert_eq!(pixel(&pixmap, 45, 15), (255, 255, 255, 255));
    }

    #[test]
    fn text_leaves_ink_inside_its_box_only() {
        let mut drawing = Drawing::new(120, 40, "text");
        drawing.text(Text::new(
            "Orca 5",
            Point::new(10.0, 30.0),
            Anchor::Start,
            20.0,
        ));
        let pixmap = decode(&render(&drawing).unwrap());
        let width = stroke_font::text_width("Orca 5", 20.0);
        let mut inked = 0;
        for y in 0..40 {
            for x in 0..120 {
                if pixel(&pixmap, x, y).0 < 200 {
                    inked += 1;
                    let (fx, fy) = (f64::from(x), f64::from(y));
                    assert!(fx >= 8.0 && fx <= 12.0 + width, "ink at x {x}");
                    assert!(
                        fy >= 30.0 - stroke_font::cap_height(20.0) - 2.0 && fy <= 32.0,
                        "ink at y {y}"
                    );
                }
            }
        }
        assert!(inked > 60, "only {inked} inked pixels");
    }
}
