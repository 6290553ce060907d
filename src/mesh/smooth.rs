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

use nalgebra::Vector4;

use super::normals::{NormalWeighting, accumulate_over_faces, compute_vertex_normals};
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
    // Boundary sides as vertex pairs, for the second and third passes below.
    let boundary_pairs: Vec<(usize, usize)> = mesh
        .triangles
        .iter()
        .zip(&boundary)
        .flat_map(|(tri, sides)| {
            (0..3).filter(|&k| sides[k]).map(move |k| (tri[k] as usize, tri[(k + 1) % 3] as usize))
        })
        .collect();
    for _ in 0..options.iterations {
        let positions = &mesh.positions;
        let triangles = &mesh.triangles;
        // (Σ w_j p_j, Σ w_j) per vertex, over the sides that are not on the boundary.
        let mut sums = accumulate_over_faces(triangles.len(), positions.len(), Vector4::zeros(), |f, sums| {
            let tri = triangles[f];
            let p = tri.map(|v| positions[v as usize]);
            for k in 0..3 {
                if boundary[f][k] {
                    continue;
                }
                let (a, b) = (k, (k + 1) % 3);
                let w = match options.weights {
                    LaplacianWeights::Uniform => 1.0,
                    LaplacianWeights::Cotangent => cotangent_at(&p[(k + 2) % 3], &p[a], &p[b]),
                };
                sums[tri[a] as usize] += weighted(&p[b], w);
                sums[tri[b] as usize] += weighted(&p[a], w);
            }
        });
        // A boundary vertex starts again from itself (weight 1), then adds its
        // boundary neighbours with weight 1 each.
        for &(a, b) in &boundary_pairs {
            sums[a] = weighted(&positions[a], 1.0);
            sums[b] = weighted(&positions[b], 1.0);
        }
        for &(a, b) in &boundary_pairs {
            sums[a] += weighted(&positions[b], 1.0);
            sums[b] += weighted(&positions[a], 1.0);
        }
        mesh.positions.par_iter_mut().zip(&sums).zip(&pinned).for_each(|((p, sum), &pinned)| {
            let weight = sum.w;
            if weight > 0.0 && !pinned {
                *p = Point::from((p.coords + sum.xyz()) / (weight + 1.0));
            }
        });
    }
    refresh_normals(mesh);
}

/// Cotangent of the angle at `apex` between the edges to `a` and `b` (`cos / sin`, the
/// same number vcglib gets through `tan(π/2 - angle)`); 0 for a degenerate corner, where
/// MeshLab's weight is meaningless.
fn cotangent_at(apex: &Point, a: &Point, b: &Point) -> f64 {
    let (u, v) = (a - apex, b - apex);
    let sine_scaled = u.cross(&v).norm();
    if sine_scaled == 0.0 {
        return 0.0;
    }
    u.dot(&v) / sine_scaled
}

/// `(w p, w)`: a position and its weight in one vector, so that sums of both are one sum.
fn weighted(p: &Point, w: f64) -> Vector4<f64> {
    Vector4::new(p.x * w, p.y * w, p.z * w, w)
}

