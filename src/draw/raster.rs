//! An orthographic z-buffer rasterizer: which face is nearest to the viewer in every pixel
//! of a parallel projection. Ambient occlusion renders depth maps with it, and the drawing
//! renders the exterior and interior views with it: a 500k-face scan rasterizes in
//! milliseconds, where drawing one vector path per face takes seconds and produces files
//! no illustration program opens comfortably.

use rayon::prelude::*;

use crate::mesh::{Point, Vector};

/// A parallel projection onto a pixel grid: `right` and `down` span the image plane,
/// `forward` points from the viewer into the scene (depth grows along it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrthographicCamera {
    /// Unit vector along increasing pixel columns.
    pub right: Vector,
    /// Unit vector along increasing pixel rows (image y points down).
    pub down: Vector,
    /// Unit viewing direction; `right x down = forward` is not required.
    pub forward: Vector,
    /// The scene point at the top-left corner of pixel (0, 0).
    pub origin: Point,
    /// Size of one pixel in millimetres.
    pub pixel_mm: f64,
    /// Image width in pixels.
    pub width: usize,
    /// Image height in pixels.
    pub height: usize,
}

impl OrthographicCamera {
    /// A camera looking along `forward` whose image just contains `points` (plus
    /// `margin_px` pixels on each side); `up_hint` (made orthogonal to `forward`) points
    /// up in the image and `right = forward x up`, so the image is not mirrored.
    pub fn fit(points: &[Point], forward: Vector, up_hint: Vector, pixel_mm: f64, margin_px: usize) -> Self {
        let forward = forward.normalize();
        let mut up = up_hint - forward * up_hint.dot(&forward);
        if up.norm() < 1e-9 {
            up = forward.cross(&Vector::x());
            if up.norm() < 1e-9 {
                up = forward.cross(&Vector::y());
            }
        }
        let up = up.normalize();
        let right = forward.cross(&up).normalize();
        let down = -up;
        let (mut u0, mut u1, mut v0, mut v1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
        // Comparisons rather than f64::min and max, which also order NaN and compile to
        // several instructions each on x86-64: a NaN fails both and is skipped all the same.
        for p in points {
            let (u, v) = (p.coords.dot(&right), p.coords.dot(&down));
            if u < u0 {
                u0 = u;
            }
            if u > u1 {
                u1 = u;
            }
            if v < v0 {
                v0 = v;
            }
            if v > v1 {
                v1 = v;
            }
        }
        if !u0.is_finite() {
            (u0, u1, v0, v1) = (0.0, 0.0, 0.0, 0.0);
        }
        let margin = margin_px as f64 * pixel_mm;
        // Saturating: a non-finite or huge extent gives a huge size (which the callers
        // bound before allocating), never one that wraps to zero.
        let width = (((u1 - u0 + 2.0 * margin) / pixel_mm).ceil() as usize).saturating_add(1);
        let height = (((v1 - v0 + 2.0 * margin) / pixel_mm).ceil() as usize).saturating_add(1);
        let origin = Point::from(right * (u0 - margin) + down * (v0 - margin));
        OrthographicCamera { right, down, forward, origin, pixel_mm, width, height }
    }

    /// `[column, row, depth_mm]` of `p`: fractional pixel coordinates (pixel centres at
    /// `.5`) and the distance along `forward`.
    #[inline]
    pub fn project(&self, p: &Point) -> [f32; 3] {
        let d = p - self.origin;
        [
            (d.dot(&self.right) / self.pixel_mm) as f32,
            (d.dot(&self.down) / self.pixel_mm) as f32,
            d.dot(&self.forward) as f32,
        ]
    }

    /// All positions projected, in parallel.
    pub fn project_all(&self, positions: &[Point]) -> Vec<[f32; 3]> {
        positions.par_iter().map(|p| self.project(p)).collect()
    }
}

/// Marks pixels no face covers.
pub const NO_FACE: u32 = u32::MAX;

/// The nearest depth and the face seen in each pixel, rows top to bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct ZBuffer {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Depth of the nearest surface per pixel; `f32::INFINITY` where empty.
    pub depth: Vec<f32>,
    /// Index of the nearest face per pixel; [`NO_FACE`] where empty.
    pub face: Vec<u32>,
}

impl ZBuffer {
    /// An empty buffer.
    pub fn new(width: usize, height: usize) -> Self {
        ZBuffer { width, height, depth: vec![f32::INFINITY; width * height], face: vec![NO_FACE; width * height] }
    }

