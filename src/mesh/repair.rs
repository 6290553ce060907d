//! Mesh repair before processing (Wilczek et al. 2018, section 2.1: the scan is cleaned
//! before normals are estimated): merge duplicate vertices (exactly, and optionally
//! within a tolerance), drop degenerate and duplicate faces, optionally keep only the
//! largest connected component, drop unreferenced vertices, and report non-manifold
//! edges and vertices, boundary edges and components. [`RepairReport`] says what changed.
//!
//! Every per-vertex attribute (normals, colours, quality) follows its vertex, and
//! per-corner texture coordinates follow their face. A merged vertex keeps the position
//! and attributes of the lowest-indexed vertex of its group, as MeshLab's "merge close
//! vertices" does, so that repair never invents values.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::Mesh;
use super::spatial::KdTree;
use super::topology::Topology;

/// What [`repair`] does beyond the steps it always takes.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RepairOptions {
    /// When set, vertices closer than this (in the mesh's units, millimetres for scans)
    /// are merged too, after exact duplicates.
    pub merge_tolerance_mm: Option<f64>,
    /// Keep only the connected component with the most faces (scans often carry specks
    /// of the turntable or of dust).
    pub keep_largest_component: bool,
}

/// At most this many non-manifold edges are listed by vertex pair in the report.
const LISTED_NON_MANIFOLD_EDGES: usize = 20;

/// What [`repair`] changed and found.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RepairReport {
    /// Vertex count before repair.
    pub vertices_before: usize,
    /// Face count before repair.
    pub faces_before: usize,
    /// Vertex count after repair.
    pub vertices_after: usize,
    /// Face count after repair.
    pub faces_after: usize,
    /// Vertices merged into another with bit-identical coordinates.
    pub duplicate_vertices_merged: usize,
    /// Vertices merged into another within `merge_tolerance_mm`.
    pub close_vertices_merged: usize,
    /// Faces removed because two corners were the same vertex or the area was zero.
    pub degenerate_faces_removed: usize,
    /// Faces removed because another face has the same three vertices (in any order).
    pub duplicate_faces_removed: usize,
    /// Faces removed with the components other than the largest.
    pub component_faces_removed: usize,
    /// Components removed (all but the largest) when asked.
    pub components_removed: usize,
    /// Vertices no face referred to, removed (never for a point cloud).
    pub unreferenced_vertices_removed: usize,
    /// Edge-connected components after repair, largest first (face counts).
    pub component_face_counts: Vec<usize>,
    /// Edges with one face after repair.
    pub boundary_edge_count: usize,
    /// Edges shared by more than two faces after repair (repair does not cut them).
    pub non_manifold_edge_count: usize,
    /// The first few non-manifold edges as vertex index pairs (after repair).
    pub non_manifold_edges: Vec<[u32; 2]>,
    /// Vertices where the surface pinches (more than one fan of faces) after repair.
    pub non_manifold_vertex_count: usize,
    /// True when the repaired mesh is closed and 2-manifold along its edges.
    pub watertight: bool,
}

impl RepairReport {
    /// True when repair changed nothing.
    pub fn changed_nothing(&self) -> bool {
        self.vertices_before == self.vertices_after && self.faces_before == self.faces_after
            && self.duplicate_vertices_merged == 0 && self.close_vertices_merged == 0
    }
}

