//! The fragment prepared for refinement around a start axis: its points and normals in the
//! start frame, the skins they are on, and the heights of the horizontal sections.

use nalgebra::Isometry3;

use super::frame::{tilts_along, AxisParameters, CandidateFrame};
use super::memo::Memo;
use super::skins::{skin_by_normal, skins_by_smooth_regions, vertex_normals, Surface};
use crate::mesh::{Mesh, Point, Vector};
use crate::orient::{Axis, Skin};
use crate::statistics::quantile;
use crate::{Error, Result};

/// The fragment prepared for refinement around a start axis.
#[derive(Clone, Debug)]
pub struct PreparedSurface {
    /// The start axis, its point moved level with the fragment's centroid.
    pub start_axis: Axis,
    /// Scan frame to start frame (start axis on z, centroid at height 0).
    pub start_frame: Isometry3<f64>,
    /// All vertices in the start frame; unchanged after preparation, since what the
    /// criteria derive from them is kept ([`PreparedSurface::derived`]).
    pub points: Vec<Point>,
    /// Unit vertex normals in the start frame.
    pub normals: Vec<Vector>,
    /// The skin of each vertex under the chosen surface, `None` for other parts
    /// (fractures, rim top, base bottom) and for the skin not chosen.
    pub skins: Vec<Option<Skin>>,
    /// Triangles whose three vertices lie on one chosen skin.
    pub skin_triangles: Vec<([u32; 3], Skin)>,
    /// Heights of the horizontal sections in the start frame.
    pub section_heights_mm: Vec<f64>,
    /// Half the thickness of a slab of vertices when there are no faces.
    pub slab_half_thickness_mm: f64,
    /// The surface choice.
    pub surface: Surface,
    /// Mean edge length of the mesh, mm; `None` for a point cloud.
    pub mean_edge_mm: Option<f64>,
    /// What the criteria derive from `points` alone, made once ([`PreparedSurface::derived`]).
    memo: Memo,
}

impl PreparedSurface {
    /// Prepares `mesh` around `start` for `surface`, with `section_count` horizontal
    /// sections (`None`: as many as the mesh resolution allows, at least 12).
    pub fn new(mesh: &Mesh, start: &Axis, surface: Surface, section_count: Option<usize>) -> Result<Self> {
        if mesh.positions.len() < 10 {
            return Err(Error::DegenerateGeometry(format!(
                "refinement needs at least 10 vertices, the mesh has {}",
                mesh.positions.len()
            )));
        }
        let normals_scan = vertex_normals(mesh)?;
        let centroid = Point::from(
            mesh.positions.iter().map(|p| p.coords).sum::<Vector>() / mesh.positions.len() as f64,
        );
        let start_axis = start.normalized(&centroid);
        let start_frame = start_axis.to_oriented_frame(&centroid);
        let points: Vec<Point> = mesh.positions.iter().map(|p| start_frame * p).collect();
        let normals: Vec<Vector> = normals_scan.iter().map(|n| start_frame * n).collect();
        let skins: Vec<Option<Skin>> = if mesh.triangles.is_empty() {
            points.iter().zip(&normals).map(|(p, n)| skin_by_normal(p, n).filter(|&skin| surface.includes(skin))).collect()
        } else {
            // Both tests must agree: the regions drop break faces whose normals look like
            // skin, the normals drop what leaked into a skin region across a blunt edge.
            skins_by_smooth_regions(mesh, &points)
                .into_iter()
                .zip(points.iter().zip(&normals))
                .map(|(skin, (p, n))| skin.filter(|&skin| surface.includes(skin) && skin_by_normal(p, n) == Some(skin)))
                .collect()
        };
        let skin_triangles: Vec<([u32; 3], Skin)> = mesh
            .triangles
            .iter()
            .filter_map(|t| {
                let skin = skins[t[0] as usize]?;
                (skins[t[1] as usize] == Some(skin) && skins[t[2] as usize] == Some(skin)).then_some((*t, skin))
            })
            .collect();
        // Sections span the skins; a piece with (almost) no skin, such as a base with its
        // floor, keeps its sections over all its points for the criteria that need no skin.
        let mut heights: Vec<f64> = points.iter().zip(&skins).filter(|(_, s)| s.is_some()).map(|(p, _)| p.z).collect();
        if heights.len() < 10 {
            heights = points.iter().map(|p| p.z).collect();
        }
        let low = quantile(&mut heights, 0.05);
        let high = quantile(&mut heights, 0.95);
        let mean_edge_mm = mean_edge_length(mesh);
        let count = section_count.unwrap_or_else(|| {
            // A cut every two edge lengths keeps neighbouring sections independent.
            let edge = mean_edge_mm.unwrap_or((high - low) / 12.0);
            (((high - low) / (2.0 * edge)).floor() as usize).clamp(12, 60)
        });
        let count = count.max(1);
        let section_heights_mm: Vec<f64> = if count == 1 {
            vec![(low + high) / 2.0]
        } else {
            (0..count).map(|i| low + (high - low) * i as f64 / (count - 1) as f64).collect()
        };
        let slab_half_thickness_mm = ((high - low) / count as f64 / 2.0).max(1e-6);
        Ok(PreparedSurface {
            start_axis,
            start_frame,
            points,
            normals,
            skins,
            skin_triangles,
            section_heights_mm,
            slab_half_thickness_mm,
            surface,
            mean_edge_mm,
            memo: Memo::default(),
        })
    }

    /// The value of type `T` under `key` that `make` derives from [`PreparedSurface::points`]
    /// (and from `key`, nothing else), made on the first call and shared by the later
    /// ones and by copies of the surface. The points must not change after it is made.
    pub fn derived<T: std::any::Any + Send + Sync>(&self, key: u64, make: impl FnOnce() -> T) -> std::sync::Arc<T> {
        self.memo.get_or_make(key, make)
    }

