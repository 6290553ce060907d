//! Quadric edge-collapse decimation (Garland and Heckbert 1997), as MeshLab's
//! "Quadric Edge Collapse Decimation" does it: every vertex carries the error quadric
//! ([`crate::mesh::quadric::Quadric`]) of its faces' planes (area weighted), edges are
//! collapsed cheapest first to the point minimising the sum of their endpoints'
//! quadrics, and a collapse is refused when it would change the topology (the link
//! condition of Dey et al. 1999), flip or fold a face (normal check), or it is
//! penalised when it creates slivers (MeshLab's quality threshold). Boundaries are kept
//! by quadrics of planes through each boundary edge perpendicular to its face (section
//! 6.1 of the paper), or frozen ([`BoundaryPolicy`]). Colours, normals and quality are
//! interpolated at the kept vertex's new place, with its barycentric coordinates in the
//! collapsed edge's face it falls most inside of (along the edge when it stays on it).
//!
//! Texture coordinates are per corner (wedges, as MeshLab keeps them), so a vertex on a
//! texture seam has one position and two or more UVs. A collapse moves each corner's UV
//! with the vertex: the new UV of a wedge is interpolated between the UVs the two
//! endpoints have in the same chart, read from the collapsed edge's own faces. A
//! collapse is refused when a moving vertex has a wedge the edge's faces do not reach
//! (it would drag a chart across a seam); seam vertices are placed like boundary
//! vertices (they stay on the seam polyline, which gets a boundary-like quadric), and
//! where three or more charts meet the vertex is kept in place.
//!
//! Speed: the orientation decimates 500k-face scans to about 20k faces first, so the
//! structures are flat arrays: per-vertex circular lists of face corners threaded
//! through one `next_corner` array, a binary heap of candidate edges with lazy
//! deletion (an entry is stale when either endpoint changed after it was pushed), and
//! no hash map. Candidates are re-evaluated when popped, since their neighbourhood
//! may have changed.
//!
//! Why not a crate: meshoptimizer's simplifier (the `meshopt` crate) was measured by an
//! earlier implementation to break topology on scans (non-manifold edges; its issue
//! tracker has such reports, e.g. zeux/meshoptimizer#699), has no link condition to
//! enable, and collapses onto existing vertices rather than the quadric's optimum.
//! It was not re-measured for this implementation.

use std::time::Instant;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::mesh::quadric::Quadric;
use crate::mesh::{Mesh, Point, Vector};
use crate::{Error, Result};

/// How boundary edges (edges with one face) are kept.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum BoundaryPolicy {
    /// Boundary vertices never move and are never removed (MeshLab's "Preserve
    /// Boundary"): the boundary stays exactly as it was, but keeps all its vertices.
    Fixed,
    /// Each boundary edge adds the quadric of the plane through it perpendicular to its
    /// face, weighted by `weight` times the squared edge length: boundary vertices may
    /// slide along the boundary but pay heavily for leaving it (Garland and Heckbert,
    /// section 6.1).
    Weighted {
        /// Relative weight of the boundary planes (face planes are weighted by area).
        weight: f64,
    },
}

/// Parameters of [`decimate_with_options`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DecimateOptions {
    /// Number of faces to reach. Each interior collapse removes two faces, a boundary
    /// one removes one, so the result has `target_faces` or one fewer, unless the
    /// topology or the boundary forbid further collapses (see the report).
    pub target_faces: usize,
    /// When set, decimation also stops once at most this many vertices remain
    /// (whichever target is reached first): the orientation asks for ~10k vertices.
    pub target_vertices: Option<usize>,
    /// How boundaries are kept.
    pub boundary: BoundaryPolicy,
    /// Collapses that turn any remaining face's normal by more than this, from its
    /// current or from its input direction, are refused; 90 degrees or more would
    /// allow flipped faces.
    pub max_normal_change_deg: f64,
    /// MeshLab's quality threshold: a collapse whose worst new triangle has a quality
    /// `q < threshold` (`q` = 1 for equilateral, 0 for degenerate; `4√3 area / Σ edge²`)
    /// has its cost multiplied by `threshold / q`. `None` ignores triangle shape.
    pub quality_threshold: Option<f64>,
    /// Place the kept vertex at the quadric's minimiser (true) or at the best point of
    /// the collapsed edge (false).
    pub optimal_placement: bool,
    /// Keep per-corner texture coordinates and the texture through decimation (texture
    /// seams then constrain the collapses); false drops them, for uses that only need the
    /// shape (the orientation).
    #[serde(default = "keep_by_default")]
    pub keep_texture_coordinates: bool,
}

fn keep_by_default() -> bool {
    true
}

