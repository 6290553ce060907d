//! The drawing model: what every writer draws. Coordinates are millimetres on the paper
//! (publication scale already applied), origin at the top-left corner, y pointing down.
//! Layers are named groups so that vector output stays editable (Inkscape, Illustrator).

/// An RGB colour.
pub type Rgb = [u8; 3];

/// The whole illustration.
#[derive(Clone, Debug, PartialEq)]
pub struct Drawing {
    /// Paper width in millimetres.
    pub width_mm: f64,
    /// Paper height in millimetres.
    pub height_mm: f64,
    /// Resolution of the raster images inside and of PNG output, dots per inch.
    pub dpi: f64,
    /// Top-level layers, drawn in order (later on top).
    pub layers: Vec<Group>,
}

/// A named group of elements (an SVG layer).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Group {
    /// Identifier, also the layer's label: "section", "exterior-view", "annotations"...
    pub id: String,
    /// Content, drawn in order.
    pub children: Vec<Element>,
}

/// One drawable thing.
#[derive(Clone, Debug, PartialEq)]
pub enum Element {
    /// Lines and filled areas.
    Path(Path),
    /// Many round dots of one size and colour (stipple).
    Dots(Dots),
    /// A line of text.
    Text(Text),
    /// A raster image.
    Image(Image),
    /// A nested group.
    Group(Group),
}

/// A step of a path outline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Segment {
    /// Starts a new sub-path at the point.
    MoveTo([f64; 2]),
    /// A straight line to the point.
    LineTo([f64; 2]),
    /// Closes the current sub-path.
    Close,
}

/// How a stroke is drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct Stroke {
    /// Colour.
    pub color: Rgb,
    /// Line width in millimetres.
    pub width_mm: f64,
    /// Dash pattern in millimetres (on, off, on, off...); empty for a solid line.
    pub dash_mm: Vec<f64>,
}

/// A path: outline segments, optionally filled (even-odd rule) and stroked.
#[derive(Clone, Debug, PartialEq)]
pub struct Path {
    /// The outline.
    pub segments: Vec<Segment>,
    /// Fill colour (even-odd rule), if filled.
    pub fill: Option<Rgb>,
    /// Stroke, if stroked.
    pub stroke: Option<Stroke>,
}

impl Path {
    /// A polyline (closed when `closed`) with the given fill and stroke.
    pub fn polyline(points: &[[f64; 2]], closed: bool, fill: Option<Rgb>, stroke: Option<Stroke>) -> Self {
        let mut segments = Vec::with_capacity(points.len() + 1);
        for (i, &p) in points.iter().enumerate() {
            segments.push(if i == 0 { Segment::MoveTo(p) } else { Segment::LineTo(p) });
        }
        if closed && !points.is_empty() {
            segments.push(Segment::Close);
        }
        Path { segments, fill, stroke }
    }

    /// Adds another sub-path.
    pub fn extend_polyline(&mut self, points: &[[f64; 2]], closed: bool) {
        for (i, &p) in points.iter().enumerate() {
            self.segments.push(if i == 0 { Segment::MoveTo(p) } else { Segment::LineTo(p) });
        }
        if closed && !points.is_empty() {
            self.segments.push(Segment::Close);
        }
    }
}

/// Round dots.
#[derive(Clone, Debug, PartialEq)]
pub struct Dots {
    /// Centres in millimetres.
    pub centers: Vec<[f64; 2]>,
    /// Radius in millimetres.
    pub radius_mm: f64,
    /// Colour.
    pub color: Rgb,
}

/// Horizontal placement of a text relative to its position.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Anchor {
    /// The text starts at the position.
    Start,
    /// The text is centred on the position.
    Middle,
    /// The text ends at the position.
    End,
}

/// A line of text in Helvetica (base-14 in PDF and EPS; the built-in stroke font in PNG).
#[derive(Clone, Debug, PartialEq)]
pub struct Text {
    /// Position of the anchor point on the baseline, in millimetres.
    pub position: [f64; 2],
    /// The text.
    pub content: String,
    /// Font size (em height) in millimetres.
    pub size_mm: f64,
    /// Horizontal alignment.
    pub anchor: Anchor,
    /// Colour.
    pub color: Rgb,
}

/// An RGBA raster placed in a rectangle of the paper.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Left edge in millimetres.
    pub x_mm: f64,
    /// Top edge in millimetres.
    pub y_mm: f64,
    /// Width on paper in millimetres.
    pub width_mm: f64,
    /// Height on paper in millimetres.
    pub height_mm: f64,
    /// Width in pixels.
    pub width_px: u32,
    /// Height in pixels.
    pub height_px: u32,
    /// `width_px * height_px * 4` bytes, straight (not premultiplied) alpha, top row first.
    pub rgba: Vec<u8>,
}

