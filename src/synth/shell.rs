//! Revolving the profile with its wall thickness into a closed triangle mesh.
//!
//! The vessel surface is parametrised by the angle `theta` about the axis and the arc
//! length `s` of the mid-wall curve; a [`ParamGrid`] divides a window of that plane into
//! cells of about equal size in millimetres. A fragment is a set of cells. Its shell is
//! the cells' quads on the outer skin, the same quads on the inner skin (reversed), and a
//! quad across the wall on every edge between a cell of the fragment and one outside it
//! (the fracture faces, or the rim top on the last row). Every grid corner gives one
//! outer and one inner vertex shared by all faces touching it, so the shell is closed
//! and watertight by construction; the cells around the base centre share a single
//! vertex per skin (a fan). Fracture corners are then slid along the break line
//! (Laplacian smoothing in the parameter plane, at most 0.45 cell) so that the break
//! does not follow the grid's staircase: otherwise every fracture face would be aligned
//! with the axis or with the profile, which would flatter axis estimators that use normals.

use rayon::prelude::*;

use super::deform::Deformation;
use super::shape::VesselProfile;
use super::truth::SurfaceKind;
use crate::mesh::Point;

/// A window of the `(theta, s)` plane divided into `columns x rows` cells.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParamGrid {
    /// Angle of the first column's left edge, radians.
    pub theta0: f64,
    /// Angular width of a cell, radians.
    pub dtheta: f64,
    /// Number of cell columns.
    pub columns: usize,
    /// True when the columns go all the way round (the last column's right edge is the
    /// first column's left edge).
    pub periodic: bool,
    /// Arc length of the first row's lower edge, mm.
    pub s0: f64,
    /// Height of a cell along the mid-wall curve, mm.
    pub ds: f64,
    /// Number of cell rows.
    pub rows: usize,
    /// True when the first row starts at the base centre (`s0 == 0`, periodic).
    pub pole: bool,
    /// True when the last row ends at the rim.
    pub rim: bool,
}

impl ParamGrid {
    /// A grid of cells about `cell_mm` wide (at `reference_radius_mm` from the axis) and
    /// high, covering `theta_range` (radians; `None` for the full turn) and `s_range`
    /// (mm, clamped to the profile of length `length_mm`). A window that reaches the base
    /// centre or nearly a full turn becomes the full turn.
    pub fn covering(theta_range: Option<[f64; 2]>, s_range: [f64; 2], length_mm: f64, cell_mm: f64, reference_radius_mm: f64) -> Self {
        let s0 = if s_range[0] <= 1e-9 { 0.0 } else { s_range[0] };
        let s1 = s_range[1].min(length_mm);
        let rows = ((s1 - s0) / cell_mm).ceil().max(1.0) as usize;
        let full_turn = std::f64::consts::TAU;
        let angular_cell = cell_mm / reference_radius_mm.max(cell_mm);
        let (theta0, span, periodic) = match theta_range {
            Some([low, high]) if s0 > 0.0 && high - low < 0.98 * full_turn => (low, high - low, false),
            Some([low, _]) => (low, full_turn, true),
            None => (0.0, full_turn, true),
        };
        let columns = ((span / angular_cell).ceil() as usize).max(if periodic { 12 } else { 3 });
        ParamGrid {
            theta0,
            dtheta: span / columns as f64,
            columns,
            periodic,
            s0,
            ds: (s1 - s0) / rows as f64,
            rows,
            pole: s0 == 0.0 && periodic,
            rim: s1 >= length_mm,
        }
    }

    /// Number of cells.
    pub fn cell_count(&self) -> usize {
        self.columns * self.rows
    }

    /// `(theta, s)` of the centre of cell `(column, row)`.
    pub fn cell_centre(&self, column: usize, row: usize) -> (f64, f64) {
        (self.theta0 + (column as f64 + 0.5) * self.dtheta, self.s0 + (row as f64 + 0.5) * self.ds)
    }

    fn corner_columns(&self) -> usize {
        if self.periodic { self.columns } else { self.columns + 1 }
    }

    /// A key per distinct grid corner: all corners of the first row are the base centre
    /// when the grid starts there, and the last column wraps onto the first when periodic.
    fn corner_key(&self, column: usize, row: usize) -> usize {
        if self.pole && row == 0 {
            return 0;
        }
        let column = if self.periodic { column % self.columns } else { column };
        1 + row * self.corner_columns() + column
    }

