//! The fragment as the refinement criteria see it (Wilczek et al. 2018, section 2.3):
//! its vertices in the frame of the start axis, split into the inner and outer skins,
//! and the horizontal sections (planes perpendicular to a candidate axis) and vertical
//! sections (angular sectors about it) the criteria are defined on.
//!
//! Horizontal sections of a mesh are exact plane cuts of its triangles, each cut segment
//! weighted by its length, so that a criterion is a continuous function of the axis (a
//! slab of vertices gains and loses points as the axis turns, which makes the objective
//! jump). Point clouds without faces fall back to slabs of vertices.

use nalgebra::{Isometry3, Rotation3, Vector2};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::mesh::topology::{Topology, UnionFind};
use crate::mesh::{planar_length, Mesh, Point, Vector};
use crate::orient::Axis;
use crate::statistics::quantile;
use crate::{Error, Result};

/// Skin triangles cut by one task of [`PreparedSurface::horizontal_sections`]: small
/// meshes stay in one or two tasks.
const TRIANGLES_PER_TASK: usize = 16_384;
/// Fewest skin triangles for which an evaluation's steps run on the thread pool. Each
/// parallel step hands its work to the pool and waits for it to come back; on a 20k-face
/// body sherd (2 cores) those hand-overs took more than half of an evaluation (kernel
/// scheduling under `perf`): cutting its sections took 452 us in parallel and 189 us on
/// one thread, and the circles refinement 360 ms against 150. On 2 cores one thread was
/// still 10-15% faster at 95k and 193k skin triangles, where more cores would win.
const PARALLEL_MIN_SKIN_TRIANGLES: usize = 4 * TRIANGLES_PER_TASK;

/// Which skin of the fragment a criterion uses (the paper's "surface choice").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
pub enum Surface {
    /// The inside of the vessel (normals towards the axis).
    Inner,
    /// The outside of the vessel (normals away from the axis).
    Outer,
    /// Both skins, each section of each skin treated on its own.
    #[default]
    Both,
}

/// The skin one vertex belongs to: the orientation's segmentation names it. Here a vertex
/// off the skins is `None` rather than `Some(Skin::Other)`, which the refinement never
/// assigns.
pub use crate::orient::Skin;

impl Surface {
    /// Whether `skin` is used under this choice.
    pub fn includes(self, skin: Skin) -> bool {
        matches!(
            (self, skin),
            (Surface::Both, Skin::Inner | Skin::Outer) | (Surface::Inner, Skin::Inner) | (Surface::Outer, Skin::Outer)
        )
    }
}

/// The smallest radial component of a unit normal for a vertex to count as skin: below
/// it the surface is closer to horizontal (rim top, base bottom, horizontal break).
const MIN_RADIAL_NORMAL: f64 = 0.35;
/// The largest tangential component: above it the normal line misses the axis by more
/// than half the radius (Eq. 1), as on fracture faces running along the profile.
const MAX_TANGENTIAL_NORMAL: f64 = 0.5;

/// A candidate axis as four parameters in the start frame: turns `tilt_x_rad` about x
/// and `tilt_y_rad` about y of the start direction (+z), and the point where the axis
/// crosses z = 0, `(shift_x_mm, shift_y_mm)`. The start axis is all zeros.
pub type AxisParameters = [f64; 4];

/// The rigid motion from the start frame to the frame of a candidate axis.
#[derive(Clone, Copy, Debug)]
pub struct CandidateFrame {
    rotation: Rotation3<f64>,
    shift: Vector,
}

impl CandidateFrame {
    /// The frame of the candidate `parameters`.
    pub fn new(parameters: &AxisParameters) -> Self {
        let rotation = Rotation3::from_axis_angle(&Vector::y_axis(), parameters[1])
            * Rotation3::from_axis_angle(&Vector::x_axis(), parameters[0]);
        CandidateFrame { rotation, shift: Vector::new(parameters[2], parameters[3], 0.0) }
    }

    /// The candidate axis's direction in the start frame.
    pub fn direction(&self) -> Vector {
        self.rotation * Vector::z()
    }

