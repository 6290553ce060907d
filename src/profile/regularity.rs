//! Vessel regularity (Wilczek et al. 2018, section 2.4.4): per-vertex distances that
//! reveal decoration, technological traces and orientation errors, and the colour map
//! (with its legend) that paints them on the model.
//!
//! * [`distance_to_axis`]: the radius of every vertex (Fig. 7:a): a well-oriented, regular
//!   vessel has one colour per horizontal band.
//! * [`distance_to_ideal_vessel`]: the distance to the surface made by revolving one
//!   profile (Fig. 7:b): a regular vessel is uniformly close to 0. For a surface of
//!   revolution this is the distance, in each vertex's own rz half-plane, to the profile.

use rayon::prelude::*;

use crate::mesh::Mesh;
use crate::orient::Axis;
use crate::profile::section::{oriented_positions, polygon_signed_area, ProfileSection};
use crate::statistics::central_range;
use crate::{Error, Result};

/// Distance of every vertex to the axis, in millimetres.
pub fn distance_to_axis(mesh: &Mesh, axis: &Axis) -> Vec<f32> {
    mesh.positions.par_iter().map(|p| axis.distance_to(p) as f32).collect()
}

/// Signed distance in millimetres of every vertex to the ideal vessel obtained by
/// revolving `section` (computed by [`crate::profile::section::profile_section`] on the
/// same mesh and axis): positive where the surface stands out of the ideal wall (added
/// material, a bulge), negative where it lies inside it (a groove). Errors when the
/// section has no closed outline.
pub fn distance_to_ideal_vessel(mesh: &Mesh, axis: &Axis, section: &ProfileSection) -> Result<Vec<f32>> {
    let mut segments = Vec::new();
    for mut outline in section.closed_outlines() {
        // Counter-clockwise outlines put the outside on the right of each segment.
        if polygon_signed_area(&outline) < 0.0 {
            outline.reverse();
        }
        for i in 0..outline.len() {
            segments.push([outline[i], outline[(i + 1) % outline.len()]]);
        }
    }
    if segments.is_empty() {
        return Err(Error::DegenerateGeometry(format!(
            "the section at {:.1} deg has no closed outline: no ideal vessel to compare with",
            section.angle_rad.to_degrees()
        )));
    }
    let grid = SegmentGrid::new(segments);
    let oriented = oriented_positions(mesh, axis);
    // sqrt, not hypot: a libm call per vertex and per candidate segment was a tenth of
    // the drawing's time; coordinates in millimetres cannot overflow when squared.
    Ok(oriented.par_iter().map(|p| grid.signed_distance([(p.x * p.x + p.y * p.y).sqrt(), p.z]) as f32).collect())
}

/// Segments bucketed in a uniform grid for nearest-segment queries.
struct SegmentGrid {
    segments: Vec<[[f64; 2]; 2]>,
    origin: [f64; 2],
    cell_mm: f64,
    columns: usize,
    rows: usize,
    cells: Vec<Vec<u32>>,
    /// The cells each segment is listed in: first and last column, first and last row.
    cell_ranges: Vec<[i64; 4]>,
}

impl SegmentGrid {
    fn new(segments: Vec<[[f64; 2]; 2]>) -> Self {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for s in &segments {
            for p in s {
                for k in 0..2 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
        }
        let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-6);
        let cell_mm = extent / 64.0;
        let columns = ((hi[0] - lo[0]) / cell_mm) as usize + 1;
        let rows = ((hi[1] - lo[1]) / cell_mm) as usize + 1;
        let mut cells = vec![Vec::new(); columns * rows];
        let mut cell_ranges = Vec::with_capacity(segments.len());
        for (i, s) in segments.iter().enumerate() {
            let c0 = ((s[0][0].min(s[1][0]) - lo[0]) / cell_mm) as usize;
            let c1 = (((s[0][0].max(s[1][0]) - lo[0]) / cell_mm) as usize).min(columns - 1);
            let r0 = ((s[0][1].min(s[1][1]) - lo[1]) / cell_mm) as usize;
            let r1 = (((s[0][1].max(s[1][1]) - lo[1]) / cell_mm) as usize).min(rows - 1);
            cell_ranges.push([c0, c1, r0, r1].map(|v| v as i64));
            for r in r0..=r1 {
                for c in c0..=c1 {
                    cells[r * columns + c].push(i as u32);
                }
            }
        }
        SegmentGrid { segments, origin: lo, cell_mm, columns, rows, cells, cell_ranges }
    }

