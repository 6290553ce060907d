//! Laplacian smoothing (uniform or cotangent weights) and HC smoothing (Vollmer, Mencl
//! and Müller 1999, "Improved Laplacian smoothing of noisy surface meshes"), computed
//! as MeshLab computes them (vcglib's `tri::Smooth::VertexCoordLaplacian` and
//! `VertexCoordLaplacianHC`), so that results can be compared with MeshLab's filters
//! vertex by vertex (`tests/meshlab_smoothing.rs`).
//!
//! One Laplacian step moves every vertex `p` to `(p + Σ w_j p_j) / (1 + Σ w_j)` over
//! its neighbours `p_j`: the vertex itself counts with weight 1. An interior edge is seen
//! from both of its faces, so with uniform weights each neighbour across an interior
//! edge counts twice; with cotangent weights each face contributes the cotangent of its
//! angle opposite the edge (the `cot α + cot β` of Desbrun et al. 1999). All vertices
//! move at once (Jacobi order). A boundary vertex is handled as [`BoundaryHandling`] says.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::normals::{NormalWeighting, compute_vertex_normals};
use super::topology::{NO_EDGE, Topology};
use super::{Mesh, Point, Vector};

/// The weight of a neighbour in a Laplacian step.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum LaplacianWeights {
    /// 1 per face sharing the edge (MeshLab's "umbrella" scheme).
    Uniform,
    /// Cotangent of the angle opposite the edge in each face sharing it (MeshLab's
    /// default): moves vertices across the surface less, so shapes drift less.
    #[default]
    Cotangent,
}

/// What happens to vertices on boundary edges (the border of an open scan or a hole).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum BoundaryHandling {
    /// The boundary polyline is smoothed by itself: a boundary vertex averages with
    /// itself (twice) and its boundary neighbours only. MeshLab's "1D Boundary
    /// Smoothing" (on by default).
    #[default]
    AlongBoundary,
    /// Boundary vertices are smoothed like interior ones, with all their neighbours
    /// (MeshLab with "1D Boundary Smoothing" off): the border shrinks inwards.
    Free,
    /// Boundary vertices do not move: the outline of a sherd's break stays where the
    /// scanner put it.
    Fixed,
}

/// Parameters of [`laplacian_smooth`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct SmoothOptions {
    /// Number of smoothing steps.
    pub iterations: usize,
    /// Neighbour weights.
    pub weights: LaplacianWeights,
    /// Treatment of boundary vertices.
    pub boundary: BoundaryHandling,
}

impl Default for SmoothOptions {
    /// MeshLab's defaults: 3 steps, cotangent weights, boundary smoothed along itself.
    fn default() -> Self {
        SmoothOptions { iterations: 3, weights: LaplacianWeights::Cotangent, boundary: BoundaryHandling::AlongBoundary }
    }
}

/// For every face side (corners `k`, `k + 1`): true when its edge has exactly one face
/// (MeshLab's border flag, from `FaceBorderFromNone`).
fn boundary_sides(mesh: &Mesh) -> Vec<[bool; 3]> {
    let topology = Topology::new(mesh);
    (0..mesh.triangles.len())
        .map(|f| {
            topology
                .face_edges(f)
                .map(|e| e != NO_EDGE && topology.faces_of_edge(e as usize).len() == 1)
        })
        .collect()
}

/// Laplacian smoothing of the vertex positions, in place. Vertices without faces do not
/// move. Vertex normals, when present, are recomputed (area-weighted, as MeshLab does
/// after a filter).
pub fn laplacian_smooth(mesh: &mut Mesh, options: &SmoothOptions) {
    if mesh.triangles.is_empty() || options.iterations == 0 {
        return;
    }
    let mut boundary = boundary_sides(mesh);
    if options.boundary == BoundaryHandling::Free {
        boundary.iter_mut().for_each(|sides| *sides = [false; 3]);
    }
    let mut pinned = vec![false; mesh.positions.len()];
    if options.boundary == BoundaryHandling::Fixed {
        for (tri, sides) in mesh.triangles.iter().zip(&boundary) {
            for k in 0..3 {
                if sides[k] {
                    pinned[tri[k] as usize] = true;
                    pinned[tri[(k + 1) % 3] as usize] = true;
                }
            }
        }
    }
    let mut sums = vec![Vector::zeros(); mesh.positions.len()];
    let mut weights = vec![0.0f64; mesh.positions.len()];
    for _ in 0..options.iterations {
        sums.iter_mut().for_each(|s| *s = Vector::zeros());
        weights.iter_mut().for_each(|w| *w = 0.0);
        let side_weights: Vec<[f64; 3]> = match options.weights {
            LaplacianWeights::Uniform => vec![[1.0; 3]; mesh.triangles.len()],
            LaplacianWeights::Cotangent => mesh
                .triangles
                .par_iter()
                .map(|tri| {
                    let p = tri.map(|v| mesh.positions[v as usize]);
                    [0, 1, 2].map(|k| cotangent_at(&p[(k + 2) % 3], &p[k], &p[(k + 1) % 3]))
                })
                .collect(),
        };
        let positions = &mesh.positions;
        for ((tri, sides), side_weight) in mesh.triangles.iter().zip(&boundary).zip(&side_weights) {
            for k in 0..3 {
                if sides[k] {
                    continue;
                }
                let (a, b) = (tri[k] as usize, tri[(k + 1) % 3] as usize);
                let w = side_weight[k];
                sums[a] += positions[b].coords * w;
                sums[b] += positions[a].coords * w;
                weights[a] += w;
                weights[b] += w;
            }
        }
        // A boundary vertex starts again from itself (weight 1), then adds its
        // boundary neighbours with weight 1 each.
        for (tri, sides) in mesh.triangles.iter().zip(&boundary) {
            for k in 0..3 {
                if sides[k] {
                    for v in [tri[k] as usize, tri[(k + 1) % 3] as usize] {
                        sums[v] = positions[v].coords;
                        weights[v] = 1.0;
                    }
                }
            }
        }
        for (tri, sides) in mesh.triangles.iter().zip(&boundary) {
            for k in 0..3 {
                if sides[k] {
                    let (a, b) = (tri[k] as usize, tri[(k + 1) % 3] as usize);
                    sums[a] += positions[b].coords;
                    sums[b] += positions[a].coords;
                    weights[a] += 1.0;
                    weights[b] += 1.0;
                }
            }
        }
        mesh.positions.par_iter_mut().enumerate().for_each(|(v, p)| {
            if weights[v] > 0.0 && !pinned[v] {
                *p = Point::from((p.coords + sums[v]) / (weights[v] + 1.0));
            }
        });
    }
    refresh_normals(mesh);
}