    /// A start-frame point in the candidate frame (axis on z).
    pub fn apply(&self, p: &Point) -> Point {
        Point::from(self.rotation.inverse_transform_vector(&(p.coords - self.shift)))
    }

    /// The height of a start-frame point in the candidate frame: [`CandidateFrame::apply`]'s
    /// `z` alone, computed the same way (the third column of the rotation dotted with the
    /// shifted point), for searches that compare heights of many points.
    #[inline]
    pub fn height(&self, p: &Point) -> f64 {
        self.rotation.matrix().column(2).dot(&(p.coords - self.shift))
    }

    /// A candidate-frame point back in the start frame.
    pub fn to_start(&self, p: &Point) -> Point {
        Point::from(self.rotation * p.coords + self.shift)
    }

    /// A start-frame vector in the candidate frame.
    pub fn apply_vector(&self, v: &Vector) -> Vector {
        self.rotation.inverse_transform_vector(v)
    }

    /// A candidate-frame vector back in the start frame.
    pub fn vector_to_start(&self, v: &Vector) -> Vector {
        self.rotation * v
    }
}

/// The tilts `[about x, about y]` of [`CandidateFrame::new`] whose axis runs along
/// `direction` (start frame, pointing up, any length).
pub fn tilts_along(direction: &Vector) -> [f64; 2] {
    // direction = Ry(b) Rx(a) z = (sin b cos a, -sin a, cos b cos a)
    let norm = direction.norm();
    [(-direction.y / norm).clamp(-1.0, 1.0).asin(), direction.x.atan2(direction.z)]
}

/// The parameters of the axis with tilts `tilts` through the point `centre` at height
/// `height_mm` of the candidate frame with those tilts and no shift.
pub fn axis_through(tilts: [f64; 2], centre: [f64; 2], height_mm: f64) -> AxisParameters {
    let frame = CandidateFrame::new(&[tilts[0], tilts[1], 0.0, 0.0]);
    let direction = frame.direction();
    let on_axis = frame.to_start(&Point::new(centre[0], centre[1], height_mm));
    let crossing = on_axis + direction * (-on_axis.z / direction.z);
    [tilts[0], tilts[1], crossing.x, crossing.y]
}

/// One horizontal section of one skin: points of the cut in the candidate frame's
/// xy-plane, with weights (cut segment lengths, or 1 per vertex in a slab).
#[derive(Clone, Debug, Default)]
pub struct HorizontalSection {
    /// Height of the plane in the candidate frame, millimetres.
    pub height_mm: f64,
    /// The skin cut.
    pub skin: Option<Skin>,
    /// Points of the cut, `[x, y]` in the candidate frame.
    pub points: Vec<[f64; 2]>,
    /// One positive weight per point.
    pub weights: Vec<f64>,
}

impl HorizontalSection {
    /// The preserved arc of the section about the candidate axis, radians: the full turn
    /// minus the largest angular gap between its points.
    pub fn sector_angle_rad(&self) -> f64 {
        sector_angle_rad(self.points.iter().map(|p| p[1].atan2(p[0])).collect())
    }
}