    /// Empties the buffer for reuse, keeping its size.
    pub fn clear(&mut self) {
        self.depth.fill(f32::INFINITY);
        self.face.fill(NO_FACE);
    }
}

/// Rasterizes `triangles` (vertices already projected by [`OrthographicCamera::project`])
/// into `buffer`, on one thread. Both windings are drawn: the nearest surface wins. Pixels
/// past column or row `i32::MAX` are left empty.
pub fn rasterize_into(buffer: &mut ZBuffer, projected: &[[f32; 3]], triangles: &[[u32; 3]]) {
    let (width, height) = (buffer.width, buffer.height);
    if width == 0 || height == 0 {
        return;
    }
    let spans = pixel_spans(projected, false);
    rasterize_rows(&mut buffer.depth, &mut buffer.face, width, 0, height, projected, &spans, triangles.iter().copied().enumerate());
}

/// Rasterizes in horizontal bands, one per task, for a single large image; the same
/// buffer as [`rasterize_into`].
pub fn rasterize_parallel(width: usize, height: usize, projected: &[[f32; 3]], triangles: &[[u32; 3]]) -> ZBuffer {
    let mut buffer = ZBuffer::new(width, height);
    if width == 0 || height == 0 {
        return buffer;
    }
    let bands = (rayon::current_num_threads() * 4).clamp(1, height.max(1));
    let rows_per_band = height.div_ceil(bands).max(1);
    // Bin faces by the bands their rows touch, so each band reads only its faces.
    let band_count = height.div_ceil(rows_per_band);
    let mut bins: Vec<Vec<u32>> = vec![Vec::new(); band_count];
    let spans = pixel_spans(projected, true);
    let bounds = PixelBounds::new(width, 0, height);
    for (f, &t) in triangles.iter().enumerate() {
        let Some([_, _, y0, y1]) = bounds.covered(&spans, t) else { continue };
        for bin in &mut bins[y0 / rows_per_band..=y1 / rows_per_band] {
            bin.push(f as u32);
        }
    }
    buffer
        .depth
        .par_chunks_mut(rows_per_band * width)
        .zip(buffer.face.par_chunks_mut(rows_per_band * width))
        .zip(bins.par_iter())
        .enumerate()
        .for_each(|(band, ((depth, face), faces))| {
            let row0 = band * rows_per_band;
            let rows = depth.len() / width;
            let faces = faces.iter().map(|&f| (f as usize, triangles[f as usize]));
            rasterize_rows(depth, face, width, row0, rows, projected, &spans, faces);
        });
    buffer
}

/// The pixel rows or columns whose centres a vertex's coordinate lies at or beyond
/// (`ceil(v - 0.5)`, at least 0) and at or before (`floor(v - 0.5)`, -1 when left of 0),
/// saturated to `i32`. Rounding is monotonic, so a triangle's range of pixel centres is the
/// minimum of its corners' firsts to the maximum of their lasts: the rounding is done
/// once per vertex instead of four times per face, and most faces of a dense scan cover
/// no pixel centre and are rejected on integers alone.
#[derive(Clone, Copy)]
struct PixelSpan {
    first: [i32; 2],
    last: [i32; 2],
}

fn pixel_spans(projected: &[[f32; 3]], parallel: bool) -> Vec<PixelSpan> {
    let mut spans = vec![PixelSpan { first: [0; 2], last: [0; 2] }; projected.len()];
    let fill = |spans: &mut [PixelSpan], projected: &[[f32; 3]]| {
        for (span, p) in spans.iter_mut().zip(projected) {
            let ((first_x, last_x), (first_y, last_y)) = (ceil_and_floor(p[0] - 0.5), ceil_and_floor(p[1] - 0.5));
            (span.first, span.last) = ([first_x, first_y], [last_x, last_y]);
        }
    };
    const CHUNK: usize = 1 << 14;
    if parallel {
        spans.par_chunks_mut(CHUNK).zip(projected.par_chunks(CHUNK)).for_each(|(spans, projected)| fill(spans, projected));
    } else {
        fill(&mut spans, projected);
    }
    spans
}

/// `ceil(u)` clamped to `0..=i32::MAX` and `floor(u)` clamped to `-1..=i32::MAX`, the
/// two from one rounding for the coordinates of an image.
#[inline]
fn ceil_and_floor(u: f32) -> (i32, i32) {
    if u.abs() < 4_194_304.0 {
        let nearest = nearest_small(u);
        let back = nearest as f32;
        ((nearest + (back < u) as i32).max(0), (nearest - (back > u) as i32).max(-1))
    } else {
        let floor = floor_to_i64(u);
        let ceil = if floor as f32 == u { floor } else { floor.saturating_add(1) };
        (ceil.clamp(0, i32::MAX as i64) as i32, floor.clamp(-1, i32::MAX as i64) as i32)
    }
}