impl Default for DecimateOptions {
    /// The settings the orientation uses: 20k faces (about 10k vertices), weighted
    /// boundary, normals turned at most 60°, quality threshold 0.3, optimal placement.
    fn default() -> Self {
        DecimateOptions {
            target_faces: 20_000,
            target_vertices: None,
            boundary: BoundaryPolicy::Weighted { weight: 100.0 },
            max_normal_change_deg: 60.0,
            quality_threshold: Some(0.3),
            optimal_placement: true,
            keep_texture_coordinates: true,
        }
    }
}

impl DecimateOptions {
    /// The default options with another target face count.
    pub fn with_target_faces(target_faces: usize) -> Self {
        DecimateOptions { target_faces, ..Default::default() }
    }

    /// The default options aiming at a vertex count instead (the face target is then
    /// one face, so only the vertex target stops decimation).
    pub fn with_target_vertices(target_vertices: usize) -> Self {
        DecimateOptions { target_faces: 1, target_vertices: Some(target_vertices), ..Default::default() }
    }
}

/// What [`decimate_with_options`] did.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct DecimateReport {
    /// Vertices of the input.
    pub input_vertices: usize,
    /// Faces of the input.
    pub input_faces: usize,
    /// Vertices of the result (unreferenced input vertices are dropped).
    pub output_vertices: usize,
    /// Faces of the result.
    pub output_faces: usize,
    /// Input faces with a repeated vertex, dropped before decimating.
    pub degenerate_faces_dropped: usize,
    /// Edge collapses performed.
    pub collapses: usize,
    /// Candidate collapses refused because they would change the topology.
    pub refused_for_topology: usize,
    /// Candidate collapses refused because a face would turn by more than the limit or
    /// degenerate.
    pub refused_for_normals: usize,
    /// Vertices that never moved: on non-manifold edges, and on the boundary with
    /// [`BoundaryPolicy::Fixed`].
    pub frozen_vertices: usize,
    /// Boundary edges before and after.
    pub boundary_edges_before: usize,
    /// Boundary edges after decimation.
    pub boundary_edges_after: usize,
    /// Edges with more than two faces in the input (their vertices are frozen).
    pub non_manifold_edges: usize,
    /// True when the target face (or vertex) count was reached.
    pub reached_target: bool,
    /// Largest collapse cost accepted, as an RMS distance in mm (the square root of
    /// the quadric error divided by the quadric's total area weight).
    pub max_collapse_error_mm: f64,
    /// Candidate collapses refused because they would drag texture coordinates across a
    /// texture seam.
    pub refused_for_texture_seams: usize,
    /// Vertices of the input on a texture seam (two or more UVs).
    pub seam_vertices: usize,
    /// Texture coordinates (and the texture) were dropped, as
    /// [`DecimateOptions::keep_texture_coordinates`] asked.
    pub texture_dropped: bool,
    /// Wall-clock time of the decimation.
    pub elapsed_seconds: f64,
}

/// Decimates `mesh` to `target_faces` faces with the default options (see
/// [`DecimateOptions::default`]).
pub fn decimate(mesh: &Mesh, target_faces: usize) -> Result<Mesh> {
    decimate_with_options(mesh, &DecimateOptions::with_target_faces(target_faces)).map(|(mesh, _)| mesh)
}

/// `mesh` decimated to `target_faces` for its shape alone (the default options without
/// texture coordinates): texture seams would only hold collapses back where nothing
/// looks at the texture (orientation, refinement).
pub fn decimate_shape(mesh: &Mesh, target_faces: usize) -> Result<Mesh> {
    let options = DecimateOptions { keep_texture_coordinates: false, ..DecimateOptions::with_target_faces(target_faces) };
    decimate_with_options(mesh, &options).map(|(decimated, _)| decimated)
}