    /// Distance to the nearest segment, signed by which side of it `p` lies on.
    fn signed_distance(&self, p: [f64; 2]) -> f64 {
        // A point outside the grid starts from the grid's nearest cell: rings grown from
        // there still bound the distance (p lies beyond that cell on the clamped axes),
        // and their count is the grid's size, not the point's distance in cells (which
        // for a tiny outline and a far vertex was billions: the pipeline fuzz target's
        // hang, fuzz/regressions/pipeline/).
        let (x, y) = ((p[0] - self.origin[0]) / self.cell_mm, (p[1] - self.origin[1]) / self.cell_mm);
        let column = (x.floor() as i64).clamp(0, self.columns as i64 - 1);
        let row = (y.floor() as i64).clamp(0, self.rows as i64 - 1);
        // How far p lies inside its own cell (0 outside the grid): the cells of ring k lie
        // at least (k - 1) cells and this inset away.
        let inset_mm =
            (x - column as f64).min(column as f64 + 1.0 - x).min(y - row as f64).min(row as f64 + 1.0 - y).max(0.0) * self.cell_mm;
        let (mut best, mut best_side) = (f64::INFINITY, 0.0);
        // `inner`: the rings already visited, when this ring's own segments are too far to
        // change the best (see below).
        let visit = |c: i64, r: i64, inner: Option<i64>, best: &mut f64, best_side: &mut f64| {
            if c < 0 || r < 0 || c >= self.columns as i64 || r >= self.rows as i64 {
                return;
            }
            for &s in &self.cells[r as usize * self.columns + c as usize] {
                if let Some(inner) = inner {
                    let [c0, c1, r0, r1] = self.cell_ranges[s as usize];
                    if c0 > column + inner || c1 < column - inner || r0 > row + inner || r1 < row - inner {
                        continue;
                    }
                }
                let [a, b] = self.segments[s as usize];
                let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                let length2 = dx * dx + dy * dy;
                let t = if length2 > 0.0 { (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length2).clamp(0.0, 1.0) } else { 0.0 };
                let (qx, qy) = (a[0] + t * dx - p[0], a[1] + t * dy - p[1]);
                let d = (qx * qx + qy * qy).sqrt();
                // Ties (a shared vertex) are broken towards the segment facing p most.
                let side = dx * (p[1] - a[1]) - dy * (p[0] - a[0]);
                let side = -side / length2.sqrt().max(1e-300);
                if d < *best - 1e-12 || (d < *best + 1e-12 && side.abs() > best_side.abs()) {
                    *best = d;
                    *best_side = side;
                }
            }
        };
        // Grow square rings of cells until no unvisited cell can hold a nearer segment.
        let max_ring = self.columns.max(self.rows) as i64;
        for ring in 0..=max_ring {
            if ring > 0 && (ring - 1) as f64 * self.cell_mm > best {
                break;
            }
            // A segment listed in no inner ring lies wholly in this ring or beyond, farther
            // than the best plus the tie margin (with room for rounding): it cannot change
            // the best, and only the inner rings' segments listed here again are measured,
            // as the search always did, so that the ties go as they did.
            let far = ring > 0 && (ring - 1) as f64 * self.cell_mm + inset_mm > best + 1e-12 + 1e-9;
            let inner = far.then_some(ring - 1);
            for c in column - ring..=column + ring {
                for r in row - ring..=row + ring {
                    if (c - column).abs() == ring || (r - row).abs() == ring {
                        visit(c, r, inner, &mut best, &mut best_side);
                    }
                }
            }
        }
        if best_side >= 0.0 { best } else { -best }
    }
}

