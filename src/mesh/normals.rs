//! Vertex normals, angle- or area-weighted, and faces oriented consistently and outward.
//!
//! The paper's pre-orientation (Wilczek et al. 2018, section 2.2) works on vertex
//! normals, so they must all point out of the sherd. Faces are first made consistent by
//! a breadth-first walk over edges shared by exactly two faces (a neighbour listing the
//! shared edge in the same direction is flipped), then each such component is turned
//! outward when its signed volume is negative. Point clouds without normals get them
//! from a principal component fit of their nearest neighbours, oriented by propagation
//! along a minimum spanning tree (Hoppe et al. 1992).

use std::cmp::Ordering;
use std::collections::{BinaryHeap, VecDeque};

use nalgebra::{Matrix3, SymmetricEigen};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::spatial::KdTree;
use super::topology::Topology;
use super::{Mesh, Point, Vector};

/// How the normals of the faces around a vertex are weighted.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum NormalWeighting {
    /// By the corner angle of each face at the vertex (Thürmer and Wüthrich 1998):
    /// independent of how the surface is triangulated.
    #[default]
    Angle,
    /// By the area of each face (MeshLab's default "area weighted" normals).
    Area,
}

/// Neighbours used to fit a plane to a point of a cloud.
const POINT_CLOUD_NEIGHBOURS: usize = 16;

/// What [`orient_faces_outward`] did.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct OrientationReport {
    /// Faces whose corner order was reversed.
    pub flipped_faces: usize,
    /// Components walked (connected through edges with exactly two faces).
    pub components: usize,
    /// Edges whose two faces could not be made consistent (a Möbius-like surface).
    pub inconsistent_edges: usize,
}

/// Each vertex's share (a third) of the area of its faces: what its normal
/// weighs, so that the dense and the sparse parts of a decimated mesh count by area.
pub fn vertex_areas(mesh: &Mesh) -> Vec<f64> {
    let mut areas = vec![0.0; mesh.vertex_count()];
    for face in 0..mesh.face_count() {
        let third_area = mesh.face_area(face) / 3.0;
        for &v in &mesh.triangles[face] {
            areas[v as usize] += third_area;
        }
    }
    areas
}

/// Unit vertex normals from the faces. Vertices without faces keep the mesh's normal
/// when it has one, else get the zero vector.
pub fn compute_vertex_normals(mesh: &Mesh, weighting: NormalWeighting) -> Vec<Vector> {
    let mut sums = accumulate_over_faces(mesh.triangles.len(), mesh.positions.len(), Vector::zeros(), |f, sums| {
        let tri = mesh.triangles[f];
        let [a, b, c] = tri.map(|v| mesh.positions[v as usize]);
        let scaled = (b - a).cross(&(c - a));
        match weighting {
            NormalWeighting::Area => {
                for v in tri {
                    sums[v as usize] += scaled;
                }
            }
            NormalWeighting::Angle => {
                let Some(unit) = scaled.try_normalize(0.0) else { return };
                let (Some(ab), Some(bc), Some(ca)) =
                    ((b - a).try_normalize(0.0), (c - b).try_normalize(0.0), (a - c).try_normalize(0.0))
                else {
                    return;
                };
                let angle = |u: &Vector, v: &Vector| (-u.dot(v)).clamp(-1.0, 1.0).acos();
                sums[tri[0] as usize] += unit * angle(&ca, &ab);
                sums[tri[1] as usize] += unit * angle(&ab, &bc);
                sums[tri[2] as usize] += unit * angle(&bc, &ca);
            }
        }
    });
    sums.par_iter_mut().enumerate().for_each(|(v, sum)| {
        *sum = match sum.try_normalize(0.0) {
            Some(unit) if unit.iter().all(|c| c.is_finite()) => unit,
            _ => mesh.normals.as_ref().and_then(|n| n.get(v)).copied().unwrap_or_else(Vector::zeros),
        };
    });
    sums
}

/// Meshes with fewer faces than this are accumulated on one thread.
const PARALLEL_ACCUMULATION_MIN_FACES: usize = 50_000;
/// Number of parts the faces of a large mesh are split into. Fixed, not the thread
/// count, so that sums are added in the same order, and results are the same to the
/// last bit, on every machine.
const ACCUMULATION_PARTS: usize = 4;

