//! Normal lines: the straight line through each vertex along its normal (Wilczek et al.
//! 2018, section 2.2, the lines `n_i` of equation (1)). On a surface of revolution every
//! such line meets the axis; every estimator of `orient` works on these lines.

use crate::mesh::normal_filter::freed_of_roughness;
use crate::mesh::normals::{compute_vertex_normals, vertex_areas, NormalWeighting};
use crate::mesh::{Mesh, Point, Vector};
use crate::{Error, Result};

/// A set of weighted normal lines, stored as flat arrays for speed.
#[derive(Clone, Debug, Default)]
pub struct NormalLines {
    /// A point of each line (the vertex).
    pub points: Vec<Point>,
    /// Unit direction of each line (the vertex normal).
    pub directions: Vec<Vector>,
    /// Weight of each line: the vertex's share of surface area for meshes (so that dense
    /// and sparse parts of a scan count by area, not by vertex count), 1 for point clouds.
    pub weights: Vec<f64>,
    /// Index of the vertex each line comes from in the mesh it was built from.
    pub vertex_indices: Vec<usize>,
}

impl NormalLines {
    /// Number of lines.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// True when there are no lines.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Lines of a mesh: face-area-weighted vertex normals when it has faces (the normals
    /// stored in the mesh are ignored then: they may predate smoothing, and scanners'
    /// normals are often noisier than the geometry), the stored normals with unit weights
    /// for a point cloud.
    pub fn from_mesh(mesh: &Mesh) -> Result<Self> {
        Self::from_mesh_with(mesh, |normals, _| normals)
    }

    /// [`NormalLines::from_mesh`], a mesh's normals freed of the scan's roughness as far
    /// as their scatter calls for ([`crate::mesh::normal_filter`]): the lines the
    /// automatic orientation reads the axis off.
    pub fn from_mesh_freed_of_roughness(mesh: &Mesh) -> Result<Self> {
        Self::from_mesh_with(mesh, |normals, weights| freed_of_roughness(mesh, normals, weights).normals)
    }

    /// The lines of `mesh`, a mesh's face normals passed through `adjust` (given the
    /// vertices' areas) first.
    fn from_mesh_with(mesh: &Mesh, adjust: impl FnOnce(Vec<Vector>, &[f64]) -> Vec<Vector>) -> Result<Self> {
        mesh.validate()?;
        if mesh.positions.is_empty() {
            return Err(Error::DegenerateGeometry("the mesh has no vertices".into()));
        }
        let (normals, weights) = if mesh.is_point_cloud() {
            let normals = mesh.normals.clone().ok_or_else(|| {
                Error::InvalidArgument("a point cloud without normals cannot be oriented: give normals or faces".into())
            })?;
            (normals, vec![1.0; mesh.vertex_count()])
        } else {
            let weights = vertex_areas(mesh);
            (adjust(compute_vertex_normals(mesh, NormalWeighting::Area), &weights), weights)
        };
        let mut lines = NormalLines::default();
        for (i, (normal, weight)) in normals.iter().zip(&weights).enumerate() {
            let length = normal.norm();
            if !(length > 1e-12) || !(*weight > 0.0) {
                continue; // unreferenced vertex or zero normal: no line
            }
            lines.push(mesh.positions[i], normal / length, *weight, i);
        }
        if lines.is_empty() {
            return Err(Error::DegenerateGeometry("no vertex has a usable normal".into()));
        }
        Ok(lines)
    }

    /// Appends a line.
    pub fn push(&mut self, point: Point, direction: Vector, weight: f64, vertex_index: usize) {
        self.points.push(point);
        self.directions.push(direction);
        self.weights.push(weight);
        self.vertex_indices.push(vertex_index);
    }

    /// The lines whose index `keep` accepts.
    pub fn filtered(&self, keep: impl Fn(usize) -> bool) -> Self {
        let mut out = NormalLines::default();
        for i in 0..self.len() {
            if keep(i) {
                out.push(self.points[i], self.directions[i], self.weights[i], self.vertex_indices[i]);
            }
        }
        out
    }

    /// Weighted centroid of the points.
    pub fn centroid(&self) -> Point {
        let total: f64 = self.weights.iter().sum();
        let sum = self.points.iter().zip(&self.weights).fold(Vector::zeros(), |s, (p, w)| s + p.coords * *w);
        Point::from(sum / total.max(f64::MIN_POSITIVE))
    }

    /// Root-mean-square distance of the points to their centroid: the length scale that
    /// tolerances are expressed in.
    pub fn size_mm(&self) -> f64 {
        let c = self.centroid();
        let total: f64 = self.weights.iter().sum();
        let sum: f64 = self.points.iter().zip(&self.weights).map(|(p, w)| (p - c).norm_squared() * w).sum();
        (sum / total.max(f64::MIN_POSITIVE)).sqrt()
    }
}