/// The largest gap between consecutive `angles` (radians, in `[-pi, pi]`) around the
/// circle, and the angle that ends it: the wrap-around gap from the largest angle to the
/// smallest unless a gap between neighbours is strictly larger, the first such in
/// increasing order. The same two numbers, bit for bit, as a scan of the sorted angles.
///
/// Without sorting (the measurements cut a 100k-vertex scan into vertical sections once
/// per bootstrap replicate): the angles go to as many buckets as there are angles, equal
/// widths between the least and the greatest. A gap inside a bucket is at most its width;
/// the largest gap between neighbours is at least the range over the count less one, so,
/// where it exceeds a bucket's width, it lies between the greatest angle of one non-empty
/// bucket and the least of the next, and bucket order is angle order. Where rounding could
/// blur that (few angles, a gap no wider than a bucket), or an angle is not a number, the
/// angles are sorted.
pub(crate) fn largest_angular_gap(angles: &[f64]) -> (f64, f64) {
    let by_sorting = || largest_angular_gap_sorted(angles);
    let count = angles.len();
    if count < 64 || angles.iter().any(|a| a.is_nan()) {
        return by_sorting();
    }
    let low = angles.iter().copied().fold(f64::INFINITY, f64::min);
    let high = angles.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let width = (high - low) / count as f64;
    if !(width > 0.0) {
        return by_sorting();
    }
    // Least and greatest angle per bucket (empty: +inf, -inf).
    let mut buckets = vec![(f64::INFINITY, f64::NEG_INFINITY); count];
    for &a in angles {
        let bucket = (((a - low) / width) as usize).min(count - 1);
        let entry = &mut buckets[bucket];
        entry.0 = entry.0.min(a);
        entry.1 = entry.1.max(a);
    }
    let mut start = low;
    let mut largest_gap = low + std::f64::consts::TAU - high;
    let mut widest_between = 0.0f64;
    let mut previous_high: Option<f64> = None;
    for &(least, greatest) in buckets.iter().filter(|b| b.0 <= b.1) {
        if let Some(previous) = previous_high {
            let gap = least - previous;
            widest_between = widest_between.max(gap);
            if gap > largest_gap {
                largest_gap = gap;
                start = least;
            }
        }
        previous_high = Some(greatest);
    }
    // Gaps inside buckets were not looked at: they are at most `width`.
    if widest_between <= width { by_sorting() } else { (start, largest_gap) }
}

/// [`largest_angular_gap`] by a scan of the sorted angles (at least one).
fn largest_angular_gap_sorted(angles: &[f64]) -> (f64, f64) {
    let mut sorted = angles.to_vec();
    sorted.sort_unstable_by(f64::total_cmp);
    let mut start = sorted[0];
    let mut largest_gap = sorted[0] + std::f64::consts::TAU - sorted[sorted.len() - 1];
    for w in sorted.windows(2) {
        if w[1] - w[0] > largest_gap {
            largest_gap = w[1] - w[0];
            start = w[1];
        }
    }
    (start, largest_gap)
}

/// The full turn minus the largest gap between the given angles (radians, within one turn).
pub fn sector_angle_rad(angles: Vec<f64>) -> f64 {
    if angles.len() < 2 {
        return 0.0;
    }
    std::f64::consts::TAU - largest_angular_gap(&angles).1
}

/// The fragment prepared for refinement around a start axis.
#[derive(Clone, Debug)]
pub struct PreparedSurface {
    /// The start axis, its point moved level with the fragment's centroid.
    pub start_axis: Axis,
    /// Scan frame to start frame (start axis on z, centroid at height 0).
    pub start_frame: Isometry3<f64>,
    /// All vertices in the start frame.
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
}

/// Vertex normals: the mesh's own, or area-weighted face normals when it has none.
fn vertex_normals(mesh: &Mesh) -> Result<Vec<Vector>> {
    if let Some(normals) = &mesh.normals {
        return Ok(normals.clone());
    }
    if mesh.triangles.is_empty() {
        return Err(Error::InvalidArgument(
            "refinement needs vertex normals or faces to tell the inner from the outer skin; the point cloud has neither"
                .into(),
        ));
    }
    let mut normals = vec![Vector::zeros(); mesh.positions.len()];
    for (face, triangle) in mesh.triangles.iter().enumerate() {
        let n = mesh.face_normal_scaled(face);
        for &v in triangle {
            normals[v as usize] += n;
        }
    }
    Ok(normals.into_iter().map(|n| n.try_normalize(1e-300).unwrap_or_else(Vector::zeros)).collect())
}