/// Per-vertex sums over the faces: `visit(face, sums)` adds a face's contributions to
/// its vertices. Large meshes are split into [`ACCUMULATION_PARTS`] runs of faces, each
/// summed into its own buffer in parallel, then added up: a scatter like MeshLab's
/// single loop, without a per-face buffer or per-vertex locks.
pub(crate) fn accumulate_over_faces<A>(
    face_count: usize,
    vertex_count: usize,
    zero: A,
    visit: impl Fn(usize, &mut [A]) + Sync,
) -> Vec<A>
where
    A: Copy + Send + Sync + std::ops::AddAssign,
{
    if face_count < PARALLEL_ACCUMULATION_MIN_FACES {
        let mut sums = vec![zero; vertex_count];
        (0..face_count).for_each(|f| visit(f, &mut sums));
        return sums;
    }
    let part_length = face_count.div_ceil(ACCUMULATION_PARTS);
    let mut parts: Vec<Vec<A>> = (0..ACCUMULATION_PARTS)
        .into_par_iter()
        .map(|part| {
            let mut sums = vec![zero; vertex_count];
            (part * part_length..((part + 1) * part_length).min(face_count)).for_each(|f| visit(f, &mut sums));
            sums
        })
        .collect();
    let mut total = parts.remove(0);
    total.par_iter_mut().enumerate().for_each(|(v, sum)| {
        for part in &parts {
            *sum += part[v];
        }
    });
    total
}

/// Makes the faces of every edge-connected piece consistently oriented, then turns each
/// piece outward (positive signed volume about its centroid; for an open piece this
/// makes the normals point away from its centroid on balance). Vertex normals are not
/// touched. Corner texture coordinates follow their corners.
pub fn orient_faces_outward(mesh: &mut Mesh) -> OrientationReport {
    let mut report = OrientationReport::default();
    if mesh.triangles.is_empty() {
        return report;
    }
    let topology = Topology::new(mesh);
    let face_count = mesh.triangles.len();
    let mut component = vec![u32::MAX; face_count];
    let mut flipped = vec![false; face_count];
    let mut queue = VecDeque::new();
    let mut component_faces: Vec<Vec<u32>> = Vec::new();
    for seed in 0..face_count {
        if component[seed] != u32::MAX {
            continue;
        }
        let label = component_faces.len() as u32;
        component[seed] = label;
        let mut members = vec![seed as u32];
        queue.push_back(seed);
        while let Some(f) = queue.pop_front() {
            for edge in topology.face_edges(f) {
                if edge == super::topology::NO_EDGE {
                    continue;
                }
                let &[f0, f1] = topology.faces_of_edge(edge as usize) else { continue };
                let g = if f0 as usize == f { f1 } else { f0 } as usize;
                // `f` may have been flipped since the topology was built: take the
                // edge's direction from its corners as they are now.
                let [u, v] = topology.edges()[edge as usize];
                let (a, b) = if runs_from(&mesh.triangles[f], u, v) { (u, v) } else { (v, u) };
                let same_direction = runs_from(&mesh.triangles[g], a, b);
                if component[g] == u32::MAX {
                    if same_direction {
                        flip_face(mesh, g);
                        flipped[g] = !flipped[g];
                    }
                    component[g] = label;
                    members.push(g as u32);
                    queue.push_back(g);
                } else if same_direction && f < g {
                    report.inconsistent_edges += 1;
                }
            }
        }
        component_faces.push(members);
    }
    report.components = component_faces.len();
    for members in &component_faces {
        if signed_volume(mesh, members) < 0.0 {
            for &f in members {
                flip_face(mesh, f as usize);
                flipped[f as usize] = !flipped[f as usize];
            }
        }
    }
    report.flipped_faces = flipped.iter().filter(|f| **f).count();
    report
}

/// Makes sure `mesh.normals` holds a unit normal per vertex. Normals the scan brought
/// are kept. Otherwise, for a mesh, faces are oriented outward and angle-weighted
/// normals computed; for a point cloud, normals are fitted to the 16 nearest neighbours
/// and oriented consistently, pointing outward at the point farthest from the centroid.
pub fn ensure_vertex_normals(mesh: &mut Mesh) {
    let usable = mesh.normals.as_ref().is_some_and(|n| {
        n.len() == mesh.positions.len() && n.iter().all(|v| v.iter().all(|c| c.is_finite()))
    });
    if usable || mesh.positions.is_empty() {
        return;
    }
    if mesh.is_point_cloud() {
        mesh.normals = Some(point_cloud_normals(&mesh.positions));
    } else {
        orient_faces_outward(mesh);
        mesh.normals = Some(compute_vertex_normals(mesh, NormalWeighting::Angle));
    }
}

/// True when triangle `tri` has the side `a -> b` (in its corner order).
fn runs_from(tri: &[u32; 3], a: u32, b: u32) -> bool {
    (0..3).any(|j| tri[j] == a && tri[(j + 1) % 3] == b)
}