/// HC smoothing (Vollmer et al. 1999) as MeshLab's "HC Laplacian Smooth" filter
/// computes it, `iterations` times, in place. Each step takes the uniform average `q_i`
/// of the neighbours (edges on the boundary count twice, interior edges once per face),
/// the average `d_i` of the neighbours' displacements `q_j - p_j`, and moves the vertex
/// to `q_i - β (q_i - p_i) + (1 - β) d_i` with `β = 0.5`. Vertices without faces do not
/// move. Vertex normals, when present, are recomputed.
///
/// MeshLab's step differs from the paper's: it blends with the previous positions only
/// (the paper's `α = 0`) and *adds* the neighbours' mean displacement where the paper
/// subtracts it, so it smooths more and shrinks more than the paper's HC. It is kept
/// because sherd is compared with MeshLab; [`hc_smooth_vollmer`] is the paper's.
pub fn hc_smooth(mesh: &mut Mesh, iterations: usize) {
    const BETA: f64 = 0.5;
    if mesh.triangles.is_empty() || iterations == 0 {
        return;
    }
    let boundary = boundary_sides(mesh);
    // Boundary sides count twice, as MeshLab counts them.
    let times = |f: usize, k: usize| if boundary[f][k] { 2.0 } else { 1.0 };
    for _ in 0..iterations {
        let positions = &mesh.positions;
        let triangles = &mesh.triangles;
        let averages: Vec<Vector4<f64>> =
            accumulate_over_faces(triangles.len(), positions.len(), Vector4::zeros(), |f, sums| {
                let tri = triangles[f];
                for k in 0..3 {
                    let (a, b) = (tri[k] as usize, tri[(k + 1) % 3] as usize);
                    sums[a] += weighted(&positions[b], times(f, k));
                    sums[b] += weighted(&positions[a], times(f, k));
                }
            })
            .into_par_iter()
            .map(|sum| if sum.w > 0.0 { Vector4::new(sum.x / sum.w, sum.y / sum.w, sum.z / sum.w, sum.w) } else { sum })
            .collect();
        // Each vertex's average minus its position: what the neighbours then average.
        let moves: Vec<Vector> = averages.par_iter().zip(positions).map(|(q, p)| q.xyz() - p.coords).collect();
        let differences = accumulate_over_faces(triangles.len(), positions.len(), Vector::zeros(), |f, sums| {
            let tri = triangles[f];
            for k in 0..3 {
                let (a, b) = (tri[k] as usize, tri[(k + 1) % 3] as usize);
                sums[a] += moves[b] * times(f, k);
                sums[b] += moves[a] * times(f, k);
            }
        });
        mesh.positions.par_iter_mut().enumerate().for_each(|(v, p)| {
            let count = averages[v].w;
            if count > 0.0 {
                let average = averages[v].xyz();
                let difference = differences[v] / count;
                *p = Point::from(average - (average - p.coords) * BETA + difference * (1.0 - BETA));
            }
        });
    }
    refresh_normals(mesh);
}

/// HC smoothing exactly as Vollmer et al. (1999) define it, which MeshLab's filter
/// (see [`hc_smooth`]) departs from: each step moves every vertex to the uniform average
/// `p_i` of its neighbours (over unique edges), measures how far that is from a blend of
/// the original and previous positions, `b_i = p_i - (α o_i + (1 - α) q_i)`, and pulls it
/// back by `β b_i + (1 - β) mean_j b_j`. With `α = 0` and `β = 0.5` the surface keeps its
/// volume far better than plain Laplacian smoothing. Vertices without faces do not move.
pub fn hc_smooth_vollmer(mesh: &mut Mesh, iterations: usize, alpha: f64, beta: f64) {
    if mesh.triangles.is_empty() || iterations == 0 {
        return;
    }
    let topology = Topology::new(mesh);
    let vertex_count = mesh.positions.len();
    let mut neighbour_start = vec![0u32; vertex_count + 1];
    for &[a, b] in topology.edges() {
        neighbour_start[a as usize + 1] += 1;
        neighbour_start[b as usize + 1] += 1;
    }
    for v in 0..vertex_count {
        neighbour_start[v + 1] += neighbour_start[v];
    }
    let mut neighbours = vec![0u32; neighbour_start[vertex_count] as usize];
    let mut filled = neighbour_start.clone();
    for &[a, b] in topology.edges() {
        neighbours[filled[a as usize] as usize] = b;
        filled[a as usize] += 1;
        neighbours[filled[b as usize] as usize] = a;
        filled[b as usize] += 1;
    }
    let around = |v: usize| &neighbours[neighbour_start[v] as usize..neighbour_start[v + 1] as usize];
    let original = mesh.positions.clone();
    for _ in 0..iterations {
        let previous = mesh.positions.clone();
        let averaged: Vec<Point> = (0..vertex_count)
            .into_par_iter()
            .map(|v| {
                let ring = around(v);
                if ring.is_empty() {
                    return previous[v];
                }
                let sum = ring.iter().fold(Vector::zeros(), |s, &j| s + previous[j as usize].coords);
                Point::from(sum / ring.len() as f64)
            })
            .collect();
        let pull_back: Vec<Vector> = (0..vertex_count)
            .into_par_iter()
            .map(|v| averaged[v].coords - (original[v].coords * alpha + previous[v].coords * (1.0 - alpha)))
            .collect();
        mesh.positions.par_iter_mut().enumerate().for_each(|(v, p)| {
            let ring = around(v);
            if ring.is_empty() {
                return;
            }
            let mean = ring.iter().fold(Vector::zeros(), |s, &j| s + pull_back[j as usize]) / ring.len() as f64;
            *p = averaged[v] - (pull_back[v] * beta + mean * (1.0 - beta));
        });
    }
    refresh_normals(mesh);
}

fn refresh_normals(mesh: &mut Mesh) {
    if mesh.normals.is_some() {
        mesh.normals = Some(compute_vertex_normals(mesh, NormalWeighting::Area));
    }
}
