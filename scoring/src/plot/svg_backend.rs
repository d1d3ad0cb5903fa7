//! SVG writer: one element per primitive, text as `<text>` in a sans-serif family, all
//! text escaped for XML.

use std::fmt::Write as _;

use super::primitives::{Anchor, Drawing, Point, Primitive, Rgba, Style, Text};
use super::stroke_font;

/// The font family asked of the SVG viewer.
const FONT_FAMILY: &str = "DejaVu Sans, Helvetica, Arial, sans-serif";

/// The drawing as a standalone SVG document.
pub fn render(drawing: &Drawing) -> String {
    let (w, h) = (drawing.width_px, drawing.height_px);
    let mut svg = String::new();
    // Writing to a String cannot fail, so the fmt::Results below are ignored.
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="{FONT_FAMILY}">"#
    );
    let _ = writeln!(svg, "<title>{}</title>", escape(&drawing.title));
    let _ = writeln!(
        svg,
        r#"<rect x="0" y="0" width="{w}" height="{h}"{}/>"#,
        paint("fill", drawing.background)
    );
    for item in &drawing.items {
        match item {
            Primitive::Path {
                points,
                closed,
                style,
                class,
            } => {
                let element = if *closed { "polygon" } else { "polyline" };
                let style = if *closed {
                    *style
                } else {
                    Style {
                        fill: None,
                        ..*style
                    }
                };
                let _ = writeln!(
                    svg,
                    r#"<{element}{} points="{}"{}/>"#,
                    class_attr(*class),
                    points_attr(points),
                    style_attrs(&style)
                );
            }
            Primitive::Circle {
                center,
                radius,
                style,
                class,
            } => {
                let _ = writeln!(
                    svg,
                    r#"<circle{} cx="{}" cy="{}" r="{}"{}/>"#,
                    class_attr(*class),
                    num(center.x),
                    num(center.y),
                    num(*radius),
                    style_attrs(style)
                );
            }
            Primitive::Text(text) => write_text(&mut svg, text),
        }
    }
    svg.push_str("</svg>\n");
    svg
}

fn write_text(svg: &mut String, text: &Text) {
    let anchor = match text.anchor {
        Anchor::Start => "start",
        Anchor::Middle => "middle",
        Anchor::End => "end",
    };
    let mut attrs = format!(
        r#"x="{}" y="{}" font-size="{}" text-anchor="{anchor}"{}"#,
        num(text.at.x),
        num(text.at.y),
        num(text.size_px),
        paint("fill", text.color)
    );
    if text.bold {
        attrs.push_str(r#" font-weight="bold""#);
    }
    if text.halo {
        let width = 2.0 * stroke_font::stroke_width(text.size_px, text.bold) + 2.0;
        let _ = write!(
            attrs,
            r##" stroke="#ffffff" stroke-width="{}" stroke-linejoin="round" paint-order="stroke""##,
            num(width)
        );
    }
    if text.rotate_deg != 0.0 {
        let _ = write!(
            attrs,
            r#" transform="rotate({} {} {})""#,
            num(text.rotate_deg),
            num(text.at.x),
            num(text.at.y)
        );
    }
    let _ = writeln!(svg, "<text {attrs}>{}</text>", escape(&text.content));
}

fn class_attr(class: Option<&str>) -> String {
    class.map_or_else(String::new, |c| format!(r#" class="{}""#, escape(c)))
}

fn points_attr(points: &[Point]) -> String {
    points
        .iter()
        .map(|p| format!("{},{}", num(p.x), num(p.y)))
        .collect::<Vec<_>>()
        .join(" ")
}

fn style_attrs(style: &Style) -> String {
    let mut attrs = match style.fill {
        Some(color) => paint("fill", color),
        None => r#" fill="none""#.to_owned(),
    };
    if let Some((color, width)) = style.stroke {
        attrs.push_str(&paint("stroke", color));
        let _ = write!(
            attrs,
            r#" stroke-width="{}" stroke-linejoin="round" stroke-linecap="round""#,
            num(width)
        );
    }
    attrs
}

/// ` fill="#rrggbb"` (or stroke), with an opacity attribute when not opaque.
fn paint(property: &str, color: Rgba) -> String {
    let mut attr = format!(
        r##" {property}="#{:02x}{:02x}{:02x}""##,
        color.r, color.g, color.b
    );
    if color.a < 255 {
        let _ = write!(
            attr,
            r#" {property}-opacity="{}""#,
            num(f64::from(color.a) / 255.0)
        );
    }
    attr
}

/// A coordinate with at most two decimals and no trailing zeros; non-finite as 0.
fn num(v: f64) -> String {
    if !v.is_finite() {
        return "0".to_owned();
    }
    let s = format!("{v:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_owned()
    } else {
        s.to_owned()
    }
}

/// `text` safe as XML character data and attribute values: markup characters become
/// entities, characters XML 1.0 cannot carry at all become U+FFFD.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            '\t' | '\n' | '\r' => out.push(c),
            c if (c as u32) < 0x20 || c == '\u{FFFE}' || c == '\u{FFFF}' => out.push('\u{FFFD}'),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markup_characters_are_escaped() {
        assert_eq!(
            escape(r#"a<b & "c" 'd'>"#),
            "a&lt;b &amp; &quot;c&quot; &apos;d&apos;&gt;"
        );
        assert_eq!(escape("Orca_full ±0.02"), "Orca_full ±0.02");
        assert_eq!(escape("bell\u{7}"), "bell\u{FFFD}");
    }

    #[test]
    fn hostile_labels_survive_an_xml_parser() {
        let mut drawing = Drawing::new(100, 50, "t</title><x>");
        let label = "</text><script>&amp;\"'\u{1}";
        drawing.text(Text::new(
            label,
            Point::new(10.0, 20.0),
            Anchor::Start,
            12.0,
        ));
        let svg = render(&drawing);
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let text = doc
            .descendants()
            .find(|n| n.has_tag_name("text"))
            .unwrap()
            .text()
            .unwrap();
        assert_eq!(text, "</text><script>&amp;\"'\u{FFFD}");
        let title = doc.descendants().find(|n| n.has_tag_name("title")).unwrap();
        assert_eq!(title.text(), Some("t</title><x>"));
    }

    #[test]
    fn numbers_are_short_and_finite() {
        assert_eq!(num(1.0), "1");
        assert_eq!(num(1.0 / 3.0), "0.33");
        assert_eq!(num(-0.001), "0");
        assert_eq!(num(f64::NAN), "0");
        assert_eq!(num(12.5), "12.5");
    }

    #[test]
    fn open_paths_are_never_filled_and_translucency_is_written() {
        let mut drawing = Drawing::new(10, 10, "t");
        let fill = Rgba::rgb(1, 2, 3).with_alpha(0.2);
        let pts = vec![
            Point::new(0.0, 0.0),
            Point::new(5.0, 5.0),
            Point::new(0.0, 5.0),
        ];
        drawing.path(pts.clone(), false, Style::filled(fill), None);
        drawing.path(pts, true, Style::filled(fill), Some("series"));
        let svg = render(&drawing);
        assert!(
            svg.contains(r#"<polyline points="0,0 5,5 0,5" fill="none"/>"#),
            "{svg}"
        );
        assert!(
            svg.contains(r##"<polygon class="series" points="0,0 5,5 0,5" fill="#010203" fill-opacity="0.2"/>"##),
            "{svg}"
        );
    }
}