fn flip_face(mesh: &mut Mesh, face: usize) {
    mesh.triangles[face].swap(1, 2);
    if let Some(uvs) = &mut mesh.corner_uvs {
        uvs.swap(3 * face + 1, 3 * face + 2);
    }
}

/// Six times the signed volume enclosed by `faces`, measured about their centroid so
/// that it does not depend on where the scan's origin is.
fn signed_volume(mesh: &Mesh, faces: &[u32]) -> f64 {
    let mut centre = Vector::zeros();
    for &f in faces {
        for &v in &mesh.triangles[f as usize] {
            centre += mesh.positions[v as usize].coords;
        }
    }
    let centre = Point::from(centre / (3 * faces.len()).max(1) as f64);
    faces
        .iter()
        .map(|&f| {
            let [a, b, c] = mesh.triangle_points(f as usize).map(|p| p - centre);
            a.dot(&b.cross(&c))
        })
        .sum()
}

/// Unit normals of a point cloud: the least-variance direction of each point's
/// neighbourhood, with signs made consistent along a minimum spanning tree whose edge
/// weights are `1 - |n_i . n_j|` (Hoppe et al. 1992), starting from the point farthest
/// from the centroid with its normal pointing away from the centroid.
fn point_cloud_normals(points: &[Point]) -> Vec<Vector> {
    let tree = KdTree::new(points);
    let neighbourhoods: Vec<Vec<usize>> = points
        .par_iter()
        .map(|p| tree.k_nearest(p, POINT_CLOUD_NEIGHBOURS).into_iter().map(|n| n.index).collect())
        .collect();
    let mut normals: Vec<Vector> = neighbourhoods
        .par_iter()
        .map(|neighbours| {
            let count = neighbours.len().max(1) as f64;
            let mean = neighbours.iter().fold(Vector::zeros(), |s, &i| s + points[i].coords) / count;
            let covariance = neighbours.iter().fold(Matrix3::zeros(), |s, &i| {
                let d = points[i].coords - mean;
                s + d * d.transpose()
            });
            let eigen = SymmetricEigen::new(covariance);
            eigen.eigenvectors.column(eigen.eigenvalues.imin()).into_owned()
        })
        .collect();
    let centroid = points.iter().fold(Vector::zeros(), |s, p| s + p.coords) / points.len() as f64;
    let mut visited = vec![false; points.len()];
    for start in 0..points.len() {
        if visited[start] {
            continue;
        }
        // Each neighbourhood-connected piece starts at its point farthest from the centroid.
        let piece = reachable(&neighbourhoods, start);
        let seed = *piece
            .iter()
            .filter(|&&p| !visited[p])
            .max_by(|&&a, &&b| (points[a].coords - centroid).norm().total_cmp(&(points[b].coords - centroid).norm()))
            .unwrap_or(&start);
        if normals[seed].dot(&(points[seed].coords - centroid)) < 0.0 {
            normals[seed] = -normals[seed];
        }
        let mut heap = BinaryHeap::new();
        visited[seed] = true;
        push_neighbours(&mut heap, &neighbourhoods, &normals, seed);
        while let Some(Candidate { point, from, .. }) = heap.pop() {
            if visited[point] {
                continue;
            }
            visited[point] = true;
            if normals[point].dot(&normals[from]) < 0.0 {
                normals[point] = -normals[point];
            }
            push_neighbours(&mut heap, &neighbourhoods, &normals, point);
        }
    }
    normals
}

fn reachable(neighbourhoods: &[Vec<usize>], start: usize) -> Vec<usize> {
    let mut seen = std::collections::HashSet::from([start]);
    let mut stack = vec![start];
    let mut piece = Vec::new();
    while let Some(p) = stack.pop() {
        piece.push(p);
        for &q in &neighbourhoods[p] {
            if seen.insert(q) {
                stack.push(q);
            }
        }
    }
    piece
}

fn push_neighbours(heap: &mut BinaryHeap<Candidate>, neighbourhoods: &[Vec<usize>], normals: &[Vector], from: usize) {
    for &point in &neighbourhoods[from] {
        let weight = 1.0 - normals[point].dot(&normals[from]).abs();
        heap.push(Candidate { weight, point, from });
    }
}

/// An edge of the spanning tree under construction; the heap pops the lowest weight.
struct Candidate {
    weight: f64,
    point: usize,
    from: usize,
}

impl PartialEq for Candidate {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl Eq for Candidate {}
impl PartialOrd for Candidate {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Candidate {
    fn cmp(&self, other: &Self) -> Ordering {
        other.weight.total_cmp(&self.weight).then_with(|| other.point.cmp(&self.point))
    }
}