    fn corner_key_count(&self) -> usize {
        1 + (self.rows + 1) * self.corner_columns()
    }
}

/// A closed fragment shell in the vessel frame, with what each vertex and face is.
#[derive(Clone, Debug, Default)]
pub struct Shell {
    /// Vertex positions (vessel frame: axis on z, standing plane z = 0), mm.
    pub positions: Vec<Point>,
    /// Outward-oriented triangles.
    pub triangles: Vec<[u32; 3]>,
    /// Outer or inner skin, per vertex.
    pub vertex_kinds: Vec<SurfaceKind>,
    /// Outer skin, inner skin, fracture or rim (top or rounding), per face.
    pub face_kinds: Vec<SurfaceKind>,
    /// Lowest and highest arc length of the fragment's cells, mm.
    pub s_range_mm: [f64; 2],
    /// True when the fragment contains part of the rim top.
    pub has_rim: bool,
}

/// How many Laplacian passes slide the fracture corners off the grid's staircase.
const BREAK_SMOOTHING_PASSES: usize = 6;

/// The closed shell of the cells of `grid` where `mask` is true. `mask` must come from
/// [`super::fracture::clean_mask`] (no pinched corners), or the shell may be non-manifold
/// at a vertex (it is still watertight).
pub fn build_shell(grid: &ParamGrid, mask: &[bool], profile: &VesselProfile, deformation: &Deformation) -> Shell {
    let mut compact = vec![u32::MAX; grid.corner_key_count()];
    let mut corners: Vec<(usize, usize)> = Vec::new();
    let mut vertex_of = |column: usize, row: usize| -> u32 {
        let key = grid.corner_key(column, row);
        if compact[key] == u32::MAX {
            compact[key] = corners.len() as u32;
            let column = if grid.periodic { column % grid.columns } else { column };
            corners.push((column, row));
        }
        compact[key]
    };

    let mut triangles: Vec<[u32; 3]> = Vec::new();
    let mut face_kinds = Vec::new();
    // Fracture edges, counter-clockwise around the fragment in the (theta, s) plane, with
    // their step in grid units (the corner indices wrap, the steps do not).
    let mut break_edges: Vec<(u32, u32, [i8; 2])> = Vec::new();
    let (mut s_low, mut s_high, mut has_rim) = (f64::INFINITY, f64::NEG_INFINITY, false);
    let outer = |v: u32| 2 * v;
    let inner = |v: u32| 2 * v + 1;
    let rim_cap_start = profile.rim_cap_start_s_mm();

    for row in 0..grid.rows {
        for column in 0..grid.columns {
            if !mask[row * grid.columns + column] {
                continue;
            }
            s_low = s_low.min(grid.s0 + row as f64 * grid.ds);
            s_high = s_high.max(grid.s0 + (row + 1) as f64 * grid.ds);
            let a = vertex_of(column, row);
            let b = vertex_of(column + 1, row);
            let c = vertex_of(column + 1, row + 1);
            let d = vertex_of(column, row + 1);
            let fan = grid.pole && row == 0;
            let on_rim_cap = grid.cell_centre(column, row).1 > rim_cap_start;
            let (outer_kind, inner_kind) = if on_rim_cap { (SurfaceKind::Rim, SurfaceKind::Rim) } else { (SurfaceKind::Outer, SurfaceKind::Inner) };
            if !fan {
                triangles.push([outer(a), outer(b), outer(c)]);
                triangles.push([inner(a), inner(c), inner(b)]);
                face_kinds.extend([outer_kind, inner_kind]);
            }
            triangles.push([outer(a), outer(c), outer(d)]);
            triangles.push([inner(a), inner(d), inner(c)]);
            face_kinds.extend([outer_kind, inner_kind]);

            let inside = |c: isize, r: isize| -> bool {
                if r < 0 || r >= grid.rows as isize {
                    return false;
                }
                let c = if grid.periodic {
                    c.rem_euclid(grid.columns as isize)
                } else if c < 0 || c >= grid.columns as isize {
                    return false;
                } else {
                    c
                };
                mask[r as usize * grid.columns + c as usize]
            };
            let (ci, ri) = (column as isize, row as isize);
            // Edges counter-clockwise: bottom a->b, right b->c, top c->d, left d->a.
            let edges = [
                (a, b, [1i8, 0i8], inside(ci, ri - 1), fan),
                (b, c, [0, 1], inside(ci + 1, ri), false),
                (c, d, [-1, 0], inside(ci, ri + 1), false),
                (d, a, [0, -1], inside(ci - 1, ri), false),
            ];
            for (index, &(p, q, step, neighbour_inside, degenerate)) in edges.iter().enumerate() {
                if neighbour_inside || degenerate {
                    continue;
                }
                triangles.push([outer(q), outer(p), inner(p)]);
                triangles.push([outer(q), inner(p), inner(q)]);
                let rim_top = index == 2 && grid.rim && row + 1 == grid.rows;
                let kind = if rim_top { SurfaceKind::Rim } else { SurfaceKind::Fracture };
                face_kinds.extend([kind, kind]);
                if rim_top {
                    has_rim = true;
                } else {
                    break_edges.push((p, q, step));
                }
            }
        }
    }

    let offsets = smooth_break_lines(grid, &corners, &break_edges);
    let mut positions = vec![Point::origin(); 2 * corners.len()];
    positions.par_chunks_mut(2).zip(corners.par_iter().zip(offsets.par_iter())).for_each(|(pair, (&(column, row), offset))| {
        let theta = grid.theta0 + column as f64 * grid.dtheta + offset[0];
        let s = grid.s0 + row as f64 * grid.ds + offset[1];
        for (slot, side) in pair.iter_mut().zip([1.0, -1.0]) {
            let [r, z] = profile.skin_at(s, side);
            *slot = deformation.apply(theta, r, z);
        }
    });
    let vertex_kinds = (0..positions.len()).map(|v| if v % 2 == 0 { SurfaceKind::Outer } else { SurfaceKind::Inner }).collect();
    Shell { positions, triangles, vertex_kinds, face_kinds, s_range_mm: [s_low, s_high], has_rim }
}

