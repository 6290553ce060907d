//! Vertex normals freed of a scan's roughness, as far as their own scatter calls for.
//!
//! A vertex normal from its faces tilts with every bump of the surface: a roughness of
//! `sigma` between vertices `spacing` apart tilts it by about `sigma / spacing` radians
//! (0.25 mm on a 1 mm mesh: about 14 degrees), and the axis is read off those normals.
//! Averaging each normal with its neighbours' (those whose normal turns little from it,
//! so that the skins, the lip and the breaks keep their edges), pass after pass, brings
//! the tilt down. How many passes run follows from how far the normals scatter about
//! their neighbours' mean on the mesh itself ([`normal_scatter`]): a smooth scan keeps
//! its normals as they are.

use super::topology::Topology;
use super::{Mesh, Vector};
use crate::statistics::upper_median;

/// Vertex normals as [`freed_of_roughness`] leaves them.
pub struct FilteredNormals {
    /// The vertex normals, filtered where they scattered more than [`TARGET_NORMAL_SCATTER`].
    pub normals: Vec<Vector>,
    /// The passes of [`filter_normals`] run: 0 where the normals were kept as they were.
    pub passes: usize,
}

/// `normals` (one per vertex of `mesh`, unit or zero) filtered as far as their scatter
/// calls for ([`passes_for_scatter`]), each vertex weighted by `weights` (its area,
/// [`crate::mesh::normals::vertex_areas`]).
pub fn freed_of_roughness(mesh: &Mesh, normals: Vec<Vector>, weights: &[f64]) -> FilteredNormals {
    let neighbours = VertexNeighbours::of(mesh);
    let passes = passes_for_scatter(normal_scatter(&normals, weights, &neighbours).unwrap_or(0.0));
    let normals = if passes > 0 { filter_normals(&normals, weights, &neighbours, passes) } else { normals };
    FilteredNormals { normals, passes }
}

/// Each vertex's neighbours across an edge, as offsets into one list.
pub struct VertexNeighbours {
    offsets: Vec<usize>,
    neighbours: Vec<u32>,
}

impl VertexNeighbours {
    /// The neighbours of every vertex of `mesh` across its edges.
    pub fn of(mesh: &Mesh) -> Self {
        let topology = Topology::new(mesh);
        let mut counts = vec![0usize; mesh.vertex_count() + 1];
        for [a, b] in topology.edges() {
            counts[*a as usize + 1] += 1;
            counts[*b as usize + 1] += 1;
        }
        for v in 0..mesh.vertex_count() {
            counts[v + 1] += counts[v];
        }
        let offsets = counts;
        let mut filled = offsets.clone();
        let mut neighbours = vec![0u32; offsets[mesh.vertex_count()]];
        for [a, b] in topology.edges() {
            neighbours[filled[*a as usize]] = *b;
            filled[*a as usize] += 1;
            neighbours[filled[*b as usize]] = *a;
            filled[*b as usize] += 1;
        }
        VertexNeighbours { offsets, neighbours }
    }

    /// The neighbours of vertex `v`.
    pub fn of_vertex(&self, v: usize) -> &[u32] {
        &self.neighbours[self.offsets[v]..self.offsets[v + 1]]
    }
}

/// How far the normals turn from their neighbours' mean, radians: the median over the
/// vertices within a smooth patch of the angle between a vertex's normal and the weighted
/// mean of its neighbours'. On a smooth surface the neighbours
/// turn evenly about the vertex and their mean is its own normal; a rough surface's
/// normals scatter about it. `None` without vertices that have neighbours.
pub fn normal_scatter(normals: &[Vector], weights: &[f64], neighbours: &VertexNeighbours) -> Option<f64> {
    let angles: Vec<f64> = (0..normals.len())
        .filter_map(|v| {
            let own = normals[v];
            if !within_a_smooth_patch(normals, neighbours, v) {
                return None;
            }
            let mean = agreeing_neighbours_sum(normals, weights, neighbours, v).try_normalize(0.0)?;
            Some(own.dot(&mean).clamp(-1.0, 1.0).acos())
        })
        .collect();
    if angles.is_empty() {
        return None;
    }
    Some(upper_median(&angles))
}

/// The scatter of the normals ([`normal_scatter`]) the filter brings them down to, radians
/// (a little over a degree): what smooth scans and smoothed working copies show.
pub const TARGET_NORMAL_SCATTER: f64 = 0.02;

/// The passes of [`filter_normals`] that bring normals scattered by `scatter` radians down
/// to [`TARGET_NORMAL_SCATTER`]: each pass divides their error by about one more (measured
/// on rough synthetic cylinders and sherds: 3.5 after two passes, 10 after eight), at most
/// [`MAX_FILTER_PASSES`].
pub fn passes_for_scatter(scatter: f64) -> usize {
    if !(scatter > TARGET_NORMAL_SCATTER) {
        return 0;
    }
    ((scatter / TARGET_NORMAL_SCATTER - 1.0).ceil() as usize).min(MAX_FILTER_PASSES)
}

/// The most passes of [`filter_normals`]: past a dozen rings, the average reaches across a
/// carination or a short wall.
pub const MAX_FILTER_PASSES: usize = 12;

/// A neighbour's normal joins a vertex's average only while it turns from the vertex's by
/// less than this (cosine of 30 degrees): across the edge between a skin and a break, or
/// round a lip, normals turn by more and stay apart.
const MIN_NEIGHBOUR_COSINE: f64 = 0.866;