/// Rasterizes into the rows `row0 .. row0 + rows` held by `depth` and `face`.
// The one inner loop of the serial and the banded rasterizer: a struct for its arguments
// would only rename them.
#[allow(clippy::too_many_arguments)]
fn rasterize_rows(
    depth: &mut [f32],
    face: &mut [u32],
    width: usize,
    row0: usize,
    rows: usize,
    projected: &[[f32; 3]],
    spans: &[PixelSpan],
    triangles: impl Iterator<Item = (usize, [u32; 3])>,
) {
    let bounds = PixelBounds::new(width, row0, rows);
    for (f, [a, b, c]) in triangles {
        let Some([x0, x1, y0, y1]) = bounds.covered(spans, [a, b, c]) else { continue };
        let (a, b, c) = (projected[a as usize], projected[b as usize], projected[c as usize]);
        let area = edge(a, b, c[0], c[1]);
        if area == 0.0 || !area.is_finite() {
            continue;
        }
        let inverse_area = 1.0 / area;
        // Long thin faces (a fracture face or wall seen edge-on) cover a few pixels of a
        // bounding box of hundreds: their rows are cut to the covered run first.
        let cut_rows = x1 - x0 >= MIN_CUT_ROW && inverse_area.is_finite();
        for y in y0..=y1 {
            let py = y as f32 + 0.5;
            let edges = [EdgeRow::new(b, c, py), EdgeRow::new(c, a, py), EdgeRow::new(a, b, py)];
            let (start, end) = if cut_rows {
                match covered_run(&edges, inverse_area, x0, x1) {
                    Some(run) => run,
                    None => continue,
                }
            } else {
                (x0, x1)
            };
            let line = (y - row0) * width;
            for x in start..=end {
                let px = x as f32 + 0.5;
                let w0 = edges[0].at(px) * inverse_area;
                let w1 = edges[1].at(px) * inverse_area;
                let w2 = edges[2].at(px) * inverse_area;
                if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                    continue;
                }
                let z = w0 * a[2] + w1 * b[2] + w2 * c[2];
                let i = line + x;
                if z < depth[i] {
                    depth[i] = z;
                    face[i] = f as u32;
                }
            }
        }
    }
}

/// Bounding boxes at least this many pixels wider than one are cut row by row to the
/// pixels the face covers; narrower ones test every pixel, which costs less than the cut.
const MIN_CUT_ROW: usize = 4;

/// [`edge`]`(a, b, px, py)` along the pixel row at `py`: the product that does not change
/// along the row computed once, the same operations in the same order.
#[derive(Clone, Copy)]
struct EdgeRow {
    constant: f32,
    slope: f32,
    origin: f32,
}

impl EdgeRow {
    #[inline]
    fn new(a: [f32; 3], b: [f32; 3], py: f32) -> Self {
        EdgeRow { constant: (b[0] - a[0]) * (py - a[1]), slope: b[1] - a[1], origin: a[0] }
    }

    #[inline]
    fn at(&self, px: f32) -> f32 {
        self.constant - self.slope * (px - self.origin)
    }
}

/// The columns `x0..=x1` of a row where no barycentric weight `edges[k].at(x + 0.5) *
/// inverse_area` is negative, the pixels the rasterizer's test keeps; `None` when there is
/// none. Every step of a weight's computation rounds monotonically, so each weight is
/// monotonic along the row and its test passes on a prefix or a suffix of it: each edge's
/// end of the run is guessed from the edge's root and settled with the test itself.
fn covered_run(edges: &[EdgeRow; 3], inverse_area: f32, x0: usize, x1: usize) -> Option<(usize, usize)> {
    let (mut start, mut end) = (x0 as i64, x1 as i64);
    for e in edges {
        let inside = |x: i64| !(e.at(x as f32 + 0.5) * inverse_area < 0.0);
        if e.slope == 0.0 {
            if !inside(start) {
                return None;
            }
            continue;
        }
        // The column whose centre the edge's line crosses, near enough to step from.
        let root = (e.origin as f64 + e.constant as f64 / e.slope as f64 - 0.5) as i64;
        if (e.slope > 0.0) == (inverse_area > 0.0) {
            // Decreasing along the row: the run ends at the last column that passes.
            let mut x = root.clamp(start - 1, end);
            while x < end && inside(x + 1) {
                x += 1;
            }
            while x >= start && !inside(x) {
                x -= 1;
            }
            end = x;
        } else {
            // Increasing: the run starts at the first column that passes.
            let mut x = root.clamp(start, end + 1);
            while x > start && inside(x - 1) {
                x -= 1;
            }
            while x <= end && !inside(x) {
                x += 1;
            }
            start = x;
        }
        if start > end {
            return None;
        }
    }
    Some((start as usize, end as usize))
}