    /// The candidate axis of `parameters` in the scan frame.
    pub fn axis_of(&self, parameters: &AxisParameters) -> Axis {
        let frame = CandidateFrame::new(parameters);
        let back = self.start_frame.inverse();
        let point = back * Point::new(parameters[2], parameters[3], 0.0);
        Axis::new(point, back * frame.direction())
    }

    /// The parameters of `axis` (scan frame) relative to the start frame.
    pub fn parameters_of(&self, axis: &Axis) -> AxisParameters {
        let direction = self.start_frame * axis.direction.into_inner();
        let direction = if direction.z < 0.0 { -direction } else { direction };
        let [tilt_x, tilt_y] = tilts_along(&direction);
        let point = self.start_frame * axis.point;
        let d = direction.normalize();
        let t = if d.z.abs() > 1e-12 { -point.z / d.z } else { 0.0 };
        let crossing = point + d * t;
        [tilt_x, tilt_y, crossing.x, crossing.y]
    }

    /// A copy keeping every k-th skin vertex on its skin (the others, and the triangles
    /// they touch, leave the skins), so that at most `count` remain; the copy itself when
    /// there are no more.
    pub fn with_skin_vertices_at_most(&self, count: usize) -> PreparedSurface {
        let skin_count = self.skin_vertex_count();
        if skin_count <= count {
            return self.clone();
        }
        let stride = skin_count.div_ceil(count.max(1));
        let mut thinned = self.clone();
        for (k, skin) in thinned.skins.iter_mut().filter(|skin| skin.is_some()).enumerate() {
            if k % stride != 0 {
                *skin = None;
            }
        }
        let skins = &thinned.skins;
        thinned.skin_triangles.retain(|(triangle, _)| triangle.iter().all(|&v| skins[v as usize].is_some()));
        thinned
    }

    /// The number of vertices on the chosen wall skins.
    pub fn skin_vertex_count(&self) -> usize {
        self.skins.iter().filter(|s| s.is_some()).count()
    }

    /// The share of the fragment's vertices on the chosen wall skins.
    pub fn wall_share(&self) -> f64 {
        self.skin_vertex_count() as f64 / self.points.len().max(1) as f64
    }

    /// Whether the fragment has faces (plane cuts) or only points (slabs).
    pub fn has_faces(&self) -> bool {
        !self.skin_triangles.is_empty()
    }

    /// Skin vertices in the candidate frame, with their skin.
    pub fn skin_points_in(&self, frame: &CandidateFrame) -> Vec<(Point, Skin)> {
        self.points.iter().zip(&self.skins).filter_map(|(p, s)| s.map(|skin| (frame.apply(p), skin))).collect()
    }
}

/// Mean length of the mesh's edges (each triangle's three), `None` without faces.
pub fn mean_edge_length(mesh: &Mesh) -> Option<f64> {
    if mesh.triangles.is_empty() {
        return None;
    }
    let total: f64 = mesh
        .triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
            (a - b).norm() + (b - c).norm() + (c - a).norm()
        })
        .sum();
    Some(total / (3 * mesh.triangles.len()) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parameters_round_trip_through_axes() {
        let mesh = Mesh::new(
            (0..20).map(|i| Point::new(50.0 * (i as f64 * 0.1).cos(), 50.0 * (i as f64 * 0.1).sin(), i as f64)).collect(),
            vec![],
        );
        let mut mesh = mesh;
        mesh.normals = Some(mesh.positions.iter().map(|p| Vector::new(p.x, p.y, 0.0).normalize()).collect());
        let start = Axis::new(Point::new(1.0, 2.0, 0.0), Vector::new(0.05, 0.0, 1.0));
        let prepared = PreparedSurface::new(&mesh, &start, Surface::Both, Some(5)).unwrap();
        let parameters = [0.03, -0.02, 1.5, -0.7];
        let axis = prepared.axis_of(&parameters);
        let back = prepared.parameters_of(&axis);
        for (a, b) in parameters.iter().zip(back) {
            assert!((a - b).abs() < 1e-9, "{parameters:?} vs {back:?}");
        }
        assert!(prepared.axis_of(&[0.0; 4]).line_angle_to_deg(&start) < 1e-9);
    }

    #[test]
    fn a_thinned_surface_keeps_every_kth_skin_vertex_and_only_whole_skin_triangles() {
        use crate::synth::{synthetic_sherd, SherdOptions, SherdPart};
        let sherd = synthetic_sherd(3, &SherdOptions { target_faces: 6_000, ..SherdOptions::for_part(SherdPart::Body) });
        let surface = PreparedSurface::new(&sherd.mesh, &sherd.truth.axis, Surface::Both, None).unwrap();
        let skin_count = surface.skin_vertex_count();
        assert!(skin_count > 2000, "{skin_count} skin vertices");
        let thinned = surface.with_skin_vertices_at_most(1000);
        let stride = skin_count.div_ceil(1000);
        assert_eq!(thinned.skin_vertex_count(), skin_count.div_ceil(stride), "of {skin_count}, every {stride}th");
        assert!(thinned.skin_vertex_count() <= 1000);
        // Kept vertices keep their skin; nothing joins a skin; the points are untouched.
        for (kept, original) in thinned.skins.iter().zip(&surface.skins) {
            assert!(kept.is_none() || kept == original);
        }
        assert_eq!(thinned.points, surface.points);
        assert!(thinned.skin_triangles.iter().all(|(t, skin)| t.iter().all(|&v| thinned.skins[v as usize] == Some(*skin))));
        assert_eq!(surface.with_skin_vertices_at_most(skin_count).skins, surface.skins);
    }
}