/// Repairs `mesh` in place and reports what changed. Point clouds (no faces) only have
/// duplicate points merged; nothing is unreferenced there.
pub fn repair(mesh: &mut Mesh, options: &RepairOptions) -> RepairReport {
    let mut report = RepairReport {
        vertices_before: mesh.positions.len(),
        faces_before: mesh.triangles.len(),
        ..Default::default()
    };

    let exact = exact_duplicate_representatives(mesh);
    report.duplicate_vertices_merged = exact.iter().enumerate().filter(|&(i, &r)| r as usize != i).count();
    let mut representative = exact;
    if let Some(tolerance) = options.merge_tolerance_mm.filter(|t| *t > 0.0) {
        let close = close_vertex_representatives(mesh, &representative, tolerance);
        report.close_vertices_merged = close
            .iter()
            .enumerate()
            .filter(|&(i, &r)| r as usize != i && representative[i] as usize == i)
            .count();
        representative = close;
    }
    for tri in &mut mesh.triangles {
        *tri = tri.map(|v| representative[v as usize]);
    }

    let keep_face = {
        let mut keep: Vec<bool> = mesh
            .triangles
            .par_iter()
            .map(|&[a, b, c]| {
                a != b && b != c && a != c && {
                    let [pa, pb, pc] = [a, b, c].map(|v| mesh.positions[v as usize]);
                    (pb - pa).cross(&(pc - pa)) != super::Vector::zeros()
                }
            })
            .collect();
        report.degenerate_faces_removed = keep.iter().filter(|k| !**k).count();
        report.duplicate_faces_removed = mark_duplicate_faces(&mesh.triangles, &mut keep);
        keep
    };
    retain_faces(mesh, &keep_face);

    if options.keep_largest_component && !mesh.triangles.is_empty() {
        let components = Topology::new(mesh).connected_components();
        if let Some(largest) = components.largest() {
            let keep: Vec<bool> = components.face_labels.iter().map(|&l| l == largest).collect();
            report.components_removed = components.count() - 1;
            report.component_faces_removed = mesh.triangles.len() - components.face_counts[largest as usize];
            retain_faces(mesh, &keep);
        }
    }

    // Vertices merged away are unreferenced now; in a point cloud they are dropped too.
    let mut keep_vertex = vec![false; mesh.positions.len()];
    if mesh.triangles.is_empty() {
        for (i, &r) in representative.iter().enumerate() {
            keep_vertex[i] = r as usize == i;
        }
    } else {
        for tri in &mesh.triangles {
            for &v in tri {
                keep_vertex[v as usize] = true;
            }
        }
    }
    let dropped = keep_vertex.iter().filter(|k| !**k).count();
    let merged = report.duplicate_vertices_merged + report.close_vertices_merged;
    report.unreferenced_vertices_removed = dropped.saturating_sub(merged);
    retain_vertices(mesh, &keep_vertex);

    let topology = Topology::new(mesh);
    let components = topology.connected_components();
    report.component_face_counts = components.face_counts;
    report.component_face_counts.sort_unstable_by(|a, b| b.cmp(a));
    report.boundary_edge_count = topology.boundary_edges().len();
    let non_manifold = topology.non_manifold_edges();
    report.non_manifold_edge_count = non_manifold.len();
    report.non_manifold_edges =
        non_manifold.iter().take(LISTED_NON_MANIFOLD_EDGES).map(|&e| topology.edges()[e]).collect();
    report.non_manifold_vertex_count = topology.non_manifold_vertices().len();
    report.watertight = topology.is_watertight();
    report.vertices_after = mesh.positions.len();
    report.faces_after = mesh.triangles.len();
    report
}

/// For every vertex, the lowest-indexed vertex with bit-identical coordinates (`-0.0`
/// and `0.0` are the same coordinate).
fn exact_duplicate_representatives(mesh: &Mesh) -> Vec<u32> {
    let key = |i: u32| {
        let p = mesh.positions[i as usize];
        // Adding 0.0 turns -0.0 into 0.0; positions are finite after reading.
        [(p.x + 0.0).to_bits(), (p.y + 0.0).to_bits(), (p.z + 0.0).to_bits()]
    };
    let mut order: Vec<u32> = (0..mesh.positions.len() as u32).collect();
    order.par_sort_unstable_by_key(|&i| (key(i), i));
    let mut representative: Vec<u32> = (0..mesh.positions.len() as u32).collect();
    let mut group_start = 0;
    for i in 1..=order.len() {
        if i == order.len() || key(order[i]) != key(order[group_start]) {
            // Sorted by (key, index): the first of a group has the lowest index.
            let lowest = order[group_start];
            for &member in &order[group_start..i] {
                representative[member as usize] = lowest;
            }
            group_start = i;
        }
    }
    representative
}