/// Cotangent of the angle at `apex` between the edges to `a` and `b`; 0 when an edge
/// has zero length (where MeshLab would use a meaningless weight).
fn cotangent_at(apex: &Point, a: &Point, b: &Point) -> f64 {
    let (u, v) = (a - apex, b - apex);
    let lengths = u.norm() * v.norm();
    if lengths == 0.0 {
        return 0.0;
    }
    // Through the angle, as vcglib does, so that the weights are the same numbers.
    let angle = (u.dot(&v) / lengths).clamp(-1.0, 1.0).acos();
    (std::f64::consts::FRAC_PI_2 - angle).tan()
}

/// HC smoothing (Vollmer et al. 1999) as MeshLab's "HC Laplacian Smooth" filter
/// computes it, `iterations` times, in place. Each step takes the uniform average `q_i`
/// of the neighbours (edges on the boundary count twice, interior edges once per face),
/// the average `d_i` of the neighbours' displacements `q_j - p_j`, and moves the vertex
/// to `q_i - β (q_i - p_i) + (1 - β) d_i` with `β = 0.5`. Vertices without faces do not
/// move. Vertex normals, when present, are recomputed.
pub fn hc_smooth(mesh: &mut Mesh, iterations: usize) {
    const BETA: f64 = 0.5;
    if mesh.triangles.is_empty() || iterations == 0 {
        return;
    }
    let boundary = boundary_sides(mesh);
    let vertex_count = mesh.positions.len();
    let mut counts = vec![0u32; vertex_count];
    for (tri, sides) in mesh.triangles.iter().zip(&boundary) {
        for k in 0..3 {
            let times = if sides[k] { 2 } else { 1 };
            counts[tri[k] as usize] += times;
            counts[tri[(k + 1) % 3] as usize] += times;
        }
    }
    let mut averages = vec![Vector::zeros(); vertex_count];
    let mut differences = vec![Vector::zeros(); vertex_count];
    for _ in 0..iterations {
        averages.iter_mut().for_each(|s| *s = Vector::zeros());
        differences.iter_mut().for_each(|s| *s = Vector::zeros());
        let positions = &mesh.positions;
        for (tri, sides) in mesh.triangles.iter().zip(&boundary) {
            for k in 0..3 {
                let (a, b) = (tri[k] as usize, tri[(k + 1) % 3] as usize);
                let times = if sides[k] { 2.0 } else { 1.0 };
                averages[a] += positions[b].coords * times;
                averages[b] += positions[a].coords * times;
            }
        }
        averages.par_iter_mut().zip(&counts).for_each(|(sum, &count)| {
            if count > 0 {
                *sum /= count as f64;
            }
        });
        for (tri, sides) in mesh.triangles.iter().zip(&boundary) {
            for k in 0..3 {
                let (a, b) = (tri[k] as usize, tri[(k + 1) % 3] as usize);
                let times = if sides[k] { 2.0 } else { 1.0 };
                differences[a] += (averages[b] - positions[b].coords) * times;
                differences[b] += (averages[a] - positions[a].coords) * times;
            }
        }
        mesh.positions.par_iter_mut().enumerate().for_each(|(v, p)| {
            if counts[v] > 0 {
                let average = averages[v];
                let difference = differences[v] / counts[v] as f64;
                *p = Point::from(average - (average - p.coords) * BETA + difference * (1.0 - BETA));
            }
        });
    }
    refresh_normals(mesh);
}

fn refresh_normals(mesh: &mut Mesh) {
    if mesh.normals.is_some() {
        mesh.normals = Some(compute_vertex_normals(mesh, NormalWeighting::Area));
    }
}