/// The skin of one vertex from its normal alone (the paper's test, section 2.2.1): outer
/// when the normal points away from the axis, inner when towards it; `None` when the
/// normal is closer to horizontal-tangential or vertical than the limits allow.
fn skin_by_normal(p: &Point, n: &Vector) -> Option<Skin> {
    let radial = Vector2::new(p.x, p.y).try_normalize(1e-9)?;
    let radial_component = n.x * radial.x + n.y * radial.y;
    let tangential_component = -n.x * radial.y + n.y * radial.x;
    if tangential_component.abs() > MAX_TANGENTIAL_NORMAL || radial_component.abs() < MIN_RADIAL_NORMAL {
        return None;
    }
    Some(if radial_component > 0.0 { Skin::Outer } else { Skin::Inner })
}

/// Adjacent faces whose normals differ by less than this belong to one smooth region.
const SMOOTH_REGION_ANGLE_DEG: f64 = 35.0;
/// A smooth region is a skin when its area is at least this share of the largest region's.
const MIN_SKIN_REGION_SHARE: f64 = 0.1;

/// Skins of a mesh (vertices in the start frame): the mesh is cut into smooth regions
/// along sharp edges (the fracture faces and a flat lip meet the skins at about 90
/// degrees), the large regions are skins, and each skin region is inner or outer by the
/// area-weighted majority of its normals. Testing each vertex's normal alone, as the
/// paper does, takes the break faces of a sloping wall for skin (their normals run along
/// the meridian, towards or away from the axis) and the inside of an everted lip for
/// outer skin; a region keeps the side of its majority.
fn skins_by_smooth_regions(mesh: &Mesh, points: &[Point]) -> Vec<Option<Skin>> {
    let face_normals: Vec<Vector> = mesh
        .triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| points[v as usize]);
            (b - a).cross(&(c - a))
        })
        .collect();
    // A region never crosses a face that is neither skin by its own normal (a rounded
    // rim, a horizontal break): at fine resolution a rounded lip turns so gradually that
    // neighbouring faces differ by a degree or two, and the inner and outer skins would
    // join through it into one region whose radial normals cancel out.
    let face_skins: Vec<Option<Skin>> = mesh
        .triangles
        .iter()
        .zip(&face_normals)
        .map(|(t, n)| {
            let centre = Point::from(t.iter().map(|&v| points[v as usize].coords).sum::<Vector>() / 3.0);
            skin_by_normal(&centre, &n.try_normalize(1e-300)?)
        })
        .collect();
    let cosine_limit = SMOOTH_REGION_ANGLE_DEG.to_radians().cos();
    let topology = Topology::new(mesh);
    let mut regions = UnionFind::new(mesh.triangles.len());
    for edge in 0..topology.edge_count() {
        // Faces come in increasing order: each later face is compared with the first.
        let (&other, later) = match topology.faces_of_edge(edge).split_first() {
            Some(split) => split,
            None => continue,
        };
        let other = other as usize;
        for &face in later {
            let face = face as usize;
            let (n, m) = (face_normals[face], face_normals[other]);
            let norms = n.norm() * m.norm();
            let same_skin = face_skins[face].is_some() && face_skins[face] == face_skins[other];
            if same_skin && norms > 0.0 && n.dot(&m) >= cosine_limit * norms {
                regions.union(face, other);
            }
        }
    }
    // Per region, indexed by its root face.
    let mut region_area = vec![0.0; mesh.triangles.len()];
    let mut region_radial = vec![0.0; mesh.triangles.len()];
    let roots: Vec<usize> = (0..mesh.triangles.len()).map(|f| regions.find(f)).collect();
    for (face, t) in mesh.triangles.iter().enumerate() {
        let n = face_normals[face];
        let centre = (points[t[0] as usize].coords + points[t[1] as usize].coords + points[t[2] as usize].coords) / 3.0;
        let radial = Vector2::new(centre.x, centre.y).try_normalize(1e-9).unwrap_or_else(Vector2::zeros);
        // |n| is twice the area: the radial component is area-weighted as it stands.
        region_radial[roots[face]] += n.x * radial.x + n.y * radial.y;
        region_area[roots[face]] += n.norm();
    }
    let largest = region_area.iter().copied().fold(0.0, f64::max);
    let region_skin = |region: usize| -> Option<Skin> {
        let area = region_area[region];
        let radial = region_radial[region] / area.max(1e-300);
        if area < MIN_SKIN_REGION_SHARE * largest || radial.abs() < 0.2 {
            return None;
        }
        Some(if radial > 0.0 { Skin::Outer } else { Skin::Inner })
    };
    let mut skins: Vec<Option<Option<Skin>>> = vec![None; points.len()];
    for (face, t) in mesh.triangles.iter().enumerate() {
        let skin = region_skin(roots[face]);
        for &v in t {
            let entry = &mut skins[v as usize];
            *entry = match *entry {
                None => Some(skin),
                Some(previous) if previous == skin => Some(skin),
                // A vertex on the border of two regions belongs to neither.
                Some(_) => Some(None),
            };
        }
    }
    skins.into_iter().map(Option::flatten).collect()
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
        })
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

    /// The horizontal sections of the chosen skins under a candidate frame.
    pub fn horizontal_sections(&self, frame: &CandidateFrame) -> Vec<HorizontalSection> {
        let skins: &[Skin] = match self.surface {
            Surface::Inner => &[Skin::Inner],
            Surface::Outer => &[Skin::Outer],
            Surface::Both => &[Skin::Inner, Skin::Outer],
        };
        let mut sections: Vec<HorizontalSection> = skins
            .iter()
            .flat_map(|&skin| {
                self.section_heights_mm.iter().map(move |&h| HorizontalSection {
                    height_mm: h,
                    skin: Some(skin),
                    ..Default::default()
                })
            })
            .collect();
        let count = self.section_heights_mm.len();
        let slot = |skin: Skin| if skins.len() == 2 && skin == Skin::Outer { count } else { 0 };
        let heights = &self.section_heights_mm;
        if self.has_faces() {
            // Every evaluation of a criterion moves all skin vertices and cuts all skin
            // triangles: on a large scan this is the whole cost of refinement, so it runs
            // on all cores, over contiguous runs of triangles whose cuts are appended in
            // their order (the sections are the same, point for point, as in one pass).
            // Each moved vertex carries the number of planes at or below it, so that the
            // planes a triangle crosses are the range between its corners' counts, and
            // the many triangles between two planes are passed over on three integers.
            // The moved vertices and their counts are kept apart: most triangles lie
            // between two planes and are passed over on their corners' counts alone
            // (4 bytes each, where a moved point takes 24), the points read only for
            // the triangles that are cut. Vertices off the skins are never read.
            // Below [`PARALLEL_MIN_SKIN_TRIANGLES`] it all runs on the calling thread.
            let parallel = self.skin_triangles.len() > PARALLEL_MIN_SKIN_TRIANGLES;
            let move_vertex = |(p, s): (&Point, &Option<Skin>)| if s.is_some() { frame.apply(p) } else { Point::origin() };
            let moved: Vec<Point> = if parallel {
                self.points.par_iter().zip(self.skins.par_iter()).map(move_vertex).collect()
            } else {
                self.points.iter().zip(&self.skins).map(move_vertex).collect()
            };
            let locate = PlaneLocator::new(heights);
            // Vertices off the skins are in no skin triangle: their rank is never read.
            let rank = |(q, s): (&Point, &Option<Skin>)| if s.is_some() { locate.planes_at_or_below(q.z) as u32 } else { 0 };
            let ranks: Vec<u32> = if parallel {
                moved.par_iter().zip(self.skins.par_iter()).map(rank).collect()
            } else {
                moved.iter().zip(&self.skins).map(rank).collect()
            };
            let cut_run = |run: &[([u32; 3], Skin)]| {
                // Room for a cut per four triangles spares most regrowths (they were
                // 5% of a 200k-face rim sherd's time under `perf record`).
                let mut cuts = Vec::with_capacity(run.len() / 4);
                for (triangle, skin) in run {
                    let ranks = triangle.map(|v| ranks[v as usize]);
                    let first_crossed = ranks[0].min(ranks[1]).min(ranks[2]) as usize;
                    let past_crossed = ranks[0].max(ranks[1]).max(ranks[2]) as usize;
                    if first_crossed == past_crossed {
                        continue;
                    }
                    // Plane `index` is crossed when one corner lies below it (count <=
                    // index) and one at or above it (count > index).
                    let corners = triangle.map(|v| moved[v as usize]);
                    for (index, &h) in heights.iter().enumerate().take(past_crossed).skip(first_crossed) {
                        if let Some((a, b)) = cut_triangle(&corners, h) {
                            let length = planar_length(a[0] - b[0], a[1] - b[1]);
                            if length > 0.0 {
                                cuts.push((slot(*skin) + index, [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0], length));
                            }
                        }
                    }
                }
                cuts
            };
            let cuts: Vec<Vec<(usize, [f64; 2], f64)>> = if parallel {
                self.skin_triangles.par_chunks(TRIANGLES_PER_TASK).map(cut_run).collect()
            } else {
                vec![cut_run(&self.skin_triangles)]
            };
            let mut cut_counts = vec![0usize; sections.len()];
            for (section_index, _, _) in cuts.iter().flatten() {
                cut_counts[*section_index] += 1;
            }
            for (section, &count) in sections.iter_mut().zip(&cut_counts) {
                section.points.reserve_exact(count);
                section.weights.reserve_exact(count);
            }
            for (section_index, point, length) in cuts.into_iter().flatten() {
                let section = &mut sections[section_index];
                section.points.push(point);
                section.weights.push(length);
            }
        } else {
            let half = self.slab_half_thickness_mm;
            for (p, skin) in self.skin_points_in(frame) {
                // Only the planes about `p.z` can hold it (the slabs are thinner than the
                // spacing); one plane of margin on each side, the exact test decides.
                let nearest = heights.partition_point(|&h| h < p.z - half).saturating_sub(1);
                let past = (heights.partition_point(|&h| h <= p.z + half) + 1).min(count);
                for (index, h) in heights.iter().enumerate().take(past).skip(nearest) {
                    if (p.z - h).abs() <= half {
                        let section = &mut sections[slot(skin) + index];
                        section.points.push([p.x, p.y]);
                        section.weights.push(1.0);
                    }
                }
            }
        }
        sections
    }
}