/// A colour scale for per-vertex values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum ColorScale {
    /// Blue (low) through cyan, green, yellow to red (high), as the paper's Fig. 7.
    Rainbow,
    /// Blue (negative) through white (0) to red (positive).
    Diverging,
}

impl ColorScale {
    /// The colour of `t` in `[0, 1]` (clamped).
    pub fn color(self, t: f64) -> [u8; 3] {
        let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 0.0 };
        let stops: &[[f64; 3]] = match self {
            ColorScale::Rainbow => &[[0.0, 0.0, 0.8], [0.0, 0.7, 1.0], [0.1, 0.8, 0.2], [1.0, 0.9, 0.0], [0.85, 0.0, 0.0]],
            ColorScale::Diverging => &[[0.1, 0.2, 0.75], [1.0, 1.0, 1.0], [0.8, 0.1, 0.1]],
        };
        let x = t * (stops.len() - 1) as f64;
        let i = (x.floor() as usize).min(stops.len() - 2);
        let f = x - i as f64;
        let mix = |k: usize| ((stops[i][k] * (1.0 - f) + stops[i + 1][k] * f) * 255.0).round() as u8;
        [mix(0), mix(1), mix(2)]
    }
}

/// How values map to colours, and what the legend says.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ColorMap {
    /// The scale.
    pub scale: ColorScale,
    /// Value shown at the low end (and below), in `unit`.
    pub low: f64,
    /// Value shown at the high end (and above).
    pub high: f64,
    /// The legend's title, e.g. "distance to axis".
    pub title: String,
    /// Unit of the values, e.g. "mm".
    pub unit: String,
}

impl ColorMap {
    /// A map spanning the 2nd to 98th percentile of `values` (robust to a few outliers);
    /// a diverging map is made symmetric about 0.
    pub fn fitted(values: &[f32], scale: ColorScale, title: &str, unit: &str) -> Self {
        let (low, high) = central_range(values.iter().copied()).unwrap_or((0.0, 1.0));
        let (mut low, mut high) = (low as f64, high as f64);
        if scale == ColorScale::Diverging {
            let m = low.abs().max(high.abs());
            (low, high) = (-m, m);
        }
        if high - low < 1e-9 {
            high = low + 1e-3;
        }
        ColorMap { scale, low, high, title: title.into(), unit: unit.into() }
    }

    /// The colour of one value.
    pub fn color(&self, value: f64) -> [u8; 3] {
        self.scale.color((value - self.low) / (self.high - self.low))
    }

    /// Opaque RGBA colours of `values`, one per value.
    pub fn rgba(&self, values: &[f32]) -> Vec<[u8; 4]> {
        values
            .iter()
            .map(|&v| {
                let [r, g, b] = self.color(v as f64);
                [r, g, b, 255]
            })
            .collect()
    }

    /// Legend ticks: `count` evenly spaced `(value, colour)` pairs from low to high.
    pub fn legend(&self, count: usize) -> Vec<(f64, [u8; 3])> {
        let count = count.max(2);
        (0..count)
            .map(|i| {
                let value = self.low + (self.high - self.low) * i as f64 / (count - 1) as f64;
                (value, self.color(value))
            })
            .collect()
    }
}

/// The distance-to-axis map (Fig. 7:a) with its colours: radii on the rainbow scale
/// fitted to them.
pub fn axis_distance_map(mesh: &Mesh, axis: &Axis) -> (Vec<f32>, ColorMap) {
    let values = distance_to_axis(mesh, axis);
    let map = ColorMap::fitted(&values, ColorScale::Rainbow, "distance to axis", "mm");
    (values, map)
}