/// Offsets `(dtheta, ds)` of every corner from its grid position, sliding fracture corners
/// along the break line. Corners on the rim or at the base centre stay where they are.
fn smooth_break_lines(grid: &ParamGrid, corners: &[(usize, usize)], break_edges: &[(u32, u32, [i8; 2])]) -> Vec<[f64; 2]> {
    let mut offsets = vec![[0.0; 2]; corners.len()];
    let mut next: Vec<Option<(u32, [i8; 2])>> = vec![None; corners.len()];
    let mut previous: Vec<Option<(u32, [i8; 2])>> = vec![None; corners.len()];
    for &(p, q, step) in break_edges {
        next[p as usize] = Some((q, step));
        previous[q as usize] = Some((p, [-step[0], -step[1]]));
    }
    let cell = [grid.dtheta, grid.ds];
    let limit = [0.45 * grid.dtheta, 0.45 * grid.ds];
    let movable: Vec<usize> = (0..corners.len())
        .filter(|&k| {
            let (_, row) = corners[k];
            let fixed = (grid.pole && row == 0) || (grid.rim && row == grid.rows);
            !fixed && next[k].is_some() && previous[k].is_some()
        })
        .collect();
    for _ in 0..BREAK_SMOOTHING_PASSES {
        let updated: Vec<[f64; 2]> = movable
            .iter()
            .map(|&k| {
                let (n, next_step) = next[k].expect("movable corners have a next corner");
                let (p, previous_step) = previous[k].expect("movable corners have a previous corner");
                let mut offset = offsets[k];
                for axis in 0..2 {
                    let towards_next = next_step[axis] as f64 * cell[axis] + offsets[n as usize][axis];
                    let towards_previous = previous_step[axis] as f64 * cell[axis] + offsets[p as usize][axis];
                    let average = 0.5 * (towards_next + towards_previous);
                    offset[axis] = (offset[axis] + 0.5 * (average - offset[axis])).clamp(-limit[axis], limit[axis]);
                }
                offset
            })
            .collect();
        for (&k, offset) in movable.iter().zip(updated) {
            offsets[k] = offset;
        }
    }
    offsets
}
