//! A candidate collapse weighed: where the kept vertex goes and at what cost, and the
//! checks that refuse it (the link condition, faces that would turn over or degenerate).

use super::collapser::{Collapser, CornerIter, Placement, BOUNDARY, FROZEN, PINNED, SEAM};
use crate::mesh::Vector;

/// Why a collapse was refused by [`Collapser::check_faces`].
pub(super) struct Refusal;

impl Collapser {
    /// Where the collapse of `first`/`second` puts the kept vertex and its quadric
    /// cost, a lower bound of the full cost ([`Collapser::check_faces`] may raise it):
    /// candidates are queued with it and checked only when they come out of the queue.
    /// `None` when both endpoints are frozen.
    pub(super) fn place(&self, first: u32, second: u32) -> Option<Placement> {
        let (i, j) = (first as usize, second as usize);
        let (p, q) = (self.positions[i], self.positions[j]);
        let quadric = self.quadrics[i] + self.quadrics[j];
        // Boundary vertices stay on the boundary polyline: a free minimiser of noisy
        // boundary planes can leave it by several times the noise.
        // Seam vertices are placed as boundary ones; chart corners are kept in place.
        let frozen = |v: usize| self.flags[v] & (FROZEN | PINNED) != 0;
        let on_boundary = |v: usize| self.flags[v] & (BOUNDARY | SEAM) != 0;
        let (position, t) = match () {
            _ if frozen(i) && frozen(j) => return None,
            _ if frozen(i) => (p, 0.0),
            _ if frozen(j) => (q, 1.0),
            _ if on_boundary(i) && on_boundary(j) => quadric.minimizer_on_segment(&p, &q),
            _ if on_boundary(i) => (p, 0.0),
            _ if on_boundary(j) => (q, 1.0),
            _ => {
                let optimal = self.optimal_placement.then(|| quadric.minimizer()).flatten();
                match optimal {
                    // A minimiser far from the edge comes from a nearly singular quadric
                    // (noise on a flat patch); the edge's best point is safer there.
                    Some(x) if (x - (p + q) / 2.0).norm_squared() <= (q - p).norm_squared() => {
                        let direction = q - p;
                        let t = ((x - p).dot(&direction) / direction.norm_squared()).clamp(0.0, 1.0);
                        (x, t)
                    }
                    _ => quadric.minimizer_on_segment(&p, &q),
                }
            }
        };
        let error = quadric.error_at(&position);
        Some(Placement { position, t, error, cost: error.max(self.cost_floor) })
    }

    /// Refuses the collapse if a remaining face would degenerate or turn by more than
    /// the limit from its current or input normal, and applies the sliver penalty to
    /// `placement.cost`. Square roots are avoided: this runs for every popped candidate.
    pub(super) fn check_faces(&self, first: u32, second: u32, placement: &mut Placement) -> std::result::Result<(), Refusal> {
        let position = placement.position;
        let cos_limit = self.min_cos_normal_change;
        // dot < cos_limit |u| |v|, given dot and |u|² |v|², without square roots.
        let turned_too_far = |dot: f64, squared_lengths: f64| {
            let bound = cos_limit * cos_limit * squared_lengths;
            if cos_limit >= 0.0 { dot < 0.0 || dot * dot < bound } else { dot < 0.0 && dot * dot > bound }
        };
        let mut worst_squared_quality: f64 = 1.0;
        for (vertex, other) in [(first, second), (second, first)] {
            let moved = self.positions[vertex as usize];
            for corner in self.corners_of(vertex) {
                let triangle = self.triangles[corner as usize / 3];
                if triangle.contains(&other) {
                    continue; // removed by the collapse
                }
                let slot = corner as usize % 3;
                let a = self.positions[triangle[(slot + 1) % 3] as usize];
                let b = self.positions[triangle[(slot + 2) % 3] as usize];
                let before = (a - moved).cross(&(b - moved));
                let after = (a - position).cross(&(b - position));
                let (before_squared, after_squared) = (before.norm_squared(), after.norm_squared());
                let input_normal = Vector::from(self.input_normals[corner as usize / 3].map(f64::from));
                if after_squared <= 1e-24 * before_squared
                    || turned_too_far(before.dot(&after), before_squared * after_squared)
                    || (input_normal != Vector::zeros() && turned_too_far(input_normal.dot(&after), after_squared))
                {
                    return Err(Refusal);
                }
                if self.quality_threshold.is_some() {
                    let squared_edges = (a - position).norm_squared() + (b - position).norm_squared() + (b - a).norm_squared();
                    // (4√3 area / Σ edge²)² with area = |after| / 2.
                    worst_squared_quality = worst_squared_quality.min(12.0 * after_squared / (squared_edges * squared_edges));
                }
            }
        }
        let worst_quality = worst_squared_quality.sqrt();
        if let Some(threshold) = self.quality_threshold
            && worst_quality < threshold
        {
            placement.cost *= threshold / worst_quality.max(1e-6);
        }
        Ok(())
    }

    /// The link condition (Dey et al. 1999): the vertices adjacent to both endpoints
    /// are exactly the opposite corners of the edge's faces; plus no interior edge
    /// between two boundary vertices (it would pinch the surface), and no vertex left
    /// with too few neighbours (a tetrahedron or a lone triangle would degenerate).
    pub(super) fn topology_allows(&mut self, first: u32, second: u32) -> bool {
        let shared_faces = self.edge_face_count(first, second);
        if shared_faces == 0 || shared_faces > 2 {
            return false;
        }
        let both_on_boundary = self.flags[first as usize] & self.flags[second as usize] & BOUNDARY != 0;
        if shared_faces == 2 && both_on_boundary {
            return false;
        }
        let around_first = self.fresh_mark();
        let counted = self.fresh_mark();
        let mut first_degree = 0;
        let corners = CornerIter { next_corner: &self.next_corner, current: self.first_corner[first as usize] };
        for corner in corners {
            let triangle = self.triangles[corner as usize / 3];
            for v in triangle {
                if v != first && self.marks[v as usize] != around_first {
                    self.marks[v as usize] = around_first;
                    first_degree += 1;
                }
            }
        }
        let (mut common, mut second_degree) = (0, 0);
        let corners = CornerIter { next_corner: &self.next_corner, current: self.first_corner[second as usize] };
        for corner in corners {
            for v in self.triangles[corner as usize / 3] {
                if v == second || self.marks[v as usize] == counted {
                    continue;
                }
                if self.marks[v as usize] == around_first {
                    common += 1;
                }
                if v != first {
                    second_degree += 1;
                }
                self.marks[v as usize] = counted;
            }
        }
        if common != shared_faces {
            return false;
        }
        // Neighbours of the merged vertex: both sets minus each other, shared once.
        let merged_degree = (first_degree - 1) + second_degree - common;
        let on_boundary = (self.flags[first as usize] | self.flags[second as usize]) & BOUNDARY != 0;
        merged_degree >= if on_boundary { 2 } else { 3 }
    }
}