/// Decimates `mesh` by quadric edge collapse; returns the result and what was done.
///
/// Errors: an invalid mesh ([`Mesh::validate`]), a point cloud, a zero target, a
/// non-finite or non-positive option.
pub fn decimate_with_options(mesh: &Mesh, options: &DecimateOptions) -> Result<(Mesh, DecimateReport)> {
    let started = Instant::now();
    mesh.validate()?;
    if mesh.is_point_cloud() {
        return Err(Error::InvalidArgument("decimation needs a mesh with faces, got a point cloud".into()));
    }
    if options.target_faces == 0 || options.target_vertices == Some(0) {
        return Err(Error::InvalidArgument("decimation target must be at least one face and one vertex".into()));
    }
    if !(options.max_normal_change_deg > 0.0 && options.max_normal_change_deg <= 180.0) {
        return Err(Error::InvalidArgument(format!(
            "max_normal_change_deg must be in (0, 180], got {}",
            options.max_normal_change_deg
        )));
    }
    if let Some(threshold) = options.quality_threshold
        && !(threshold > 0.0 && threshold <= 1.0)
    {
        return Err(Error::InvalidArgument(format!("quality_threshold must be in (0, 1], got {threshold}")));
    }
    if let BoundaryPolicy::Weighted { weight } = options.boundary
        && !(weight.is_finite() && weight >= 0.0)
    {
        return Err(Error::InvalidArgument(format!("boundary weight must be finite and >= 0, got {weight}")));
    }

    if mesh.face_count() <= options.target_faces || options.target_vertices.is_some_and(|n| mesh.vertex_count() <= n) {
        let report = DecimateReport {
            input_vertices: mesh.vertex_count(),
            input_faces: mesh.face_count(),
            output_vertices: mesh.vertex_count(),
            output_faces: mesh.face_count(),
            reached_target: true,
            elapsed_seconds: started.elapsed().as_secs_f64(),
            ..Default::default()
        };
        return Ok((mesh.clone(), report));
    }
    let mut collapser = Collapser::new(mesh, options);
    collapser.run(options.target_faces, options.target_vertices.unwrap_or(0));
    let (mut result, mut report) = collapser.finish();
    if result.corner_uvs.is_some() {
        result.texture = mesh.texture.clone();
    }
    report.elapsed_seconds = started.elapsed().as_secs_f64();
    Ok((result, report))
}

const NONE: u32 = u32::MAX;
const BOUNDARY: u8 = 1;
const FROZEN: u8 = 2;
/// On a texture seam: placed like a boundary vertex.
const SEAM: u8 = 4;
/// Where three or more texture charts meet: never moves (it may absorb a neighbour).
const PINNED: u8 = 8;

/// A candidate collapse of the edge `(first, second)`.
#[derive(Clone, Copy, Debug)]
struct Candidate {
    cost: f32,
    first: u32,
    second: u32,
    /// The collapse counter when pushed: stale once either endpoint changed later.
    pushed_at: u32,
}

/// A collapse as evaluated: where the kept vertex goes and at what cost.
#[derive(Clone, Copy, Debug)]
struct Placement {
    position: Vector,
    /// Parameter along `first -> second` used to interpolate attributes.
    t: f64,
    /// Quadric error at `position` (area-weighted squared distance, mm⁴).
    error: f64,
    /// `error`, floored and penalised for slivers: the heap's key.
    cost: f64,
}

/// Why a collapse was refused by [`Collapser::check_faces`].
struct Refusal;

struct Collapser {
    /// Positions relative to `origin`, so that quadrics of scans far from the origin
    /// keep their precision.
    positions: Vec<Vector>,
    origin: Vector,
    triangles: Vec<[u32; 3]>,
    face_alive: Vec<bool>,
    /// Each face's unit normal in the input: the normal check compares with it too,
    /// so that a face cannot turn over by many small steps.
    input_normals: Vec<[f32; 3]>,
    live_faces: usize,
    /// Head of each vertex's list of face corners (`3 * face + slot`), or `NONE`.
    first_corner: Vec<u32>,
    /// Next corner of the same vertex, or `NONE`.
    next_corner: Vec<u32>,
    quadrics: Vec<Quadric>,
    /// Sum of plane weights per vertex (area), to express costs as distances.
    quadric_area: Vec<f64>,
    flags: Vec<u8>,
    vertex_alive: Vec<bool>,
    changed_at: Vec<u32>,
    /// Scratch marks for neighbourhood queries, compared with `mark_counter`.
    marks: Vec<u32>,
    mark_counter: u32,
    neighbours: Vec<u32>,
    colors: Option<Vec<[f32; 4]>>,
    normals: Option<Vec<Vector>>,
    quality: Option<Vec<f32>>,
    /// Texture coordinates per corner (`3 * face + slot`), when kept.
    uvs: Option<Vec<[f32; 2]>>,
    /// The UVs the accepted collapse gives to corners: `(corner, uv)`.
    uv_updates: Vec<(u32, [f32; 2])>,
    heap: CandidateQueue,
    collapses: u32,
    min_cos_normal_change: f64,
    quality_threshold: Option<f64>,
    optimal_placement: bool,
    /// Costs below this count as this (as MeshLab's quadric epsilon): on exactly flat
    /// patches triangle quality alone decides.
    cost_floor: f64,
    report: DecimateReport,
}