/// The ideal-vessel map (Fig. 7:b) as exports show it: the signed distances of
/// [`distance_to_ideal_vessel`] on a diverging scale symmetric about 0 (blue where the
/// surface lies inside the ideal wall, white on it, red where it stands out).
pub fn ideal_vessel_map(mesh: &Mesh, axis: &Axis, section: &ProfileSection) -> Result<(Vec<f32>, ColorMap)> {
    let values = distance_to_ideal_vessel(mesh, axis, section)?;
    let map = ColorMap::fitted(&values, ColorScale::Diverging, "distance to the ideal vessel", "mm");
    Ok((values, map))
}

/// A copy of `mesh` carrying `values` as per-vertex quality and their colours under `map`
/// as vertex colours, for PLY export and MeshLab.
pub fn regularity_mesh(mesh: &Mesh, values: &[f32], map: &ColorMap) -> Result<Mesh> {
    if values.len() != mesh.vertex_count() {
        return Err(Error::InvalidArgument(format!(
            "{} regularity values for {} vertices",
            values.len(),
            mesh.vertex_count()
        )));
    }
    let mut out = mesh.clone();
    out.quality = Some(values.to_vec());
    out.colors = Some(map.rgba(values));
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Point, Vector};
    use crate::profile::revolve::revolve_profile;
    use crate::profile::section::{profile_section, ProfileCurve};

    fn ring() -> Mesh {
        let section = ProfileSection {
            angle_rad: 0.0,
            curves: vec![ProfileCurve { points: vec![[50.0, 0.0], [55.0, 0.0], [55.0, 40.0], [50.0, 40.0]], closed: true }],
        };
        revolve_profile(&section, 90).unwrap()
    }

    #[test]
    fn radius_is_constant_on_a_ring_wall() {
        let mesh = ring();
        let axis = Axis::new(Point::new(0.0, 0.0, -3.0), Vector::z());
        let d = distance_to_axis(&mesh, &axis);
        assert!(d.iter().all(|&r| (r - 50.0).abs() < 1e-4 || (r - 55.0).abs() < 1e-4));
    }

    #[test]
    fn ideal_vessel_distance_is_zero_for_a_regular_vessel_and_shows_a_bump() {
        let mut mesh = ring();
        let axis = Axis::z();
        let section = profile_section(&mesh, &axis, 0.01);
        let regular = distance_to_ideal_vessel(&mesh, &axis, &section).unwrap();
        // Cut between rings, the section sees chords: at most r (1 - cos(2 deg)).
        let chord = 55.0 * (1.0 - (std::f64::consts::PI / 90.0).cos());
        assert!(regular.iter().all(|d| (d.abs() as f64) <= chord + 1e-4), "max {:?}", regular.iter().fold(0f32, |m, d| m.max(d.abs())));
        // Push one outer vertex out by 2 mm and one in by 1 mm, away from the cut.
        let far = mesh.positions.iter().position(|p| p.x < -54.0 && (p.z - 40.0).abs() < 1e-9).unwrap();
        mesh.positions[far].x -= 2.0;
        let dent = mesh.positions.iter().position(|p| p.y < -54.0 && (p.z - 40.0).abs() < 1e-9).unwrap();
        mesh.positions[dent].y += 1.0; // 1 mm in from the corner both ways
        mesh.positions[dent].z -= 1.0;
        let bumped = distance_to_ideal_vessel(&mesh, &axis, &section).unwrap();
        assert!((bumped[far] - 2.0).abs() < 0.05, "bulge {}", bumped[far]);
        assert!((bumped[dent] + 1.0).abs() < 0.05, "groove {}", bumped[dent]);
    }

    /// [`SegmentGrid::signed_distance`] measuring every segment of every ring it visits.
    fn signed_distance_every_ring(grid: &SegmentGrid, p: [f64; 2]) -> f64 {
        let column = (((p[0] - grid.origin[0]) / grid.cell_mm).floor() as i64).clamp(0, grid.columns as i64 - 1);
        let row = (((p[1] - grid.origin[1]) / grid.cell_mm).floor() as i64).clamp(0, grid.rows as i64 - 1);
        let (mut best, mut best_side) = (f64::INFINITY, 0.0f64);
        for ring in 0..=grid.columns.max(grid.rows) as i64 {
            if ring > 0 && (ring - 1) as f64 * grid.cell_mm > best {
                break;
            }
            for c in column - ring..=column + ring {
                for r in row - ring..=row + ring {
                    let on_ring = (c - column).abs() == ring || (r - row).abs() == ring;
                    if !on_ring || c < 0 || r < 0 || c >= grid.columns as i64 || r >= grid.rows as i64 {
                        continue;
                    }
                    for &s in &grid.cells[r as usize * grid.columns + c as usize] {
                        let [a, b] = grid.segments[s as usize];
                        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                        let length2 = dx * dx + dy * dy;
                        let t = if length2 > 0.0 { (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length2).clamp(0.0, 1.0) } else { 0.0 };
                        let (qx, qy) = (a[0] + t * dx - p[0], a[1] + t * dy - p[1]);
                        let d = (qx * qx + qy * qy).sqrt();
                        let side = -(dx * (p[1] - a[1]) - dy * (p[0] - a[0])) / length2.sqrt().max(1e-300);
                        if d < best - 1e-12 || (d < best + 1e-12 && side.abs() > best_side.abs()) {
                            (best, best_side) = (d, side);
                        }
                    }
                }
            }
        }
        if best_side >= 0.0 { best } else { -best }
    }

    #[test]
    fn skipping_far_segments_changes_no_distance() {
        // A wavy closed outline of long and short segments (some spanning many cells),
        // points on it, at its vertices, near it, inside, and far outside the grid.
        let outline: Vec<[f64; 2]> = (0..400)
            .map(|i| {
                let t = i as f64 / 400.0 * std::f64::consts::TAU;
                let r = 30.0 + 3.0 * (7.0 * t).sin() + if i % 50 < 3 { 8.0 } else { 0.0 };
                [r * t.cos(), 0.5 * r * t.sin()]
            })
            .collect();
        let segments: Vec<[[f64; 2]; 2]> = (0..outline.len()).map(|i| [outline[i], outline[(i + 1) % outline.len()]]).collect();
        let grid = SegmentGrid::new(segments);
        let mut state = 99u64;
        let mut random = move || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut points: Vec<[f64; 2]> = outline.clone();
        points.extend(outline.windows(2).map(|w| [(w[0][0] + w[1][0]) / 2.0, (w[0][1] + w[1][1]) / 2.0]));
        for _ in 0..20_000 {
            points.push([random() * 90.0 - 45.0, random() * 50.0 - 25.0]);
        }
        for _ in 0..200 {
            points.push([random() * 4000.0 - 2000.0, random() * 4000.0 - 2000.0]);
        }
        for p in points {
            assert_eq!(grid.signed_distance(p).to_bits(), signed_distance_every_ring(&grid, p).to_bits(), "{p:?}");
        }
    }

    #[test]
    fn colour_map_and_legend() {
        let values: Vec<f32> = (0..=100).map(|i| i as f32).collect();
        let map = ColorMap::fitted(&values, ColorScale::Rainbow, "distance to axis", "mm");
        assert!((map.low - 2.0).abs() < 1e-9 && (map.high - 98.0).abs() < 1e-9);
        assert_eq!(map.color(-5.0), ColorScale::Rainbow.color(0.0));
        let blue = map.color(map.low);
        assert!(blue[2] > blue[0] && blue[2] > blue[1]);
        let red = map.color(map.high);
        assert!(red[0] > red[2]);
        assert_eq!(map.legend(5).len(), 5);
        let diverging = ColorMap::fitted(&[-1.0, 3.0], ColorScale::Diverging, "d", "mm");
        assert_eq!(diverging.low, -diverging.high);
        assert_eq!(diverging.color(0.0), [255, 255, 255]);
        let mesh = ring();
        assert!(regularity_mesh(&mesh, &values, &map).is_err());
        let colored = regularity_mesh(&mesh, &vec![10.0; mesh.vertex_count()], &map).unwrap();
        assert_eq!(colored.colors.unwrap().len(), mesh.vertex_count());
    }
}