/// True when `v` has a normal and neighbours, and every neighbour's normal turns by less
/// than 30 degrees from its own: the measures of roughness leave out the vertices on an
/// edge between a skin and a break or round a lip, where the surface's own shape turns
/// the normals (on a coarse mesh, a large share of its vertices).
fn within_a_smooth_patch(normals: &[Vector], neighbours: &VertexNeighbours, v: usize) -> bool {
    let own = normals[v];
    let around = neighbours.of_vertex(v);
    own.norm_squared() > 0.5 && !around.is_empty() && around.iter().all(|&u| normals[u as usize].dot(&own) > MIN_NEIGHBOUR_COSINE)
}

/// The weighted sum of the normals of `v`'s neighbours that turn by less than 30 degrees
/// from its own.
fn agreeing_neighbours_sum(normals: &[Vector], weights: &[f64], neighbours: &VertexNeighbours, v: usize) -> Vector {
    let own = normals[v];
    neighbours
        .of_vertex(v)
        .iter()
        .map(|&u| (normals[u as usize], weights[u as usize]))
        .filter(|(other, _)| other.dot(&own) > MIN_NEIGHBOUR_COSINE)
        .fold(Vector::zeros(), |sum, (other, weight)| sum + other * weight)
}

/// `normals` averaged `passes` times with their neighbours' (weighted by `weights`, the
/// vertices' areas), each neighbour counting only while its normal turns by less than 30
/// degrees from the vertex's. Zero normals stay zero.
pub fn filter_normals(normals: &[Vector], weights: &[f64], neighbours: &VertexNeighbours, passes: usize) -> Vec<Vector> {
    let mut current = normals.to_vec();
    for _ in 0..passes {
        current = (0..current.len())
            .map(|v| {
                let own = current[v];
                if own.norm_squared() < 0.5 {
                    return own;
                }
                let sum = own * weights[v] + agreeing_neighbours_sum(&current, weights, neighbours, v);
                sum.try_normalize(0.0).unwrap_or(own)
            })
            .collect();
    }
    current
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::normals::{compute_vertex_normals, NormalWeighting};
    use crate::mesh::Point;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use rand_distr::StandardNormal;

    /// A cylinder of radius 60 mm, 1 mm between vertices, its radius roughened by
    /// Gaussian noise of `sigma_mm`.
    fn rough_cylinder(sigma_mm: f64, seed: u64) -> Mesh {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let (radius, columns, rows) = (60.0, 60, 40);
        let mut positions = Vec::new();
        for row in 0..rows {
            for column in 0..columns {
                let angle = column as f64 / radius;
                let noise: f64 = rng.sample(StandardNormal);
                let r = radius + sigma_mm * noise;
                positions.push(Point::new(r * angle.cos(), r * angle.sin(), row as f64));
            }
        }
        let mut triangles = Vec::new();
        for row in 0..rows - 1 {
            for column in 0..columns - 1 {
                let at = |r: usize, c: usize| (r * columns + c) as u32;
                triangles.push([at(row, column), at(row, column + 1), at(row + 1, column + 1)]);
                triangles.push([at(row, column), at(row + 1, column + 1), at(row + 1, column)]);
            }
        }
        Mesh { positions, triangles, ..Default::default() }
    }

    /// The scatter is nil on a smooth cylinder and grows with the roughness in proportion
    /// (about 0.56 radians per unit of roughness over spacing).
    #[test]
    fn the_scatter_grows_with_the_roughness() {
        let scatter = |sigma: f64| {
            let mesh = rough_cylinder(sigma, 3);
            let normals = compute_vertex_normals(&mesh, NormalWeighting::Area);
            normal_scatter(&normals, &vec![1.0; normals.len()], &VertexNeighbours::of(&mesh)).unwrap()
        };
        let (smooth, slight, rough) = (scatter(0.0), scatter(0.05), scatter(0.25));
        assert!(smooth < 1e-3, "smooth: {smooth}");
        assert!((0.02..0.04).contains(&slight) && (4.0..6.0).contains(&(rough / slight)), "{slight} {rough}");
        assert_eq!(passes_for_scatter(smooth), 0);
        assert!(passes_for_scatter(slight) <= 1 && passes_for_scatter(rough) >= 5, "{} {}", passes_for_scatter(slight), passes_for_scatter(rough));
        assert_eq!(passes_for_scatter(10.0), MAX_FILTER_PASSES);
    }

    /// Filtering brings the rough cylinder's normals back towards the radial direction.
    #[test]
    fn filtered_normals_turn_less_from_the_true_ones() {
        let mesh = rough_cylinder(0.25, 5);
        let normals = compute_vertex_normals(&mesh, NormalWeighting::Area);
        let weights = vec![1.0; normals.len()];
        let neighbours = VertexNeighbours::of(&mesh);
        let error_deg = |normals: &[Vector]| {
            let mut angles: Vec<f64> = mesh
                .positions
                .iter()
                .zip(normals)
                .map(|(p, n)| {
                    let radial = Vector::new(p.x, p.y, 0.0).normalize();
                    n.dot(&radial).abs().clamp(-1.0, 1.0).acos().to_degrees()
                })
                .collect();
            angles.sort_by(f64::total_cmp);
            angles[angles.len() / 2]
        };
        let before = error_deg(&normals);
        let after = error_deg(&filter_normals(&normals, &weights, &neighbours, 8));
        assert!(before > 8.0 && after < before / 5.0, "median error {before:.1} deg before, {after:.1} after");
        let smooth = rough_cylinder(0.0, 5);
        let normals = compute_vertex_normals(&smooth, NormalWeighting::Area);
        let kept = freed_of_roughness(&smooth, normals.clone(), &crate::mesh::normals::vertex_areas(&smooth));
        assert_eq!((kept.passes, kept.normals), (0, normals), "a smooth scan's normals are kept as they are");
    }
}