/// Helvetica advance widths (per 1000 em) of ASCII 32..=126, from the font's AFM, to
/// place anchored text in PDF (which, unlike SVG and PostScript, cannot measure it).
const HELVETICA_WIDTHS: [u16; 95] = [
    278, 278, 355, 556, 556, 889, 667, 191, 333, 333, 389, 584, 278, 333, 278, 278, 556, 556, 556, 556, 556, 556, 556,
    556, 556, 556, 278, 278, 584, 584, 584, 556, 1015, 667, 667, 722, 722, 667, 611, 778, 722, 278, 500, 667, 556, 833,
    722, 778, 667, 778, 722, 667, 611, 722, 667, 944, 667, 667, 611, 278, 278, 278, 469, 556, 333, 556, 556, 500, 556,
    556, 278, 556, 556, 222, 222, 500, 222, 833, 556, 556, 556, 556, 333, 500, 278, 556, 500, 722, 500, 500, 500, 334,
    260, 334, 584,
];

/// Width of `text` in Helvetica at `size_mm`, in millimetres.
pub fn helvetica_width_mm(text: &str, size_mm: f64) -> f64 {
    text.chars()
        .map(|c| match c {
            ' '..='~' => HELVETICA_WIDTHS[c as usize - 32] as f64,
            'Ø' => 778.0,
            '°' => 400.0,
            _ => 556.0,
        })
        .sum::<f64>()
        * size_mm
        / 1000.0
}

/// `text` as Latin-1 bytes (the encoding the PostScript and PDF writers select);
/// characters outside Latin-1 become `?`.
pub fn latin1_bytes(text: &str) -> Vec<u8> {
    text.chars().map(|c| if (c as u32) < 256 { c as u32 as u8 } else { b'?' }).collect()
}

/// A rectangle `[left, top, right, bottom]` in millimetres.
pub type Bounds = [f64; 4];

/// The width a text takes in every writer: the PNG's stroke font is a little wider than
/// the Helvetica of the vector formats, so the wider of the two.
pub fn text_extent_mm(text: &str, size_mm: f64) -> f64 {
    helvetica_width_mm(text, size_mm).max(crate::draw::font::text_width_mm(text, size_mm))
}

/// Gives `include` the corners of what `element` covers. `text_scale` is the length one
/// paper millimetre of text or dot takes in the element's coordinates (the publication
/// scale while the layout works in object millimetres); `y_up` says whether y grows
/// upwards there (the layout's z) or downwards (the paper's y).
pub(crate) fn element_extent(element: &Element, text_scale: f64, y_up: bool, include: &mut dyn FnMut(f64, f64)) {
    let up = if y_up { 1.0 } else { -1.0 };
    match element {
        Element::Path(p) => p.segments.iter().for_each(|s| match s {
            Segment::MoveTo(q) | Segment::LineTo(q) => include(q[0], q[1]),
            Segment::Close => {}
        }),
        Element::Dots(d) => {
            let r = d.radius_mm * text_scale;
            d.centers.iter().for_each(|c| {
                include(c[0] - r, c[1] - r);
                include(c[0] + r, c[1] + r);
            })
        }
        Element::Text(t) => {
            let width = text_extent_mm(&t.content, t.size_mm) * text_scale;
            let left = match t.anchor {
                Anchor::Start => t.position[0],
                Anchor::Middle => t.position[0] - width / 2.0,
                Anchor::End => t.position[0] - width,
            };
            // Descenders below the baseline, capitals and accents above it.
            include(left, t.position[1] - up * 0.25 * t.size_mm * text_scale);
            include(left + width, t.position[1] + up * 0.8 * t.size_mm * text_scale);
        }
        Element::Image(i) => {
            include(i.x_mm, i.y_mm);
            include(i.x_mm + i.width_mm, i.y_mm - up * i.height_mm);
        }
        Element::Group(g) => g.children.iter().for_each(|c| element_extent(c, text_scale, y_up, include)),
    }
}

/// The smallest rectangle holding every corner `visit` gives, `None` when it gives none.
pub(crate) fn bounds_of(visit: impl FnOnce(&mut dyn FnMut(f64, f64))) -> Option<Bounds> {
    let mut bounds = [f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY];
    visit(&mut |x, y| {
        bounds = [bounds[0].min(x), bounds[1].min(y), bounds[2].max(x), bounds[3].max(y)];
    });
    bounds.iter().all(|v| v.is_finite()).then_some(bounds)
}

impl Element {
    /// The paper rectangle the element covers (text at its widest writer's width).
    pub fn bounds(&self) -> Option<Bounds> {
        bounds_of(|include| element_extent(self, 1.0, false, include))
    }
}

impl Group {
    /// The paper rectangle the group's elements cover, `None` when empty.
    pub fn bounds(&self) -> Option<Bounds> {
        bounds_of(|include| self.children.iter().for_each(|e| element_extent(e, 1.0, false, include)))
    }
}

/// Whether two rectangles share more than a boundary.
pub fn bounds_overlap(a: &Bounds, b: &Bounds) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

impl Drawing {
    /// All elements, depth first, with the ids of the groups enclosing them.
    pub fn elements(&self) -> Vec<(&str, &Element)> {
        fn walk<'a>(group: &'a Group, out: &mut Vec<(&'a str, &'a Element)>) {
            for e in &group.children {
                out.push((group.id.as_str(), e));
                if let Element::Group(g) = e {
                    walk(g, out);
                }
            }
        }
        let mut out = Vec::new();
        for layer in &self.layers {
            walk(layer, &mut out);
        }
        out
    }

    /// The layer with this id.
    pub fn layer(&self, id: &str) -> Option<&Group> {
        self.layers.iter().find(|g| g.id == id)
    }
}
