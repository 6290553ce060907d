//! Texture seams: the vertices on them, the boundary's treatment of seam edges, and the
//! new texture coordinates of a collapse's corners, which may not drag a chart across a seam.

use super::barycentric::{barycentric, clamped_to_triangle, least};
use super::collapser::{Collapser, Placement, FROZEN, PINNED, SEAM};
use super::options::BoundaryPolicy;

impl Collapser {
    /// Flags the vertices with two or more distinct UVs (seams) and three or more
    /// (chart corners), and gives each seam edge (two faces that disagree on its UVs) the
    /// boundary's treatment: a perpendicular plane quadric, or frozen vertices with
    /// [`BoundaryPolicy::Fixed`].
    pub(super) fn mark_texture_seams(&mut self, boundary: BoundaryPolicy) {
        let Some(uvs) = self.uvs.take() else { return };
        for vertex in 0..self.positions.len() {
            // Distinct UVs among the vertex's corners, counted up to three.
            let mut seen = [[0.0f32; 2]; 2];
            let mut count = 0;
            for corner in self.corners_of(vertex as u32) {
                let uv = uvs[corner as usize];
                if !seen[..count].contains(&uv) {
                    if count == 2 {
                        count = 3;
                        break;
                    }
                    seen[count] = uv;
                    count += 1;
                }
            }
            if count >= 2 {
                self.flags[vertex] |= SEAM;
                self.report.seam_vertices += 1;
            }
            if count >= 3 {
                self.flags[vertex] |= PINNED;
            }
        }
        for face in 0..self.triangles.len() {
            for slot in 0..3 {
                let (a, b) = (self.triangles[face][slot], self.triangles[face][(slot + 1) % 3]);
                if self.flags[a as usize] & self.flags[b as usize] & SEAM == 0 {
                    continue;
                }
                // Each seam edge once: from the face whose corner of `a` has the lower index.
                let own = (3 * face + slot) as u32;
                let across = self.corners_of(a).find(|&c| {
                    let other = c as usize / 3;
                    other != face && self.triangles[other].contains(&b)
                });
                let Some(across) = across.filter(|&c| c > own) else { continue };
                let other_face = across as usize / 3;
                let b_slot = |f: usize| (0..3).find(|&s| self.triangles[f][s] == b).expect("the edge's face holds b");
                let same_chart = uvs[own as usize] == uvs[across as usize]
                    && uvs[3 * face + b_slot(face)] == uvs[3 * other_face + b_slot(other_face)];
                if same_chart {
                    continue;
                }
                match boundary {
                    BoundaryPolicy::Fixed => {
                        self.flags[a as usize] |= FROZEN;
                        self.flags[b as usize] |= FROZEN;
                    }
                    BoundaryPolicy::Weighted { .. } => self.add_boundary_quadric(a.min(b), a.max(b), boundary),
                }
            }
        }
        self.report.frozen_vertices = self.flags.iter().filter(|&&f| f & FROZEN != 0).count();
        self.uvs = Some(uvs);
    }

    /// Plans the new UVs of the corners around the collapse of `first`/`second` into
    /// `uv_updates`; false when a moving vertex has a corner in a texture chart the
    /// edge's faces do not reach (the collapse would cross a seam). A vertex that stays
    /// where it is keeps its corners' UVs.
    ///
    /// In each chart the merged vertex takes the UV of the placement's barycentric
    /// coordinates in the edge's face of that chart (the face it falls most inside of):
    /// on the edge this is the interpolation along it, and an optimal placement beside
    /// the edge gets the UV of where it lies beside it.
    pub(super) fn plan_texture_coordinates(&mut self, first: u32, second: u32, placement: &Placement) -> bool {
        let Some(uvs) = &self.uvs else { return true };
        let mut updates = std::mem::take(&mut self.uv_updates);
        updates.clear();
        // Per face of the edge: the endpoints' UVs in its chart, the placement's UV
        // there, and how far inside the face the placement falls (its least barycentric
        // coordinate).
        let mut charts = [EdgeChart::default(); 2];
        let mut chart_count = 0;
        for corner in self.corners_of(first) {
            let face = corner as usize / 3;
            let triangle = self.triangles[face];
            if !triangle.contains(&second) || chart_count == 2 {
                continue;
            }
            let [a, b, c] = triangle.map(|v| self.positions[v as usize]);
            let weights = barycentric(&placement.position, &a, &b, &c);
            let inside = least(&weights);
            let weights = clamped_to_triangle(weights);
            let slot_of = |v: u32| 3 * face + triangle.iter().position(|&w| w == v).expect("the face holds v");
            charts[chart_count] = EdgeChart {
                at_first: uvs[slot_of(first)],
                at_second: uvs[slot_of(second)],
                at_placement: std::array::from_fn(|k| {
                    (0..3).map(|s| weights[s] * f64::from(uvs[3 * face + s][k])).sum::<f64>() as f32
                }),
                inside,
            };
            chart_count += 1;
        }
        for (vertex, other, is_first) in [(first, second, true), (second, first, false)] {
            if self.positions[vertex as usize] == placement.position {
                continue;
            }
            for corner in self.corners_of(vertex) {
                if self.triangles[corner as usize / 3].contains(&other) {
                    continue; // the face goes with the edge
                }
                let uv = uvs[corner as usize];
                let mut best: Option<&EdgeChart> = None;
                for chart in charts[..chart_count].iter().filter(|c| uv == if is_first { c.at_first } else { c.at_second }) {
                    let other_uv = |c: &EdgeChart| if is_first { c.at_second } else { c.at_first };
                    match best {
                        // One wedge of this vertex faces two charts of the other: a seam
                        // ends here, and no single UV is right.
                        Some(earlier) if other_uv(earlier) != other_uv(chart) => return false,
                        Some(earlier) if earlier.inside >= chart.inside => {}
                        _ => best = Some(chart),
                    }
                }
                match best {
                    Some(chart) => updates.push((corner, chart.at_placement)),
                    None => return false,
                }
            }
        }
        self.uv_updates = updates;
        true
    }
}

/// One face of a collapsing edge, seen from the texture: see
/// [`Collapser::plan_texture_coordinates`].
#[derive(Clone, Copy, Default)]
struct EdgeChart {
    at_first: [f32; 2],
    at_second: [f32; 2],
    at_placement: [f32; 2],
    inside: f64,
}
