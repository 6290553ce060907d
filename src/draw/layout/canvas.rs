//! The object-millimetre canvas the layout draws on, in named layers, and its mapping to
//! paper at the publication scale once everything is placed.

use crate::draw::model::{bounds_of, element_extent, Anchor, Drawing, Element, Group, Segment, Stroke, Text};

use super::BLACK;

/// Paper margin around everything, mm.
const MARGIN_MM: f64 = 8.0;

/// Elements in object coordinates, grouped in layers, with the publication scale.
pub(super) struct Canvas {
    /// Object millimetres per paper millimetre (2 for 1:2).
    pub(super) scale: f64,
    pub(super) layers: Vec<Group>,
}

impl Canvas {
    pub(super) fn layer(&mut self, id: &str) -> &mut Vec<Element> {
        if let Some(i) = self.layers.iter().position(|g| g.id == id) {
            return &mut self.layers[i].children;
        }
        self.layers.push(Group { id: id.into(), children: Vec::new() });
        &mut self.layers.last_mut().expect("just pushed").children
    }

    pub(super) fn stroke(&self, width_mm: f64, dash_mm: &[f64]) -> Stroke {
        Stroke { color: BLACK, width_mm, dash_mm: dash_mm.to_vec() }
    }

    /// The rectangle (object millimetres, z up) `elements` cover.
    pub(super) fn bounds(&self, elements: &[Element]) -> Option<[f64; 4]> {
        bounds_of(|include| elements.iter().for_each(|e| element_extent(e, self.scale, true, include)))
    }

    /// Maps object coordinates to paper millimetres and wraps up the drawing.
    pub(super) fn finish(mut self, dpi: f64) -> Drawing {
        let all: Vec<Element> = self.layers.iter().map(|g| Element::Group(g.clone())).collect();
        let [x0, z0, x1, z1] = self.bounds(&all).unwrap_or([0.0, 0.0, 1.0, 1.0]);
        let scale = self.scale;
        let map = move |p: [f64; 2]| [(p[0] - x0) / scale + MARGIN_MM, (z1 - p[1]) / scale + MARGIN_MM];
        fn convert(e: &mut Element, scale: f64, map: &dyn Fn([f64; 2]) -> [f64; 2]) {
            match e {
                Element::Path(p) => p.segments.iter_mut().for_each(|s| match s {
                    Segment::MoveTo(q) | Segment::LineTo(q) => *q = map(*q),
                    Segment::Close => {}
                }),
                Element::Dots(d) => d.centers.iter_mut().for_each(|c| *c = map(*c)),
                Element::Text(t) => t.position = map(t.position),
                Element::Image(i) => {
                    let corner = map([i.x_mm, i.y_mm]);
                    (i.x_mm, i.y_mm) = (corner[0], corner[1]);
                    i.width_mm /= scale;
                    i.height_mm /= scale;
                }
                Element::Group(g) => g.children.iter_mut().for_each(|c| convert(c, scale, map)),
            }
        }
        for layer in &mut self.layers {
            for e in &mut layer.children {
                convert(e, scale, &map);
            }
        }
        Drawing {
            width_mm: (x1 - x0) / scale + 2.0 * MARGIN_MM,
            height_mm: (z1 - z0) / scale + 2.0 * MARGIN_MM,
            dpi,
            layers: self.layers,
        }
    }

    pub(super) fn text(&mut self, layer: &str, position: [f64; 2], content: String, size_mm: f64, anchor: Anchor) {
        self.layer(layer).push(Element::Text(Text { position, content, size_mm, anchor, color: BLACK }));
    }
}

pub(super) fn translate_element(e: &mut Element, offset: [f64; 2]) {
    let moved = |q: &mut [f64; 2]| {
        q[0] += offset[0];
        q[1] += offset[1];
    };
    match e {
        Element::Path(p) => p.segments.iter_mut().for_each(|s| match s {
            Segment::MoveTo(q) | Segment::LineTo(q) => moved(q),
            Segment::Close => {}
        }),
        Element::Dots(d) => d.centers.iter_mut().for_each(moved),
        Element::Text(t) => moved(&mut t.position),
        Element::Image(i) => {
            i.x_mm += offset[0];
            i.y_mm += offset[1];
        }
        Element::Group(g) => g.children.iter_mut().for_each(|c| translate_element(c, offset)),
    }
}