/// The columns and rows a buffer (or band of rows) holds, saturated like [`PixelSpan`]:
/// pixels past column or row `i32::MAX` stay empty (f32 pixel centres stop being
/// distinct long before, at 2^24).
struct PixelBounds {
    last_column: i32,
    first_row: i32,
    last_row: i32,
}

impl PixelBounds {
    fn new(width: usize, row0: usize, rows: usize) -> Self {
        let saturate = |v: usize| v.min(i32::MAX as usize) as i32;
        PixelBounds { last_column: saturate(width - 1), first_row: saturate(row0), last_row: saturate(row0 + rows - 1) }
    }

    /// `[x0, x1, y0, y1]`, the pixel centres (inclusive) in the bounding box of `triangle`
    /// within the bounds; `None` when there is none.
    #[inline]
    fn covered(&self, spans: &[PixelSpan], [a, b, c]: [u32; 3]) -> Option<[usize; 4]> {
        let (a, b, c) = (&spans[a as usize], &spans[b as usize], &spans[c as usize]);
        // A last of -1 (left of or above the image) is below any first.
        let x0 = a.first[0].min(b.first[0]).min(c.first[0]);
        let x1 = a.last[0].max(b.last[0]).max(c.last[0]).min(self.last_column);
        if x0 > x1 {
            return None;
        }
        let y0 = a.first[1].min(b.first[1]).min(c.first[1]).max(self.first_row);
        let y1 = a.last[1].max(b.last[1]).max(c.last[1]).min(self.last_row);
        (y0 <= y1).then_some([x0 as usize, x1 as usize, y0 as usize, y1 as usize])
    }
}

/// `floor(v)` without the libm call `f32::floor` compiles to on baseline x86-64 (no
/// SSE4.1 rounding instruction): the rasterizer and ambient occlusion round millions of
/// coordinates per view. Saturates at the ends of `i64`; NaN gives 0.
#[inline]
pub fn floor_to_i64(v: f32) -> i64 {
    if v.abs() < 4_194_304.0 {
        let nearest = nearest_small(v);
        (nearest - (nearest as f32 > v) as i32) as i64
    } else {
        // Exact for `|v| < 2^23`; larger values are whole already.
        let t = v as i64;
        if (t as f32) > v { t.saturating_sub(1) } else { t }
    }
}

/// `v` rounded to a whole number, for `|v| < 2^22`: adding 1.5 * 2^23 leaves no bits for
/// a fraction, and the sum's low bits are the number.
#[inline]
fn nearest_small(v: f32) -> i32 {
    const MAGIC: f32 = 12_582_912.0;
    (v + MAGIC).to_bits() as i32 - MAGIC.to_bits() as i32
}

/// Twice the signed area of (a, b, p).
#[inline]
fn edge(a: [f32; 3], b: [f32; 3], px: f32, py: f32) -> f32 {
    (b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0])
}