/// Greedy clustering within `tolerance`: vertices are visited in index order, and each
/// one not yet taken takes every untaken vertex within `tolerance` of it. Vertices
/// already merged exactly (`representative[i] != i`) follow their representative.
fn close_vertex_representatives(mesh: &Mesh, representative: &[u32], tolerance: f64) -> Vec<u32> {
    let distinct: Vec<u32> = (0..mesh.positions.len() as u32).filter(|&i| representative[i as usize] == i).collect();
    let distinct_points: Vec<_> = distinct.iter().map(|&i| mesh.positions[i as usize]).collect();
    let tree = KdTree::new(&distinct_points);
    let mut taken_by = vec![u32::MAX; distinct.len()];
    for slot in 0..distinct.len() {
        if taken_by[slot] != u32::MAX {
            continue;
        }
        taken_by[slot] = distinct[slot];
        tree.for_each_within_radius(&distinct_points[slot], tolerance, |other, _| {
            if taken_by[other] == u32::MAX {
                taken_by[other] = distinct[slot];
            }
        });
    }
    let mut result = representative.to_vec();
    for (slot, &vertex) in distinct.iter().enumerate() {
        result[vertex as usize] = taken_by[slot];
    }
    for i in 0..result.len() {
        let r = representative[i] as usize;
        if r != i {
            result[i] = result[r];
        }
    }
    result
}

/// Clears `keep` for every face whose vertex set repeats an earlier kept face's; returns
/// how many it cleared.
fn mark_duplicate_faces(triangles: &[[u32; 3]], keep: &mut [bool]) -> usize {
    let mut order: Vec<([u32; 3], u32)> = triangles
        .iter()
        .enumerate()
        .filter(|&(f, _)| keep[f])
        .map(|(f, tri)| {
            let mut sorted = *tri;
            sorted.sort_unstable();
            (sorted, f as u32)
        })
        .collect();
    order.par_sort_unstable();
    let mut removed = 0;
    for pair in order.windows(2) {
        if pair[0].0 == pair[1].0 {
            keep[pair[1].1 as usize] = false;
            removed += 1;
        }
    }
    removed
}

/// Keeps the faces with `keep[f]`, and their corner texture coordinates.
pub(super) fn retain_faces(mesh: &mut Mesh, keep: &[bool]) {
    if keep.iter().all(|&k| k) {
        return;
    }
    let mut f = 0;
    mesh.triangles.retain(|_| {
        f += 1;
        keep[f - 1]
    });
    if let Some(uvs) = &mut mesh.corner_uvs {
        let mut corner = 0;
        uvs.retain(|_| {
            corner += 1;
            keep[(corner - 1) / 3]
        });
    }
}

/// Keeps the vertices with `keep[v]`, renumbering faces and compacting attributes; the
/// faces must use kept vertices only.
pub(super) fn retain_vertices(mesh: &mut Mesh, keep: &[bool]) {
    if keep.iter().all(|&k| k) {
        return;
    }
    let mut new_index = vec![u32::MAX; keep.len()];
    let mut next = 0u32;
    for (v, &k) in keep.iter().enumerate() {
        if k {
            new_index[v] = next;
            next += 1;
        }
    }
    fn compact<T>(values: &mut Vec<T>, keep: &[bool]) {
        let mut i = 0;
        values.retain(|_| {
            i += 1;
            keep[i - 1]
        });
    }
    compact(&mut mesh.positions, keep);
    if let Some(normals) = &mut mesh.normals {
        compact(normals, keep);
    }
    if let Some(colors) = &mut mesh.colors {
        compact(colors, keep);
    }
    if let Some(quality) = &mut mesh.quality {
        compact(quality, keep);
    }
    for tri in &mut mesh.triangles {
        *tri = tri.map(|v| new_index[v as usize]);
    }
}