/// Counts the section planes at or below a height: a triangle's corners with counts
/// `i < j` lie on either side of planes `i..j` and of no other.
struct PlaneLocator<'a> {
    /// Plane heights, ascending.
    heights: &'a [f64],
    /// Planes per millimetre when they are evenly spaced (as `PreparedSurface::new`
    /// places them), 0 otherwise.
    planes_per_mm: f64,
}

impl<'a> PlaneLocator<'a> {
    fn new(heights: &'a [f64]) -> Self {
        let span = match heights {
            [first, .., last] => last - first,
            _ => 0.0,
        };
        let planes_per_mm = if span > 0.0 && span.is_finite() { (heights.len() - 1) as f64 / span } else { 0.0 };
        PlaneLocator { heights, planes_per_mm }
    }

    /// The number of planes at or below `z`, exactly `heights.partition_point(|&h| h <= z)`.
    /// Evenly spaced planes give the count from the spacing and a step or two of
    /// correction against the heights themselves (a binary search per vertex and per
    /// evaluation was a fifth of the refinement's time); any other spacing searches.
    fn planes_at_or_below(&self, z: f64) -> usize {
        let heights = self.heights;
        if self.planes_per_mm == 0.0 || !z.is_finite() {
            return heights.partition_point(|&h| h <= z);
        }
        // Truncation after the clamp is the floor (`f64::floor` is a call into libm
        // on the baseline target); the loops below make any estimate exact.
        let estimate = (z - heights[0]) * self.planes_per_mm + 1.0;
        let mut count = estimate.clamp(0.0, heights.len() as f64) as usize;
        while count > 0 && heights[count - 1] > z {
            count -= 1;
        }
        while count < heights.len() && heights[count] <= z {
            count += 1;
        }
        count
    }
}