impl Collapser {
    fn new(mesh: &Mesh, options: &DecimateOptions) -> Self {
        let vertex_count = mesh.vertex_count();
        let (low, high) = mesh.bounding_box().expect("validated mesh with faces has vertices");
        let origin = (low.coords + high.coords) / 2.0;
        let diagonal = (high - low).norm().max(f64::MIN_POSITIVE);
        let positions: Vec<Vector> = mesh.positions.iter().map(|p| p.coords - origin).collect();
        let mut report = DecimateReport {
            input_vertices: vertex_count,
            input_faces: mesh.face_count(),
            texture_dropped: !options.keep_texture_coordinates && (mesh.corner_uvs.is_some() || mesh.texture.is_some()),
            ..Default::default()
        };
        let is_proper = |[a, b, c]: &[u32; 3]| a != b && b != c && a != c;
        let triangles: Vec<[u32; 3]> = mesh.triangles.iter().copied().filter(is_proper).collect();
        let uvs = mesh.corner_uvs.as_ref().filter(|_| options.keep_texture_coordinates).map(|uvs| {
            let faces = mesh.triangles.iter().zip(uvs.chunks_exact(3)).filter(|(t, _)| is_proper(t));
            faces.flat_map(|(_, corners)| corners.iter().copied()).collect::<Vec<[f32; 2]>>()
        });
        report.degenerate_faces_dropped = mesh.face_count() - triangles.len();

        let mut first_corner = vec![NONE; vertex_count];
        let mut next_corner = vec![NONE; 3 * triangles.len()];
        for (face, triangle) in triangles.iter().enumerate() {
            for (slot, &vertex) in triangle.iter().enumerate() {
                let corner = 3 * face + slot;
                next_corner[corner] = first_corner[vertex as usize];
                first_corner[vertex as usize] = corner as u32;
            }
        }

        let input_normals = triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| positions[v as usize]);
                let normal = (b - a).cross(&(c - a)).try_normalize(0.0).unwrap_or_default();
                [normal.x as f32, normal.y as f32, normal.z as f32]
            })
            .collect();
        let mut collapser = Collapser {
            input_normals,
            positions,
            origin,
            live_faces: triangles.len(),
            face_alive: vec![true; triangles.len()],
            triangles,
            first_corner,
            next_corner,
            quadrics: vec![Quadric::default(); vertex_count],
            quadric_area: vec![0.0; vertex_count],
            flags: vec![0; vertex_count],
            vertex_alive: vec![true; vertex_count],
            changed_at: vec![0; vertex_count],
            marks: vec![0; vertex_count],
            mark_counter: 0,
            neighbours: Vec::new(),
            colors: mesh.colors.as_ref().map(|colors| {
                colors.iter().map(|c| c.map(f32::from)).collect()
            }),
            normals: mesh.normals.clone(),
            quality: mesh.quality.clone(),
            uvs,
            uv_updates: Vec::new(),
            heap: CandidateQueue::default(),
            collapses: 0,
            min_cos_normal_change: options.max_normal_change_deg.to_radians().cos(),
            quality_threshold: options.quality_threshold,
            optimal_placement: options.optimal_placement,
            cost_floor: 1e-30 * diagonal.powi(4),
            report,
        };
        let edges = collapser.build_quadrics(options.boundary);
        collapser.mark_texture_seams(options.boundary);
        collapser.push_initial_candidates(edges);
        collapser
    }

    /// Flags the vertices with two or more distinct UVs (seams) and three or more
    /// (chart corners), and gives each seam edge (two faces that disagree on its UVs) the
    /// boundary's treatment: a perpendicular plane quadric, or frozen vertices with
    /// [`BoundaryPolicy::Fixed`].
    fn mark_texture_seams(&mut self, boundary: BoundaryPolicy) {
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

    /// Classifies edges by sorting them (no hash map), flags boundary and
    /// non-manifold vertices, and sums the face and boundary plane quadrics. Returns
    /// the manifold edges (one or two faces) as `low << 32 | high` keys.
    fn build_quadrics(&mut self, boundary: BoundaryPolicy) -> Vec<u64> {
        // Keys only (8 bytes per half-edge): this is the largest temporary.
        let mut edges: Vec<u64> = self
            .triangles
            .iter()
            .flat_map(|&[a, b, c]| [(a, b), (b, c), (c, a)])
            .map(|(from, to)| (u64::from(from.min(to)) << 32) | u64::from(from.max(to)))
            .collect();
        edges.par_sort_unstable();

        for triangle in &self.triangles {
            let [a, b, c] = triangle.map(|v| self.positions[v as usize]);
            let scaled_normal = (b - a).cross(&(c - a));
            let area = 0.5 * scaled_normal.norm();
            if area <= 0.0 {
                continue;
            }
            let quadric = Quadric::from_plane_through(&a, &(scaled_normal / (2.0 * area)), area);
            for &v in triangle {
                self.quadrics[v as usize] += quadric;
                self.quadric_area[v as usize] += area;
            }
        }

        // Classify each run of equal keys, and keep the manifold edges, once each, in
        // the front of the same vector.
        let (mut run_start, mut manifold_count) = (0, 0);
        while run_start < edges.len() {
            let key = edges[run_start];
            let run_end = run_start + edges[run_start..].iter().take_while(|&&k| k == key).count();
            let (low, high) = ((key >> 32) as u32, key as u32);
            if run_end - run_start > 2 {
                self.report.non_manifold_edges += 1;
                self.flags[low as usize] |= FROZEN;
                self.flags[high as usize] |= FROZEN;
            } else {
                if run_end - run_start == 1 {
                    self.report.boundary_edges_before += 1;
                    self.flags[low as usize] |= BOUNDARY;
                    self.flags[high as usize] |= BOUNDARY;
                    self.add_boundary_quadric(low, high, boundary);
                }
                edges[manifold_count] = key;
                manifold_count += 1;
            }
            run_start = run_end;
        }
        edges.truncate(manifold_count);
        if boundary == BoundaryPolicy::Fixed {
            for flag in &mut self.flags {
                if *flag & BOUNDARY != 0 {
                    *flag |= FROZEN;
                }
            }
        }
        self.report.frozen_vertices = self.flags.iter().filter(|&&f| f & FROZEN != 0).count();
        edges
    }

    /// The plane through the boundary edge `low`-`high`, perpendicular to its face,
    /// added to both endpoints.
    fn add_boundary_quadric(&mut self, low: u32, high: u32, boundary: BoundaryPolicy) {
        let BoundaryPolicy::Weighted { weight } = boundary else { return };
        let Some(triangle) = self.corners_of(low).map(|c| self.triangles[c as usize / 3]).find(|t| t.contains(&high))
        else {
            return;
        };
        let slot = (0..3).find(|&s| triangle[s] != low && triangle[s] != high).expect("a triangle has three vertices");
        let [opposite, from, to] = [triangle[slot], triangle[(slot + 1) % 3], triangle[(slot + 2) % 3]];
        let [p, q, r] = [from, to, opposite].map(|v| self.positions[v as usize]);
        let edge = q - p;
        let face_normal = edge.cross(&(r - p));
        let Some(plane_normal) = face_normal.cross(&edge).try_normalize(0.0) else { return };
        let quadric = Quadric::from_plane_through(&p, &plane_normal, weight * edge.norm_squared());
        self.quadrics[from as usize] += quadric;
        self.quadrics[to as usize] += quadric;
    }

    /// Evaluates every edge once (in parallel: evaluation only reads) and heapifies.
    fn push_initial_candidates(&mut self, edges: Vec<u64>) {
        let this = &*self;
        // Indexed, so rayon writes straight into the two vectors (an unindexed
        // collect would hold a second copy). Edges between frozen vertices are queued
        // at infinite cost and never collapse.
        let (mut costs, mut candidates) = (Vec::new(), Vec::new());
        edges
            .par_iter()
            .map(|&key| {
                let (first, second) = ((key >> 32) as u32, key as u32);
                let cost = this.place(first, second).map_or(f32::INFINITY, |placement| placement.cost as f32);
                (cost, [first, second, 0])
            })
            .unzip_into_vecs(&mut costs, &mut candidates);
        drop(edges);
        self.heap = CandidateQueue { costs, edges: candidates };
        self.heap.heapify();
    }

    /// A mark value no vertex carries yet, for neighbourhood queries.
    fn fresh_mark(&mut self) -> u32 {
        if self.mark_counter == u32::MAX {
            self.marks.fill(0);
            self.mark_counter = 0;
        }
        self.mark_counter += 1;
        self.mark_counter
    }

    fn corners_of(&self, vertex: u32) -> CornerIter<'_> {
        CornerIter { next_corner: &self.next_corner, current: self.first_corner[vertex as usize] }
    }

    fn edge_face_count(&self, a: u32, b: u32) -> usize {
        self.corners_of(a).filter(|&c| self.triangles[c as usize / 3].contains(&b)).count()
    }

    /// Where the collapse of `first`/`second` puts the kept vertex and its quadric
    /// cost, a lower bound of the full cost ([`Collapser::check_faces`] may raise it):
    /// candidates are queued with it and checked only when they come out of the queue.
    /// `None` when both endpoints are frozen.
    fn place(&self, first: u32, second: u32) -> Option<Placement> {
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
    fn check_faces(&self, first: u32, second: u32, placement: &mut Placement) -> std::result::Result<(), Refusal> {
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
    fn topology_allows(&mut self, first: u32, second: u32) -> bool {
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

    fn run(&mut self, target_faces: usize, target_vertices: usize) {
        // The largest error / area ratio so far, as a fraction to avoid dividing in the loop.
        let mut max_error_area: (f64, f64) = (0.0, 1.0);
        let mut live_vertices = self.first_corner.iter().filter(|&&c| c != NONE).count();
        while self.live_faces > target_faces && live_vertices > target_vertices {
            let Some(candidate) = self.heap.pop() else { break };
            let (a, b) = (candidate.first, candidate.second);
            if !self.vertex_alive[a as usize]
                || !self.vertex_alive[b as usize]
                || self.changed_at[a as usize] > candidate.pushed_at
                || self.changed_at[b as usize] > candidate.pushed_at
            {
                continue;
            }
            if !self.topology_allows(a, b) {
                self.report.refused_for_topology += 1;
                continue;
            }
            let Some(mut placement) = self.place(a, b) else { continue };
            if self.check_faces(a, b, &mut placement).is_err() {
                self.report.refused_for_normals += 1;
                continue;
            }
            if !self.plan_texture_coordinates(a, b, &placement) {
                self.report.refused_for_texture_seams += 1;
                continue;
            }
            // Queued at a lower bound (quadric only, or an older neighbourhood): queue
            // it again at its true cost instead of collapsing out of order.
            if placement.cost as f32 > candidate.cost * 1.0001 {
                self.heap.push(Candidate { cost: placement.cost as f32, pushed_at: self.collapses, ..candidate });
                continue;
            }
            let area = self.quadric_area[a as usize] + self.quadric_area[b as usize];
            if placement.error * max_error_area.1 > max_error_area.0 * area {
                max_error_area = (placement.error, area);
            }
            self.collapse(a, b, placement);
            live_vertices -= 1;
            self.compact_heap_if_stale();
        }
        self.report.max_collapse_error_mm = (max_error_area.0 / max_error_area.1).sqrt();
        self.report.reached_target = self.live_faces <= target_faces || live_vertices <= target_vertices;
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
    fn plan_texture_coordinates(&mut self, first: u32, second: u32, placement: &Placement) -> bool {
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

    /// The vertices of the edge's face the placement falls most inside of, and the
    /// placement's barycentric weights there (clamped to the face, so attributes stay
    /// between their neighbours' values): per-vertex attributes are interpolated at
    /// the placement, also where an optimal placement leaves the edge.
    fn placement_weights(&self, first: u32, second: u32, placement: &Placement) -> ([u32; 3], [f64; 3]) {
        let along_edge = ([first, second, first], [1.0 - placement.t, placement.t, 0.0]);
        let faces = self.corners_of(first).map(|c| self.triangles[c as usize / 3]).filter(|t| t.contains(&second));
        let weighted = faces.map(|triangle| {
            let [a, b, c] = triangle.map(|v| self.positions[v as usize]);
            (triangle, barycentric(&placement.position, &a, &b, &c))
        });
        let most_inside = weighted.max_by(|x, y| least(&x.1).total_cmp(&least(&y.1)));
        most_inside.map_or(along_edge, |(triangle, weights)| (triangle, clamped_to_triangle(weights)))
    }

    /// Merges `removed` into `kept` at the placement, then queues `kept`'s edges.
    fn collapse(&mut self, first: u32, second: u32, placement: Placement) {
        // The frozen endpoint (if any) is the one that stays; `t` is measured from `first`.
        let (kept, removed) = if self.flags[second as usize] & FROZEN != 0 { (second, first) } else { (first, second) };
        let (k, r) = (kept as usize, removed as usize);
        let (vertices, weights) = self.placement_weights(first, second, &placement);
        let [i, j, l] = vertices.map(|v| v as usize);
        let [w_i, w_j, w_l] = weights;
        let [f_i, f_j, f_l] = weights.map(|w| w as f32);
        if let Some(colors) = &mut self.colors {
            let mixed: [f32; 4] = std::array::from_fn(|c| f_i * colors[i][c] + f_j * colors[j][c] + f_l * colors[l][c]);
            colors[k] = mixed;
        }
        if let Some(normals) = &mut self.normals {
            let mixed = normals[i] * w_i + normals[j] * w_j + normals[l] * w_l;
            normals[k] = mixed.try_normalize(1e-12).unwrap_or(normals[k]);
        }
        if let Some(quality) = &mut self.quality {
            quality[k] = f_i * quality[i] + f_j * quality[j] + f_l * quality[l];
        }
        if let Some(uvs) = &mut self.uvs {
            for &(corner, uv) in &self.uv_updates {
                uvs[corner as usize] = uv;
            }
        }
        self.positions[k] = placement.position;
        self.quadrics[k] = self.quadrics[k] + self.quadrics[r];
        self.quadric_area[k] += self.quadric_area[r];
        self.flags[k] |= self.flags[r];
        self.vertex_alive[r] = false;

        let mut corner = self.first_corner[r];
        self.first_corner[r] = NONE;
        while corner != NONE {
            let next = self.next_corner[corner as usize];
            let face = corner as usize / 3;
            if self.triangles[face].contains(&kept) {
                self.face_alive[face] = false;
                self.live_faces -= 1;
                for v in self.triangles[face] {
                    if v != removed {
                        self.unlink(v, face);
                    }
                }
            } else {
                self.triangles[face][corner as usize % 3] = kept;
                self.next_corner[corner as usize] = self.first_corner[k];
                self.first_corner[k] = corner;
            }
            corner = next;
        }

        self.collapses += 1;
        self.report.collapses += 1;
        self.changed_at[k] = self.collapses;
        self.push_edges_of(kept);
    }

    /// Removes `face`'s corner from `vertex`'s list.
    fn unlink(&mut self, vertex: u32, face: usize) {
        let mut previous = NONE;
        let mut corner = self.first_corner[vertex as usize];
        while corner != NONE {
            let next = self.next_corner[corner as usize];
            if corner as usize / 3 == face {
                if previous == NONE {
                    self.first_corner[vertex as usize] = next;
                } else {
                    self.next_corner[previous as usize] = next;
                }
                return;
            }
            previous = corner;
            corner = next;
        }
    }

    fn push_edges_of(&mut self, vertex: u32) {
        let stamp = self.fresh_mark();
        let mut neighbours = std::mem::take(&mut self.neighbours);
        neighbours.clear();
        let corners = CornerIter { next_corner: &self.next_corner, current: self.first_corner[vertex as usize] };
        for corner in corners {
            for v in self.triangles[corner as usize / 3] {
                if v != vertex && self.marks[v as usize] != stamp {
                    self.marks[v as usize] = stamp;
                    neighbours.push(v);
                }
            }
        }
        for &neighbour in &neighbours {
            if let Some(placement) = self.place(vertex, neighbour) {
                self.heap.push(Candidate {
                    cost: placement.cost as f32,
                    first: vertex,
                    second: neighbour,
                    pushed_at: self.collapses,
                });
            }
        }
        self.neighbours = neighbours;
    }

    /// Lazy deletion lets stale entries pile up; filtering them out in one linear
    /// pass whenever the queue outgrows the live edges (about 1.5 per face) is far
    /// cheaper than popping them one by one (on 500k faces: 0.4M pops instead of 1.8M).
    fn compact_heap_if_stale(&mut self) {
        if self.heap.len() < 2 * self.live_faces + 4096 {
            return;
        }
        let (alive, changed_at) = (&self.vertex_alive, &self.changed_at);
        self.heap.retain(|c| {
            let (a, b) = (c.first as usize, c.second as usize);
            alive[a] && alive[b] && changed_at[a] <= c.pushed_at && changed_at[b] <= c.pushed_at
        });
    }

    fn finish(mut self) -> (Mesh, DecimateReport) {
        let mut new_index = vec![NONE; self.positions.len()];
        let mut positions = Vec::new();
        let mut kept_vertices = Vec::new();
        let mut triangles = Vec::with_capacity(self.live_faces);
        for (face, triangle) in self.triangles.iter().enumerate() {
            if !self.face_alive[face] {
                continue;
            }
            triangles.push(triangle.map(|v| {
                let slot = &mut new_index[v as usize];
                if *slot == NONE {
                    *slot = positions.len() as u32;
                    positions.push(Point::from(self.positions[v as usize] + self.origin));
                    kept_vertices.push(v as usize);
                }
                *slot
            }));
        }
        let colors = self.colors.as_ref().map(|colors| {
            kept_vertices.iter().map(|&v| colors[v].map(|c| c.round().clamp(0.0, 255.0) as u8)).collect()
        });
        let normals = self.normals.as_ref().map(|normals| kept_vertices.iter().map(|&v| normals[v]).collect());
        let quality = self.quality.as_ref().map(|quality| kept_vertices.iter().map(|&v| quality[v]).collect());
        let corner_uvs = self.uvs.as_ref().map(|uvs| {
            let live = (0..self.triangles.len()).filter(|&face| self.face_alive[face]);
            live.flat_map(|face| [uvs[3 * face], uvs[3 * face + 1], uvs[3 * face + 2]]).collect()
        });
        let result = Mesh { positions, triangles, normals, colors, quality, corner_uvs, texture: None };
        self.report.output_vertices = result.vertex_count();
        self.report.output_faces = result.face_count();
        self.report.boundary_edges_after = count_boundary_edges(&result.triangles);
        (result, self.report)
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

/// Barycentric coordinates of `point` projected on the plane of the triangle `a b c`
/// (uniform weights for a degenerate triangle).
fn barycentric(point: &Vector, a: &Vector, b: &Vector, c: &Vector) -> [f64; 3] {
    let (ab, ac, ap) = (b - a, c - a, point - a);
    let (d00, d01, d11) = (ab.dot(&ab), ab.dot(&ac), ac.dot(&ac));
    let (d20, d21) = (ap.dot(&ab), ap.dot(&ac));
    let denominator = d00 * d11 - d01 * d01;
    if !(denominator.abs() > 1e-30 * d00 * d11) {
        return [1.0 / 3.0; 3];
    }
    let beta = (d11 * d20 - d01 * d21) / denominator;
    let gamma = (d00 * d21 - d01 * d20) / denominator;
    [1.0 - beta - gamma, beta, gamma]
}

/// The least of barycentric weights: positive inside the triangle, the further inside
/// the larger.
fn least(weights: &[f64; 3]) -> f64 {
    weights.iter().copied().fold(f64::INFINITY, f64::min)
}

/// Barycentric weights moved onto the triangle (negative ones to zero, renormalised).
fn clamped_to_triangle(weights: [f64; 3]) -> [f64; 3] {
    let clamped = weights.map(|w| w.max(0.0));
    let sum: f64 = clamped.iter().sum();
    if sum > 0.0 { clamped.map(|w| w / sum) } else { [1.0 / 3.0; 3] }
}

/// Number of edges with exactly one face.
fn count_boundary_edges(triangles: &[[u32; 3]]) -> usize {
    let mut keys: Vec<u64> = triangles
        .iter()
        .flat_map(|&[a, b, c]| [(a, b), (b, c), (c, a)])
        .map(|(from, to)| (u64::from(from.min(to)) << 32) | u64::from(from.max(to)))
        .collect();
    keys.sort_unstable();
    keys.chunk_by(|x, y| x == y).filter(|run| run.len() == 1).count()
}

struct CornerIter<'a> {
    next_corner: &'a [u32],
    current: u32,
}

impl Iterator for CornerIter<'_> {
    type Item = u32;
    fn next(&mut self) -> Option<u32> {
        if self.current == NONE {
            return None;
        }
        let corner = self.current;
        self.current = self.next_corner[corner as usize];
        Some(corner)
    }
}

/// A 4-ary min-heap of candidates with the costs in their own array: popping is the
/// inner loop's bottleneck, and a sift-down that compares four adjacent `f32` costs
/// touches one cache line per level, over half as many levels as a binary heap.
/// (Measured on 500k faces: `std`'s `BinaryHeap` of whole entries spent twice as
/// long; keys pointing into a slab made the periodic compaction slower than it saved.)
#[derive(Default)]
struct CandidateQueue {
    costs: Vec<f32>,
    /// `(first, second, pushed_at)`, parallel to `costs`.
    edges: Vec<[u32; 3]>,
}

impl CandidateQueue {
    fn heapify(&mut self) {
        for index in (0..self.costs.len().div_ceil(4)).rev() {
            self.sift_down(index);
        }
    }

    /// Keeps only the candidates for which `keep` holds.
    fn retain(&mut self, mut keep: impl FnMut(&Candidate) -> bool) {
        let mut kept = 0;
        for index in 0..self.costs.len() {
            let [first, second, pushed_at] = self.edges[index];
            if keep(&Candidate { cost: self.costs[index], first, second, pushed_at }) {
                self.costs[kept] = self.costs[index];
                self.edges[kept] = self.edges[index];
                kept += 1;
            }
        }
        self.costs.truncate(kept);
        self.edges.truncate(kept);
        self.heapify();
    }

    fn len(&self) -> usize {
        self.costs.len()
    }

    fn push(&mut self, candidate: Candidate) {
        let edge = [candidate.first, candidate.second, candidate.pushed_at];
        self.costs.push(candidate.cost);
        self.edges.push(edge);
        let mut index = self.costs.len() - 1;
        while index > 0 {
            let parent = (index - 1) / 4;
            if self.costs[parent] <= candidate.cost {
                break;
            }
            self.costs[index] = self.costs[parent];
            self.edges[index] = self.edges[parent];
            index = parent;
        }
        self.costs[index] = candidate.cost;
        self.edges[index] = edge;
    }

    fn pop(&mut self) -> Option<Candidate> {
        let cost = *self.costs.first()?;
        let [first, second, pushed_at] = self.edges[0];
        let (last_cost, last_edge) = (self.costs.pop().expect("not empty"), self.edges.pop().expect("parallel"));
        if !self.costs.is_empty() {
            self.costs[0] = last_cost;
            self.edges[0] = last_edge;
            self.sift_down(0);
        }
        Some(Candidate { cost, first, second, pushed_at })
    }

    fn sift_down(&mut self, mut index: usize) {
        let (cost, edge) = (self.costs[index], self.edges[index]);
        let length = self.costs.len();
        loop {
            let first_child = 4 * index + 1;
            if first_child >= length {
                break;
            }
            let children = &self.costs[first_child..(first_child + 4).min(length)];
            let (offset, &smallest) =
                children.iter().enumerate().min_by(|a, b| a.1.total_cmp(b.1)).expect("a child");
            if smallest >= cost {
                break;
            }
            self.costs[index] = smallest;
            self.edges[index] = self.edges[first_child + offset];
            index = first_child + offset;
        }
        self.costs[index] = cost;
        self.edges[index] = edge;
    }
}