/// Barycentric weights of pixel centre `(x, y)` in the projected triangle `tri`
/// (clamped to the triangle), to interpolate vertex attributes.
pub fn barycentric(projected: &[[f32; 3]], tri: [u32; 3], x: usize, y: usize) -> [f32; 3] {
    let (a, b, c) = (projected[tri[0] as usize], projected[tri[1] as usize], projected[tri[2] as usize]);
    let (px, py) = (x as f32 + 0.5, y as f32 + 0.5);
    let area = edge(a, b, c[0], c[1]);
    if area == 0.0 {
        return [1.0 / 3.0; 3];
    }
    let w = [edge(b, c, px, py) / area, edge(c, a, px, py) / area, edge(a, b, px, py) / area].map(|w| w.max(0.0));
    let sum = w[0] + w[1] + w[2];
    if sum > 0.0 { w.map(|w| w / sum) } else { [1.0 / 3.0; 3] }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The first pixel whose centre (`.5`) is at or right of `v` (clamped at 0): a face's
    /// bounds rounded directly, what [`PixelSpan`] must agree with.
    fn first_pixel(v: f32) -> usize {
        // ceil(v - 0.5) = -floor(0.5 - v)
        floor_to_i64(0.5 - v).saturating_neg().max(0) as usize
    }

    /// The last pixel whose centre is at or left of `v`; `None` when that is left of 0.
    fn last_pixel(v: f32) -> Option<usize> {
        let last = floor_to_i64(v - 0.5);
        (last >= 0).then_some(last as usize)
    }

    fn quad_at(z: f64, half: f64) -> (Vec<Point>, Vec<[u32; 3]>) {
        (
            vec![Point::new(-half, -half, z), Point::new(half, -half, z), Point::new(half, half, z), Point::new(-half, half, z)],
            vec![[0, 1, 2], [0, 2, 3]],
        )
    }

    #[test]
    fn pixel_spans_match_first_and_last_pixel() {
        let values = [
            -1e30f32, -5e6, -4_194_304.5, -3.5, -2.0, -0.7, -0.5, -0.25, -0.0, 0.0, 0.2, 0.5, 0.50001, 1.0, 1.49, 1.5, 7.5,
            2047.5, 4_194_303.5, 4_194_304.0, 1e6 + 0.5, 3e9, 1e30, f32::MIN_POSITIVE, -f32::MIN_POSITIVE,
        ];
        let expected = |u: f32| ((u.ceil() as i64).clamp(0, i32::MAX as i64) as i32, (u.floor() as i64).clamp(-1, i32::MAX as i64) as i32);
        for v in values {
            assert_eq!(ceil_and_floor(v), expected(v), "{v}");
            let span = pixel_spans(&[[v, v, 0.0]], false)[0];
            let first = (first_pixel(v) as i64).min(i32::MAX as i64) as i32;
            let last = last_pixel(v).map_or(-1, |l| (l as i64).min(i32::MAX as i64) as i32);
            assert_eq!((span.first, span.last), ([first; 2], [last; 2]), "span {v}");
        }
        // Whole and half numbers and their neighbours, where rounding would slip.
        for k in -40_000..40_000 {
            let v = k as f32 * 0.25 + if k % 7 == 0 { 1_000_000.0 } else { 0.0 };
            for v in [v, f32::from_bits(v.to_bits() + 1), f32::from_bits(v.to_bits().saturating_sub(1))] {
                assert_eq!(ceil_and_floor(v), expected(v), "{v}");
                assert_eq!(floor_to_i64(v), v.floor() as i64, "{v}");
            }
        }
    }

    /// Every pixel of the bounding box tested, as the rasterizer did before it cut rows.
    fn rasterize_every_pixel(width: usize, height: usize, projected: &[[f32; 3]], triangles: &[[u32; 3]]) -> ZBuffer {
        let mut buffer = ZBuffer::new(width, height);
        for (f, t) in triangles.iter().enumerate() {
            let [a, b, c] = t.map(|v| projected[v as usize]);
            let area = edge(a, b, c[0], c[1]);
            if area == 0.0 || !area.is_finite() {
                continue;
            }
            let x0 = first_pixel(a[0].min(b[0]).min(c[0]));
            let y0 = first_pixel(a[1].min(b[1]).min(c[1]));
            let (Some(x1), Some(y1)) = (last_pixel(a[0].max(b[0]).max(c[0])), last_pixel(a[1].max(b[1]).max(c[1]))) else {
                continue;
            };
            let inverse_area = 1.0 / area;
            for y in y0..=y1.min(height - 1) {
                for x in x0..=x1.min(width - 1) {
                    let (px, py) = (x as f32 + 0.5, y as f32 + 0.5);
                    let w = [edge(b, c, px, py), edge(c, a, px, py), edge(a, b, px, py)].map(|e| e * inverse_area);
                    let z = w[0] * a[2] + w[1] * b[2] + w[2] * c[2];
                    if w.iter().all(|&w| !(w < 0.0)) && z < buffer.depth[y * width + x] {
                        buffer.depth[y * width + x] = z;
                        buffer.face[y * width + x] = f as u32;
                    }
                }
            }
        }
        buffer
    }

    #[test]
    fn cut_rows_cover_what_testing_every_pixel_covers() {
        // Slivers in every direction and size, across pixel centres, partly outside the
        // image, both windings, some degenerate; and a few ordinary faces.
        let (width, height) = (120, 90);
        let mut state = 12345u64;
        let mut random = move || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        let mut projected = Vec::new();
        let mut triangles = Vec::new();
        for i in 0..20_000u32 {
            let a = [random() * 140.0 - 10.0, random() * 110.0 - 10.0, random() * 10.0];
            let length = if i % 3 == 0 { random() * 5.0 } else { random() * 150.0 };
            let angle = random() * std::f32::consts::TAU;
            let thickness = match i % 5 {
                0 => 0.0,
                1 => 1e-4,
                2 => random() * 0.5,
                _ => random() * 20.0,
            };
            let b = [a[0] + length * angle.cos(), a[1] + length * angle.sin(), random() * 10.0];
            let t = random();
            let c = [a[0] + t * (b[0] - a[0]) - thickness * angle.sin(), a[1] + t * (b[1] - a[1]) + thickness * angle.cos(), random() * 10.0];
            let base = projected.len() as u32;
            projected.extend([a, b, c]);
            triangles.push(if i % 2 == 0 { [base, base + 1, base + 2] } else { [base, base + 2, base + 1] });
        }
        // Exact half-pixel coordinates, where the tests tie.
        for i in 0..2_000u32 {
            let [x, y] = [(random() * 100.0).round() + 0.5, (random() * 80.0).round() + 0.5];
            let base = projected.len() as u32;
            projected.extend([[x, y, 1.0], [x + (i % 40) as f32 + 1.0, y + (i % 3) as f32, 2.0], [x + (i % 7) as f32, y + (i % 5) as f32 + 1.0, 0.5]]);
            triangles.push([base, base + 1, base + 2]);
        }
        let reference = rasterize_every_pixel(width, height, &projected, &triangles);
        let mut serial = ZBuffer::new(width, height);
        rasterize_into(&mut serial, &projected, &triangles);
        assert!(serial == reference, "{} pixels differ", serial.face.iter().zip(&reference.face).filter(|(a, b)| a != b).count());
        assert_eq!(rasterize_parallel(width, height, &projected, &triangles), reference);
        assert!(reference.face.iter().filter(|&&f| f != NO_FACE).count() > width * height / 2);
    }

    #[test]
    fn pixel_rounding_matches_floor_and_ceil() {
        for v in [-1e30f32, -3e9, -4_194_304.5, -3.5, -2.0, -0.7, -0.5, 0.0, 0.2, 0.5, 0.50001, 1.0, 1.49, 7.5, 1e6 + 0.5, 4_194_304.0, 3e9] {
            assert_eq!(floor_to_i64(v), v.floor() as i64, "floor {v}");
            assert_eq!(first_pixel(v), (v - 0.5).ceil().max(0.0) as usize, "first {v}");
            let last = (v - 0.5).floor();
            assert_eq!(last_pixel(v), (last >= 0.0).then_some(last as usize), "last {v}");
        }
    }

    #[test]
    fn nearer_square_hides_farther_and_covers_its_area() {
        let (mut positions, mut triangles) = quad_at(0.0, 10.0);
        let (near, near_triangles) = quad_at(5.0, 4.0);
        positions.extend(near);
        triangles.extend(near_triangles.iter().map(|t| t.map(|v| v + 4)));
        // Looking down -z: larger z is nearer.
        let camera = OrthographicCamera::fit(&positions, -Vector::z(), Vector::y(), 0.1, 0);
        assert_eq!((camera.width, camera.height), (201, 201));
        let projected = camera.project_all(&positions);
        let serial = {
            let mut b = ZBuffer::new(camera.width, camera.height);
            rasterize_into(&mut b, &projected, &triangles);
            b
        };
        let parallel = rasterize_parallel(camera.width, camera.height, &projected, &triangles);
        assert_eq!(serial, parallel);
        let near_pixels = parallel.face.iter().filter(|&&f| f >= 2 && f != NO_FACE).count();
        // 8 mm square at 0.1 mm per pixel: 80 x 80 pixel centres.
        assert!((near_pixels as i64 - 6400).abs() <= 170, "{near_pixels}");
        let covered = parallel.face.iter().filter(|&&f| f != NO_FACE).count();
        assert!((covered as i64 - 40000).abs() <= 420, "{covered}");
        // The image's top rows are +y (up_hint) and the near square's depth is smaller.
        let centre = 100 * camera.width + 100;
        assert!(parallel.face[centre] >= 2);
        assert!(parallel.depth[centre] < parallel.depth[5 * camera.width + 5]);
        let top = camera.project(&Point::new(0.0, 10.0, 0.0));
        assert!(top[1] < 1.0);
    }
}
