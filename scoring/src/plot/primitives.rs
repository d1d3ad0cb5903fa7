//! The drawing description both backends render: a canvas and an ordered list of primitives
//! in pixel coordinates (origin top left, y down), painted in list order.

/// A colour with straight (not premultiplied) alpha.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rgba {
    /// Red, 0–255.
    pub r: u8,
    /// Green, 0–255.
    pub g: u8,
    /// Blue, 0–255.
    pub b: u8,
    /// Opacity, 0 (transparent) to 255 (opaque).
    pub a: u8,
}

impl Rgba {
    /// An opaque colour.
    pub const fn rgb(r: u8, g: u8, b: u8) -> Self {
        Self { r, g, b, a: 255 }
    }

    /// The same colour with opacity `alpha` in [0, 1] (clamped).
    pub fn with_alpha(self, alpha: f64) -> Self {
        let a = (alpha.clamp(0.0, 1.0) * 255.0).round() as u8;
        Self { a, ..self }
    }

    /// Opaque white.
    pub const WHITE: Self = Self::rgb(255, 255, 255);
    /// Near-black for text and axes.
    pub const INK: Self = Self::rgb(34, 34, 34);
    /// Mid grey for secondary text.
    pub const GREY: Self = Self::rgb(102, 102, 102);
    /// Light grey for grid lines.
    pub const GRID: Self = Self::rgb(204, 204, 204);
}

/// A point in pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// Pixels from the left edge.
    pub x: f64,
    /// Pixels from the top edge.
    pub y: f64,
}

impl Point {
    /// The point `(x, y)`.
    pub const fn new(x: f64, y: f64) -> Self {
        Self { x, y }
    }
}

/// How a shape is painted: an optional fill, then an optional outline.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Style {
    /// Interior colour, if filled.
    pub fill: Option<Rgba>,
    /// Outline colour and width in pixels, if outlined.
    pub stroke: Option<(Rgba, f64)>,
}

impl Style {
    /// An outline only.
    pub const fn line(color: Rgba, width_px: f64) -> Self {
        Self {
            fill: None,
            stroke: Some((color, width_px)),
        }
    }

    /// A fill only.
    #[cfg(test)]
    pub const fn filled(color: Rgba) -> Self {
        Self {
            fill: Some(color),
            stroke: None,
        }
    }

    /// A fill and an outline.
    pub const fn filled_and_outlined(fill: Rgba, stroke: Rgba, width_px: f64) -> Self {
        Self {
            fill: Some(fill),
            stroke: Some((stroke, width_px)),
        }
    }
}

/// Which point of a text line its position names, horizontally. Vertically the position is
/// always on the baseline.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Anchor {
    /// The position is where the text starts.
    Start,
    /// The position is the middle of the text.
    Middle,
    /// The position is where the text ends.
    End,
}

/// One line of text.
#[derive(Debug, Clone, PartialEq)]
pub struct Text {
    /// The characters.
    pub content: String,
    /// Anchor point on the baseline.
    pub at: Point,
    /// Horizontal anchoring of `at`.
    pub anchor: Anchor,
    /// Font size (em) in pixels.
    pub size_px: f64,
    /// Text colour.
    pub color: Rgba,
    /// Heavier strokes (titles).
    pub bold: bool,
    /// A white outline under the glyphs, so text stays readable over lines and fills.
    pub halo: bool,
    /// Rotation about `at` in degrees, clockwise (-90 reads bottom to top).
    pub rotate_deg: f64,
}

impl Text {
    /// Plain dark text of `size_px`, horizontal, no halo.
    pub fn new(content: impl Into<String>, at: Point, anchor: Anchor, size_px: f64) -> Self {
        Self {
            content: content.into(),
            at,
            anchor,
            size_px,
            color: Rgba::INK,
            bold: false,
            halo: false,
            rotate_deg: 0.0,
        }
    }
}

/// One thing to paint.
#[derive(Debug, Clone, PartialEq)]
pub enum Primitive {
    /// A polyline (`closed == false`) or polygon (`closed == true`).
    Path {
        /// Vertices in order.
        points: Vec<Point>,
        /// Whether the last vertex joins the first.
        closed: bool,
        /// Fill and outline (a fill is only painted when closed).
        style: Style,
        /// A name for what the shape shows, written as the SVG `class` (e.g. `series`).
        class: Option<&'static str>,
    },
    /// A circle.
    Circle {
        /// Centre.
        center: Point,
        /// Radius in pixels.
        radius: f64,
        /// Fill and outline.
        style: Style,
        /// A name for what the shape shows, written as the SVG `class` (e.g. `marker`).
        class: Option<&'static str>,
    },
    /// A line of text.
    Text(Text),
}

/// A complete figure: canvas size, background and primitives in painting order.
#[derive(Debug, Clone, PartialEq)]
pub struct Drawing {
    /// Canvas width in pixels.
    pub width_px: u32,
    /// Canvas height in pixels.
    pub height_px: u32,
    /// Figure title (the SVG `<title>`).
    pub title: String,
    /// Painted first, over the whole canvas.
    pub background: Rgba,
    /// Painted in order, later over earlier.
    pub items: Vec<Primitive>,
}

impl Drawing {
    /// An empty white canvas.
    pub fn new(width_px: u32, height_px: u32, title: impl Into<String>) -> Self {
        Self {
            width_px,
            height_px,
            title: title.into(),
            background: Rgba::WHITE,
            items: Vec::new(),
        }
    }

    /// Adds a straight line segment.
    pub fn line(&mut self, from: Point, to: Point, color: Rgba, width_px: f64) {
        self.items.push(Primitive::Path {
            points: vec![from, to],
            closed: false,
            style: Style::line(color, width_px),
            class: None,
        });
    }

    /// Adds a polygon or polyline.
    pub fn path(
        &mut self,
        points: Vec<Point>,
        closed: bool,
        style: Style,
        class: Option<&'static str>,
    ) {
        self.items.push(Primitive::Path {
            points,
            closed,
            style,
            class,
        });
    }

    /// Adds a circle.
    pub fn circle(
        &mut self,
        center: Point,
        radius: f64,
        style: Style,
        class: Option<&'static str>,
    ) {
        self.items.push(Primitive::Circle {
            center,
            radius,
            style,
            class,
        });
    }

    /// Adds a line of text.
    pub fn text(&mut self, text: Text) {
        self.items.push(Primitive::Text(text));
    }
}