/// The segment where the plane z = `height` cuts a triangle, if it does.
fn cut_triangle(corners: &[Point; 3], height: f64) -> Option<([f64; 2], [f64; 2])> {
    let mut crossings: [[f64; 2]; 2] = [[0.0; 2]; 2];
    let mut found = 0;
    for i in 0..3 {
        let (p, q) = (corners[i], corners[(i + 1) % 3]);
        // Half-open test so that a plane through a vertex counts it once.
        if (p.z < height) != (q.z < height) {
            let t = (height - p.z) / (q.z - p.z);
            if found < 2 {
                crossings[found] = [p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)];
            }
            found += 1;
        }
    }
    (found == 2).then_some((crossings[0], crossings[1]))
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

/// Vertical sections (angular sectors about the candidate axis) of the given points:
/// `count` sectors spanning the preserved arc, each the list of indices into `points`.
pub fn vertical_sections(points: &[Point], count: usize) -> Vec<Vec<usize>> {
    if points.is_empty() || count == 0 {
        return Vec::new();
    }
    let angles: Vec<f64> = points.iter().map(|p| p.y.atan2(p.x)).collect();
    // Measure angles from the start of the preserved arc so that the arc does not wrap.
    let (start, largest_gap) = largest_angular_gap(&angles);
    let span = (std::f64::consts::TAU - largest_gap).max(1e-12);
    let mut sections = vec![Vec::new(); count];
    for (i, a) in angles.iter().enumerate() {
        let offset = (a - start).rem_euclid(std::f64::consts::TAU);
        let index = ((offset / span * count as f64) as usize).min(count - 1);
        sections[index].push(i);
    }
    sections
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

    /// Every skin triangle cut by every plane, or every skin vertex tested against every
    /// slab: what `horizontal_sections` must give, point for point, bit for bit.
    fn sections_by_brute_force(surface: &PreparedSurface, frame: &CandidateFrame) -> Vec<(usize, [f64; 2], f64)> {
        let count = surface.section_heights_mm.len();
        let slot = |skin: Skin| if surface.surface == Surface::Both && skin == Skin::Outer { count } else { 0 };
        let mut cuts = Vec::new();
        if surface.has_faces() {
            for (triangle, skin) in &surface.skin_triangles {
                let corners = triangle.map(|v| frame.apply(&surface.points[v as usize]));
                for (index, &h) in surface.section_heights_mm.iter().enumerate() {
                    if let Some((a, b)) = cut_triangle(&corners, h) {
                        let length = planar_length(a[0] - b[0], a[1] - b[1]);
                        if length > 0.0 {
                            cuts.push((slot(*skin) + index, [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0], length));
                        }
                    }
                }
            }
        } else {
            for (p, skin) in surface.skin_points_in(frame) {
                for (index, h) in surface.section_heights_mm.iter().enumerate() {
                    if (p.z - h).abs() <= surface.slab_half_thickness_mm {
                        cuts.push((slot(skin) + index, [p.x, p.y], 1.0));
                    }
                }
            }
        }
        // Sections collect their points in triangle (vertex) order: a stable sort by
        // section keeps that order within each.
        cuts.sort_by_key(|&(index, _, _)| index);
        cuts
    }

    fn flattened(sections: &[HorizontalSection]) -> Vec<(usize, [f64; 2], f64)> {
        sections
            .iter()
            .enumerate()
            .flat_map(|(index, s)| s.points.iter().zip(&s.weights).map(move |(p, w)| (index, *p, *w)))
            .collect()
    }

    #[test]
    fn sections_cut_only_the_planes_they_reach_yet_equal_every_plane_against_every_triangle() {
        use crate::synth::{synthetic_sherd, SherdOptions, SherdPart};
        let sherd = synthetic_sherd(7, &SherdOptions { target_faces: 6_000, ..SherdOptions::for_part(SherdPart::Rim) });
        let mut cloud = sherd.mesh.clone();
        cloud.triangles.clear();
        let start = sherd.truth.axis;
        let candidates = [[0.0, 0.0, 0.0, 0.0], [0.03, -0.05, 1.5, -2.0], [-0.12, 0.09, -4.0, 3.0]];
        for (mesh, sections) in [(&sherd.mesh, None), (&cloud, Some(15)), (&sherd.mesh, Some(40))] {
            for surface_choice in [Surface::Both, Surface::Outer] {
                let surface = PreparedSurface::new(mesh, &start, surface_choice, sections).unwrap();
                for parameters in &candidates {
                    let frame = CandidateFrame::new(parameters);
                    let found = flattened(&surface.horizontal_sections(&frame));
                    let expected = sections_by_brute_force(&surface, &frame);
                    assert!(!expected.is_empty());
                    assert_eq!(found.len(), expected.len(), "faces: {}, {parameters:?}", surface.has_faces());
                    for (a, b) in found.iter().zip(&expected) {
                        let same = a.0 == b.0 && a.1.map(f64::to_bits) == b.1.map(f64::to_bits);
                        assert!(same && a.2.to_bits() == b.2.to_bits(), "{a:?} vs {b:?}");
                    }
                }
            }
        }
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

    #[test]
    fn plane_counts_from_the_spacing_equal_the_binary_search() {
        let even: Vec<f64> = (0..37).map(|i| -12.3 + 41.7 * i as f64 / 36.0).collect();
        let uneven = [-3.0, -1.0, 0.5, 0.5, 7.0];
        for heights in [&even[..], &uneven[..], &[2.0][..], &[][..]] {
            let locate = PlaneLocator::new(heights);
            let mut heights_and_between: Vec<f64> = heights.to_vec();
            heights_and_between.extend(heights.windows(2).map(|w| (w[0] + w[1]) / 2.0));
            heights_and_between.extend(heights.iter().flat_map(|&h| [h - 1e-12, h + 1e-12]));
            heights_and_between.extend([-1e9, 1e9, f64::NAN, f64::INFINITY, f64::NEG_INFINITY]);
            for z in heights_and_between {
                assert_eq!(locate.planes_at_or_below(z), heights.partition_point(|&h| h <= z), "{z} in {heights:?}");
            }
        }
    }

    #[test]
    fn largest_gap_from_buckets_equals_the_sorted_scan_bit_for_bit() {
        use rand::{Rng, SeedableRng};
        let sorted_scan = |angles: &[f64]| {
            let (start, largest) = largest_angular_gap_sorted(angles);
            (start.to_bits(), largest.to_bits())
        };
        let pi = std::f64::consts::PI;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        for case in 0..400 {
            let count = [64, 65, 100, 1000, 20_000][case % 5];
            let angles: Vec<f64> = match case % 4 {
                // An arc somewhere on the circle, across the +-pi seam for some.
                0 => {
                    let (from, length) = (rng.random_range(-pi..pi), rng.random_range(0.05..6.0));
                    (0..count).map(|_| (from + rng.random_range(0.0..length) + pi).rem_euclid(2.0 * pi) - pi).collect()
                }
                // The whole circle, evenly: gaps no wider than a bucket (the sorting path).
                1 => (0..count).map(|k| -pi + 2.0 * pi * k as f64 / count as f64).collect(),
                // Few distinct values, many repeated, two clusters.
                2 => (0..count).map(|k| if k % 3 == 0 { 0.25 } else { [1.0, 1.5, -2.0][k % 3] + (k % 7) as f64 * 1e-3 }).collect(),
                // Two arcs with gaps of the same width (ties go to the first).
                _ => (0..count).map(|k| if k % 2 == 0 { -2.0 + (k % 50) as f64 * 0.01 } else { 1.0 + (k % 50) as f64 * 0.01 }).collect(),
            };
            let (start, gap) = largest_angular_gap(&angles);
            assert_eq!((start.to_bits(), gap.to_bits()), sorted_scan(&angles), "case {case}");
        }
    }

    #[test]
    fn sector_angle_handles_wrap_around() {
        let angles = vec![3.0, -3.0, 3.1, -3.1];
        let sector = sector_angle_rad(angles);
        assert!((sector - (std::f64::consts::TAU - 6.0)).abs() < 1e-12, "{sector}");
    }
}
