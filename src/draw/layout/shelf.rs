//! The rows below the drawing that the scale bar, preservation figures, annotations and
//! legend are placed in, so that none overlaps another or the drawing.

use crate::draw::model::Element;

use super::canvas::{translate_element, Canvas};

/// Space between the items below the drawing and between their rows, paper mm.
const ITEM_GAP_MM: f64 = 4.0;

/// Rows of items below the drawing, filled left to right between `left` and `right`
/// (object millimetres) and wrapped to a new row when the next item does not fit: no item
/// overlaps another or the drawing above.
pub(super) struct Shelf {
    left: f64,
    right: f64,
    gap: f64,
    cursor: f64,
    row_top: f64,
    row_bottom: f64,
}

impl Shelf {
    pub(super) fn below(canvas: &Canvas, left: f64, right: f64, z: f64) -> Shelf {
        let gap = ITEM_GAP_MM * canvas.scale;
        Shelf { left, right, gap, cursor: left, row_top: z - gap, row_bottom: z - gap }
    }

    /// Moves `item` (built anywhere) to the next free place.
    pub(super) fn place(&mut self, canvas: &Canvas, item: &mut [Element]) {
        let Some([x0, z0, x1, z1]) = canvas.bounds(item) else { return };
        if self.cursor > self.left && self.cursor + (x1 - x0) > self.right {
            self.row_top = self.row_bottom - self.gap;
            self.cursor = self.left;
        }
        let offset = [self.cursor - x0, self.row_top - z1];
        item.iter_mut().for_each(|e| translate_element(e, offset));
        self.cursor += x1 - x0 + self.gap;
        self.row_bottom = self.row_bottom.min(self.row_top - (z1 - z0));
    }
}
