//! The collapser: the mesh as flat arrays (per-vertex lists of face corners, quadrics,
//! flags), their set-up, the collapse loop, the collapse itself and the result.

use rayon::prelude::*;

use super::barycentric::{barycentric, clamped_to_triangle, least};
use super::options::{BoundaryPolicy, DecimateOptions, DecimateReport};
use super::queue::{Candidate, CandidateQueue};
use crate::mesh::quadric::Quadric;
use crate::mesh::{Mesh, Point, Vector};

const NONE: u32 = u32::MAX;
/// [`Collapser::changed_at`] of a removed vertex: later than any collapse count.
const REMOVED: u32 = u32::MAX;
pub(super) const BOUNDARY: u8 = 1;
pub(super) const FROZEN: u8 = 2;
/// On a texture seam: placed like a boundary vertex.
pub(super) const SEAM: u8 = 4;
/// Where three or more texture charts meet: never moves (it may absorb a neighbour).
pub(super) const PINNED: u8 = 8;

/// A collapse as evaluated: where the kept vertex goes and at what cost.
#[derive(Clone, Copy, Debug)]
pub(super) struct Placement {
    pub(super) position: Vector,
    /// Parameter along `first -> second` used to interpolate attributes.
    pub(super) t: f64,
    /// Quadric error at `position` (area-weighted squared distance, mm⁴).
    pub(super) error: f64,
    /// `error`, floored and penalised for slivers: the heap's key.
    pub(super) cost: f64,
}

pub(super) struct Collapser {
    /// Positions relative to `origin`, so that quadrics of scans far from the origin
    /// keep their precision.
    pub(super) positions: Vec<Vector>,
    origin: Vector,
    pub(super) triangles: Vec<[u32; 3]>,
    face_alive: Vec<bool>,
    /// Each face's unit normal in the input: the normal check compares with it too,
    /// so that a face cannot turn over by many small steps.
    pub(super) input_normals: Vec<[f32; 3]>,
    live_faces: usize,
    /// Head of each vertex's list of face corners (`3 * face + slot`), or `NONE`.
    pub(super) first_corner: Vec<u32>,
    /// Next corner of the same vertex, or `NONE`.
    pub(super) next_corner: Vec<u32>,
    pub(super) quadrics: Vec<Quadric>,
    /// Sum of plane weights per vertex (area), to express costs as distances.
    quadric_area: Vec<f64>,
    pub(super) flags: Vec<u8>,
    /// The collapse count when each vertex last changed, [`REMOVED`] once merged away:
    /// a queued candidate is stale when either endpoint's is later than its own. Dead
    /// and changed vertices in one array, so that the check of every popped candidate
    /// reads one cache line per endpoint.
    changed_at: Vec<u32>,
    /// Scratch marks for neighbourhood queries, compared with `mark_counter`.
    pub(super) marks: Vec<u32>,
    mark_counter: u32,
    neighbours: Vec<u32>,
    colors: Option<Vec<[f32; 4]>>,
    normals: Option<Vec<Vector>>,
    quality: Option<Vec<f32>>,
    /// Texture coordinates per corner (`3 * face + slot`), when kept.
    pub(super) uvs: Option<Vec<[f32; 2]>>,
    /// The UVs the accepted collapse gives to corners: `(corner, uv)`.
    pub(super) uv_updates: Vec<(u32, [f32; 2])>,
    heap: CandidateQueue,
    collapses: u32,
    pub(super) min_cos_normal_change: f64,
    pub(super) quality_threshold: Option<f64>,
    pub(super) optimal_placement: bool,
    /// Costs below this count as this (as MeshLab's quadric epsilon): on exactly flat
    /// patches triangle quality alone decides.
    pub(super) cost_floor: f64,
    pub(super) report: DecimateReport,
}

impl Collapser {
    pub(super) fn new(mesh: &Mesh, options: &DecimateOptions) -> Self {
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
    pub(super) fn add_boundary_quadric(&mut self, low: u32, high: u32, boundary: BoundaryPolicy) {
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
    pub(super) fn fresh_mark(&mut self) -> u32 {
        if self.mark_counter == u32::MAX {
            self.marks.fill(0);
            self.mark_counter = 0;
        }
        self.mark_counter += 1;
        self.mark_counter
    }

    pub(super) fn corners_of(&self, vertex: u32) -> CornerIter<'_> {
        CornerIter { next_corner: &self.next_corner, current: self.first_corner[vertex as usize] }
    }

    pub(super) fn edge_face_count(&self, a: u32, b: u32) -> usize {
        self.corners_of(a).filter(|&c| self.triangles[c as usize / 3].contains(&b)).count()
    }

    pub(super) fn run(&mut self, target_faces: usize, target_vertices: usize) {
        // The largest error / area ratio so far, as a fraction to avoid dividing in the loop.
        let mut max_error_area: (f64, f64) = (0.0, 1.0);
        let mut live_vertices = self.first_corner.iter().filter(|&&c| c != NONE).count();
        while self.live_faces > target_faces && live_vertices > target_vertices {
            let Some(candidate) = self.heap.pop() else { break };
            let (a, b) = (candidate.first, candidate.second);
            if self.changed_at[a as usize] > candidate.pushed_at || self.changed_at[b as usize] > candidate.pushed_at {
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
        self.changed_at[r] = REMOVED;

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
        let changed_at = &self.changed_at;
        self.heap.retain(|c| changed_at[c.first as usize] <= c.pushed_at && changed_at[c.second as usize] <= c.pushed_at);
    }

    pub(super) fn finish(mut self) -> (Mesh, DecimateReport) {
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

pub(super) struct CornerIter<'a> {
    pub(super) next_corner: &'a [u32],
    pub(super) current: u32,
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
