//! The exterior and interior views (Wilczek et al. 2018, sections 2.4.1 and 2.4.3): the
//! oriented fragment turned about the axis, projected orthographically onto the xz-plane
//! with a z-buffer, and shaded per pixel by the chosen styles (vertex colour or texture,
//! directional light, ambient occlusion, regularity colours). The view's outline and
//! visible crease lines are traced as vector paths.

use nalgebra::Rotation3;
use rayon::prelude::*;

use super::raster::{barycentric, rasterize_parallel, OrthographicCamera, ZBuffer, NO_FACE};
use crate::mesh::topology::Topology;
use crate::mesh::{segment_distance, Mesh, Point, Vector};
use crate::profile::regularity::ColorMap;

/// Per-vertex data the shading reads, all in the oriented frame.
pub(crate) struct Surface<'a> {
    pub mesh: &'a Mesh,
    pub oriented: &'a [Point],
    pub normals: &'a [Vector],
    /// Ambient light.
    pub occlusion: Option<&'a OcclusionField>,
    /// Values and their colour map.
    pub regularity: Option<(&'a [f32], &'a ColorMap)>,
}

/// Ambient light per vertex in two parts (see [`super::occlusion::near_and_far_light`]):
/// a pixel's light is `near` times `far_factor` smoothed over the view, stretched by
/// `(light - low) / span` to [0, 1].
pub(crate) struct OcclusionField {
    /// Light left by the near occluders, per vertex.
    pub near: Vec<f32>,
    /// What the far occluders take away, as a factor in [0, 1] per vertex.
    pub far_factor: Vec<f32>,
    /// Light shown black.
    pub low: f32,
    /// Light range from black to white.
    pub span: f32,
}

/// Width of the far occlusion's smoothing, as a share of the view's larger side: wide
/// enough to melt the one-direction shadow edges of a few dozen directions into the
/// gradient many directions give.
const FAR_OCCLUSION_SMOOTHING_SHARE: f64 = 0.12;

/// What the view's pixels show.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Shading {
    pub colour: bool,
    pub light: bool,
    pub occlusion: bool,
    pub regularity: bool,
    /// Unit direction towards the light in the view frame (x right, -y towards the
    /// viewer, z up).
    pub light_direction: [f64; 3],
}

/// A rendered view: the z-buffer and, per pixel, the colour and the tone stipple reads.
pub(crate) struct View {
    pub camera: OrthographicCamera,
    pub buffer: ZBuffer,
    pub projected: Vec<[f32; 3]>,
    /// RGBA, straight alpha; transparent where no face is seen.
    pub rgba: Vec<u8>,
    /// Darkness in [0, 1] per pixel (0 where empty).
    pub darkness: Vec<f32>,
}

impl View {
    /// Object-space `[x, z]` of the top-left corner of pixel (0, 0).
    pub fn top_left(&self) -> [f64; 2] {
        [self.camera.origin.x, self.camera.origin.z]
    }

    /// The first and last covered pixel column of each row, `None` for an empty row.
    pub fn covered_columns(&self) -> Vec<Option<(usize, usize)>> {
        let width = self.buffer.width;
        self.buffer
            .face
            .chunks(width.max(1))
            .map(|row| {
                let first = row.iter().position(|&f| f != NO_FACE)?;
                let last = row.iter().rposition(|&f| f != NO_FACE)?;
                Some((first, last))
            })
            .collect()
    }

    /// Keeps the pixel columns `start..end` only: the view cut along a vertical line, as an
    /// illustrator cuts a view that does not fit at the axis. Projected vertices keep
    /// their place on the object (their columns move with the cut).
    pub fn crop_columns(&mut self, start: usize, end: usize) {
        let width = self.camera.width;
        let end = end.min(width);
        let start = start.min(end);
        if (start, end) == (0, width) {
            return;
        }
        fn crop<T: Copy>(values: &[T], width: usize, per_pixel: usize, start: usize, end: usize) -> Vec<T> {
            values.chunks(width * per_pixel).flat_map(|row| row[start * per_pixel..end * per_pixel].iter().copied()).collect()
        }
        self.buffer.depth = crop(&self.buffer.depth, width, 1, start, end);
        self.buffer.face = crop(&self.buffer.face, width, 1, start, end);
        self.rgba = crop(&self.rgba, width, 4, start, end);
        self.darkness = crop(&self.darkness, width, 1, start, end);
        self.buffer.width = end - start;
        self.camera.width = end - start;
        self.camera.origin += self.camera.right * (start as f64 * self.camera.pixel_mm);
        for p in &mut self.projected {
            p[0] -= start as f32;
        }
    }
}

/// Renders the surface turned by `rotation_rad` about z, seen from -y (x right, z up).
pub(crate) fn render_view(surface: &Surface, rotation_rad: f64, pixel_mm: f64, shading: &Shading) -> View {
    let rotation = Rotation3::from_axis_angle(&Vector::z_axis(), rotation_rad);
    let rotated: Vec<Point> = surface.oriented.par_iter().map(|p| rotation * p).collect();
    let camera = OrthographicCamera::fit(&rotated, Vector::y(), Vector::z(), pixel_mm, 2);
    let projected = camera.project_all(&rotated);
    drop(rotated);
    let buffer = rasterize_parallel(camera.width, camera.height, &projected, &surface.mesh.triangles);
    let (width, height) = (camera.width, camera.height);
    let mut rgba = vec![0u8; width * height * 4];
    let mut darkness = vec![0f32; width * height];
    let light = Vector::from(shading.light_direction).normalize();
    let mesh = surface.mesh;
    let far_light = match (shading.occlusion, surface.occlusion) {
        (true, Some(field)) => Some(smoothed_far_factor(&buffer, &projected, mesh, &field.far_factor)),
        _ => None,
    };
    rgba.par_chunks_mut(width * 4).zip(darkness.par_chunks_mut(width)).enumerate().for_each(|(y, (row, dark_row))| {
        for x in 0..width {
            let face = buffer.face[y * width + x];
            if face == NO_FACE {
                continue;
            }
            let tri = mesh.triangles[face as usize];
            let w = barycentric(&projected, tri, x, y);
            let corners = tri.map(|v| v as usize);
            let mut normal = rotation * (surface.normals[corners[0]] * w[0] as f64 + surface.normals[corners[1]] * w[1] as f64 + surface.normals[corners[2]] * w[2] as f64);
            if normal.y > 0.0 {
                normal = -normal; // seen from behind (noisy normals, interior): light the side we see
            }
            let normal = normal.try_normalize(1e-12).unwrap_or(-Vector::y());
            let mut tone = 1.0f64;
            if shading.light {
                // Wrapped Lambert: surfaces turned slightly away from the light keep some
                // modelling instead of going flat black.
                tone *= 0.25 + 0.75 * ((normal.dot(&light) + 0.3) / 1.3).max(0.0);
            }
            if let (Some(field), Some(far)) = (surface.occlusion, &far_light) {
                let near = field.near[corners[0]] * w[0] + field.near[corners[1]] * w[1] + field.near[corners[2]] * w[2];
                let a = ((near * far[y * width + x] - field.low) / field.span).clamp(0.0, 1.0);
                tone *= 0.35 + 0.65 * a as f64;
            }
            let mut base = [1.0f64; 3];
            if let (true, Some((values, map))) = (shading.regularity, surface.regularity) {
                let v = values[corners[0]] * w[0] + values[corners[1]] * w[1] + values[corners[2]] * w[2];
                base = map.color(v as f64).map(|c| c as f64 / 255.0);
            } else if shading.colour {
                base = surface_colour(mesh, face as usize, corners, w);
            }
            let luminance = 0.2126 * base[0] + 0.7152 * base[1] + 0.0722 * base[2];
            dark_row[x] = (1.0 - tone * luminance).clamp(0.0, 1.0) as f32;
            let px = &mut row[x * 4..x * 4 + 4];
            for k in 0..3 {
                px[k] = (base[k] * tone * 255.0).round().clamp(0.0, 255.0) as u8;
            }
            px[3] = 255;
        }
    });
    View { camera, buffer, projected, rgba, darkness }
}

/// The far occlusion factor per pixel, interpolated from the vertices and smoothed over
/// the pixels the fragment covers (normalised convolution: empty pixels do not darken the
/// outline). Three box passes approach a Gaussian at a cost independent of the width.
fn smoothed_far_factor(buffer: &ZBuffer, projected: &[[f32; 3]], mesh: &Mesh, far_factor: &[f32]) -> Vec<f32> {
    let (width, height) = (buffer.width, buffer.height);
    let mut weighted = vec![0f32; width * height];
    let mut covered = vec![0f32; width * height];
    weighted.par_chunks_mut(width).zip(covered.par_chunks_mut(width)).enumerate().for_each(|(y, (row, mask))| {
        for x in 0..width {
            let face = buffer.face[y * width + x];
            if face == NO_FACE {
                continue;
            }
            let tri = mesh.triangles[face as usize];
            let w = barycentric(projected, tri, x, y);
            row[x] = (0..3).map(|k| far_factor[tri[k] as usize] * w[k]).sum();
            mask[x] = 1.0;
        }
    });
    let radius = ((FAR_OCCLUSION_SMOOTHING_SHARE * width.max(height) as f64) / 3.0).round().max(1.0) as usize;
    for _ in 0..3 {
        for image in [&mut weighted, &mut covered] {
            box_blur_rows(image, width, radius);
            box_blur_columns(image, width, height, radius);
        }
    }
    weighted.iter().zip(&covered).map(|(&v, &c)| if c > 1e-6 { (v / c).clamp(0.0, 1.0) } else { 1.0 }).collect()
}

/// Mean over `2 radius + 1` pixels along each row (the window clipped at the ends).
fn box_blur_rows(image: &mut [f32], width: usize, radius: usize) {
    image.par_chunks_mut(width).for_each(|row| {
        let line = row.to_vec();
        box_mean(&line, radius, |i, v| row[i] = v);
    });
}

/// Mean over `2 radius + 1` pixels along each column.
fn box_blur_columns(image: &mut [f32], width: usize, height: usize, radius: usize) {
    let columns: Vec<Vec<f32>> = (0..width)
        .into_par_iter()
        .map(|x| {
            let column: Vec<f32> = (0..height).map(|y| image[y * width + x]).collect();
            let mut out = vec![0f32; height];
            box_mean(&column, radius, |i, v| out[i] = v);
            out
        })
        .collect();
    for (x, column) in columns.iter().enumerate() {
        for (y, v) in column.iter().enumerate() {
            image[y * width + x] = *v;
        }
    }
}

/// Running-sum mean of `values` over windows of `2 radius + 1` (sums of zeros beyond the
/// ends, so that a normalised convolution stays exact at the border), given to `put`.
fn box_mean(values: &[f32], radius: usize, mut put: impl FnMut(usize, f32)) {
    let n = values.len();
    let window = (2 * radius + 1) as f32;
    let mut sum: f64 = values[..radius.min(n)].iter().map(|&v| v as f64).sum();
    for i in 0..n {
        if i + radius < n {
            sum += values[i + radius] as f64;
        }
        put(i, (sum / window as f64) as f32);
        if i >= radius {
            sum -= values[i - radius] as f64;
        }
    }
}

/// The colour of the surface at barycentric `w` of `face`: the texture when there is one,
/// the vertex colours otherwise, light grey when neither.
fn surface_colour(mesh: &Mesh, face: usize, corners: [usize; 3], w: [f32; 3]) -> [f64; 3] {
    if let (Some(uvs), Some(texture)) = (&mesh.corner_uvs, &mesh.texture) {
        let uv = [0, 1].map(|k| uvs[3 * face][k] * w[0] + uvs[3 * face + 1][k] * w[1] + uvs[3 * face + 2][k] * w[2]);
        let column = ((uv[0].rem_euclid(1.0)) * texture.width as f32) as usize;
        let row = (((1.0 - uv[1]).rem_euclid(1.0)) * texture.height as f32) as usize;
        let i = (row.min(texture.height as usize - 1) * texture.width as usize + column.min(texture.width as usize - 1)) * 4;
        if let Some(px) = texture.rgba.get(i..i + 3) {
            return [px[0], px[1], px[2]].map(|c| c as f64 / 255.0);
        }
    }
    if let Some(colors) = &mesh.colors {
        let mut c = [0.0; 3];
        for (k, &v) in corners.iter().enumerate() {
            for j in 0..3 {
                c[j] += colors[v][j] as f64 * w[k] as f64 / 255.0;
            }
        }
        return c;
    }
    [0.85; 3]
}

/// The outline of the covered pixels as closed polylines in pixel coordinates (pixel
/// corners), traced along pixel borders and simplified to within `tolerance_px`. Loops
/// start at their first corner in row order, so the same buffer always gives the same
/// paths (the SVG, EPS and PDF files are reproducible byte for byte).
pub(crate) fn outline_loops(buffer: &ZBuffer, tolerance_px: f64) -> Vec<Vec<[f64; 2]>> {
    let (w, h) = (buffer.width as i64, buffer.height as i64);
    let covered = |x: i64, y: i64| x >= 0 && y >= 0 && x < w && y < h && buffer.face[(y * w + x) as usize] != NO_FACE;
    // Corners numbered row by row over the (w + 1) x (h + 1) grid of pixel corners.
    let corner = |x: i64, y: i64| (y * (w + 1) + x) as u64;
    let position = |c: u64| [(c % (w as u64 + 1)) as f64, (c / (w as u64 + 1)) as f64];
    // Directed border edges (start, end) with the covered pixel on their left (y down).
    let mut edges: Vec<(u64, u64)> = Vec::new();
    for y in 0..h {
        for x in 0..w {
            if !covered(x, y) {
                continue;
            }
            if !covered(x, y - 1) {
                edges.push((corner(x + 1, y), corner(x, y)));
            }
            if !covered(x, y + 1) {
                edges.push((corner(x, y + 1), corner(x + 1, y + 1)));
            }
            if !covered(x - 1, y) {
                edges.push((corner(x, y), corner(x, y + 1)));
            }
            if !covered(x + 1, y) {
                edges.push((corner(x + 1, y + 1), corner(x + 1, y)));
            }
        }
    }
    // Sorted by start corner, the edges leaving a corner are one run (two at a pixel
    // diagonal); `used` marks the walked ones.
    edges.sort_unstable();
    let mut used = vec![false; edges.len()];
    let take_from = |c: u64, used: &mut [bool]| {
        let first = edges.partition_point(|e| e.0 < c);
        (first..edges.len()).take_while(|&i| edges[i].0 == c).find(|&i| !used[i]).map(|i| {
            used[i] = true;
            edges[i].1
        })
    };
    let mut loops = Vec::new();
    for i in 0..edges.len() {
        if used[i] {
            continue;
        }
        used[i] = true;
        let start = edges[i].0;
        let mut points = vec![position(start)];
        let mut current = edges[i].1;
        while current != start {
            points.push(position(current));
            match take_from(current, &mut used) {
                Some(n) => current = n,
                None => break,
            }
        }
        if points.len() >= 8 {
            loops.push(simplify_closed(&points, tolerance_px));
        }
    }
    loops
}

/// Douglas-Peucker on a closed polyline.
fn simplify_closed(points: &[[f64; 2]], tolerance: f64) -> Vec<[f64; 2]> {
    // Split at the point farthest from the first, simplify both halves.
    let far = (0..points.len())
        .max_by(|&a, &b| distance2(points[0], points[a]).total_cmp(&distance2(points[0], points[b])))
        .unwrap_or(0);
    let mut first: Vec<[f64; 2]> = points[..=far].to_vec();
    let mut second: Vec<[f64; 2]> = points[far..].to_vec();
    second.push(points[0]);
    first = douglas_peucker(&first, tolerance);
    second = douglas_peucker(&second, tolerance);
    first.pop();
    first.extend(second);
    first.pop();
    // The split points themselves may lie on a straight run: drop those.
    let mut i = 0;
    while first.len() > 3 && i < first.len() {
        let n = first.len();
        let (previous, next) = (first[(i + n - 1) % n], first[(i + 1) % n]);
        if segment_distance(first[i], previous, next) <= tolerance {
            first.remove(i);
        } else {
            i += 1;
        }
    }
    first
}

fn douglas_peucker(points: &[[f64; 2]], tolerance: f64) -> Vec<[f64; 2]> {
    if points.len() < 3 {
        return points.to_vec();
    }
    let mut keep = vec![false; points.len()];
    keep[0] = true;
    keep[points.len() - 1] = true;
    let mut stack = vec![(0, points.len() - 1)];
    while let Some((a, b)) = stack.pop() {
        let (mut worst, mut index) = (0.0, 0);
        for i in a + 1..b {
            let d = segment_distance(points[i], points[a], points[b]);
            if d > worst {
                (worst, index) = (d, i);
            }
        }
        if worst > tolerance {
            keep[index] = true;
            stack.push((a, index));
            stack.push((index, b));
        }
    }
    points.iter().zip(keep).filter(|(_, k)| *k).map(|(p, _)| *p).collect()
}

fn distance2(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)
}


/// The crease edges of `mesh` (dihedral angle above `angle_deg`: rim, fracture edges,
/// sharp decoration) as vertex pairs. Found once per drawing: both views test the same
/// edges for visibility with [`visible_crease_lines`].
pub(crate) fn crease_edges(mesh: &Mesh, angle_deg: f64) -> Vec<[u32; 2]> {
    let cos_limit = angle_deg.to_radians().cos();
    let topology = Topology::new(mesh);
    let face_normal = |f: u32| mesh.face_normal_scaled(f as usize).try_normalize(1e-30).unwrap_or_else(Vector::zeros);
    (0..topology.edge_count())
        .into_par_iter()
        .filter(|&edge| {
            topology.faces_of_edge(edge).windows(2).any(|pair| face_normal(pair[0]).dot(&face_normal(pair[1])) <= cos_limit)
        })
        .map(|edge| topology.edges()[edge])
        .collect()
}

/// The crease edges seen in `view` (their midpoint not behind the z-buffer's surface), joined
/// end to end into polylines in pixel coordinates and simplified within `tolerance_px`. One
/// stroke per chain draws proper joins where thousands of separately capped edges would
/// not, and keeps the vector files and the rasterizer's work small.
pub(crate) fn visible_crease_lines(creases: &[[u32; 2]], view: &View, tolerance_px: f64) -> Vec<Vec<[f64; 2]>> {
    let buffer = &view.buffer;
    let pixel = view.camera.pixel_mm as f32;
    let visible: Vec<[u32; 2]> = creases
        .par_iter()
        .copied()
        .filter(|&[a, b]| {
            let (p, q) = (view.projected[a as usize], view.projected[b as usize]);
            let mid = [(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0, (p[2] + q[2]) / 2.0];
            // Midpoints in (-1, 0) would truncate to pixel 0: test the sign first.
            if !(mid[0] >= 0.0 && mid[1] >= 0.0) {
                return false;
            }
            let (x, y) = (mid[0] as usize, mid[1] as usize);
            if x >= buffer.width || y >= buffer.height {
                return false;
            }
            mid[2] <= buffer.depth[y * buffer.width + x] + 2.0 * pixel
        })
        .collect();
    chain_edges(&visible)
        .par_iter()
        .map(|chain| {
            let points: Vec<[f64; 2]> =
                chain.iter().map(|&v| [view.projected[v as usize][0] as f64, view.projected[v as usize][1] as f64]).collect();
            douglas_peucker(&points, tolerance_px)
        })
        .collect()
}

/// `edges` joined into chains of vertices: a chain runs through vertices shared by exactly
/// two edges and stops at ends and branchings; a closed loop repeats its first vertex.
pub(crate) fn chain_edges(edges: &[[u32; 2]]) -> Vec<Vec<u32>> {
    // Incident edges of each vertex, as (vertex, edge) pairs sorted by vertex.
    let mut incidence: Vec<(u32, u32)> = Vec::with_capacity(edges.len() * 2);
    for (e, &[a, b]) in edges.iter().enumerate() {
        incidence.push((a, e as u32));
        incidence.push((b, e as u32));
    }
    incidence.sort_unstable();
    let incident = |v: u32| {
        let start = incidence.partition_point(|&(w, _)| w < v);
        let end = incidence.partition_point(|&(w, _)| w <= v);
        &incidence[start..end]
    };
    let mut used = vec![false; edges.len()];
    // From the end vertex `from` of the chain, follow the one unused edge while `from` has
    // exactly two edges.
    let extend = |chain: &mut Vec<u32>, used: &mut Vec<bool>| loop {
        let from = *chain.last().unwrap_or(&0);
        let around = incident(from);
        if around.len() != 2 {
            return;
        }
        let Some(&(_, e)) = around.iter().find(|&&(_, e)| !used[e as usize]) else { return };
        used[e as usize] = true;
        let [a, b] = edges[e as usize];
        chain.push(if a == from { b } else { a });
    };
    let mut chains = Vec::new();
    for (e, &[a, b]) in edges.iter().enumerate() {
        if used[e] {
            continue;
        }
        used[e] = true;
        let mut forward = vec![a, b];
        extend(&mut forward, &mut used);
        let mut backward = vec![a];
        extend(&mut backward, &mut used);
        backward.reverse();
        backward.pop();
        backward.extend(forward);
        chains.push(backward);
    }
    chains
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_mean_of_a_step_is_a_ramp_as_wide_as_the_window() {
        let values: Vec<f32> = (0..20).map(|i| if i < 10 { 0.0 } else { 1.0 }).collect();
        let mut out = [0f32; 20];
        box_mean(&values, 2, |i, v| out[i] = v);
        assert_eq!(&out[..8], &[0.0; 8]);
        assert_eq!(&out[12..18], &[1.0; 6]);
        // Zeros beyond the ends: the normalised convolution divides them out.
        for (i, expected) in [(8, 0.2), (9, 0.4), (10, 0.6), (11, 0.8), (18, 0.8), (19, 0.6)] {
            assert!((out[i] - expected).abs() < 1e-6, "{i}: {}", out[i]);
        }
    }

    #[test]
    fn smoothing_keeps_a_uniform_far_factor_uniform_up_to_the_outline() {
        // A square of two triangles covering part of a 40 x 30 view.
        let mesh = Mesh::new(
            vec![Point::new(5.0, 4.0, 0.0), Point::new(30.0, 4.0, 0.0), Point::new(30.0, 25.0, 0.0), Point::new(5.0, 25.0, 0.0)],
            vec![[0, 1, 2], [0, 2, 3]],
        );
        let projected: Vec<[f32; 3]> = mesh.positions.iter().map(|p| [p.x as f32, p.y as f32, 0.0]).collect();
        let buffer = rasterize_parallel(40, 30, &projected, &mesh.triangles);
        let smoothed = smoothed_far_factor(&buffer, &projected, &mesh, &[0.6; 4]);
        for (i, &face) in buffer.face.iter().enumerate() {
            if face != NO_FACE {
                assert!((smoothed[i] - 0.6).abs() < 1e-5, "pixel {i}: {}", smoothed[i]);
            }
        }
        // A factor that changes from one corner to the other changes smoothly.
        let ramp = smoothed_far_factor(&buffer, &projected, &mesh, &[0.2, 1.0, 1.0, 0.2]);
        let row = 15 * 40;
        let steps: Vec<f32> = (6..29).map(|x| ramp[row + x + 1] - ramp[row + x]).collect();
        assert!(steps.iter().all(|d| *d >= -1e-6 && *d < 0.08), "{steps:?}");
    }

    #[test]
    fn edges_chain_through_degree_two_vertices_and_stop_at_branches() {
        // A path 0-1-2-3 given out of order and reversed, a loop 10-11-12, and a branch
        // at 20 with three spokes.
        let edges = [[2, 1], [3, 2], [0, 1], [10, 11], [12, 10], [11, 12], [20, 21], [22, 20], [20, 23]];
        let mut chains = chain_edges(&edges);
        let path = chains.iter().find(|c| c.contains(&0)).unwrap().clone();
        assert!(path == vec![0, 1, 2, 3] || path == vec![3, 2, 1, 0], "{path:?}");
        let cycle = chains.iter().find(|c| c.contains(&10)).unwrap();
        assert_eq!(cycle.len(), 4, "a loop of 3 edges repeats its start: {cycle:?}");
        assert_eq!(cycle.first(), cycle.last());
        chains.retain(|c| c.contains(&20));
        assert_eq!(chains.len(), 3, "three spokes from a branch: {chains:?}");
        let total: usize = chain_edges(&edges).iter().map(|c| c.len() - 1).sum();
        assert_eq!(total, edges.len(), "every edge drawn once");
    }

    #[test]
    fn outline_of_a_filled_square_is_its_four_corners() {
        let mut buffer = ZBuffer::new(10, 10);
        for y in 2..7 {
            for x in 3..8 {
                buffer.face[y * 10 + x] = 0;
            }
        }
        let loops = outline_loops(&buffer, 0.5);
        assert_eq!(loops.len(), 1);
        let mut corners = loops[0].clone();
        corners.sort_by(|a, b| a.partial_cmp(b).unwrap());
        assert_eq!(corners, vec![[3.0, 2.0], [3.0, 7.0], [8.0, 2.0], [8.0, 7.0]]);
    }

    #[test]
    fn outline_is_the_same_on_every_call() {
        // Two 3x3 blocks meeting diagonally (a corner with two outgoing edges) and a ring.
        let mut buffer = ZBuffer::new(16, 16);
        for (x0, y0) in [(2, 2), (5, 5)] {
            for y in y0..y0 + 3 {
                for x in x0..x0 + 3 {
                    buffer.face[y * 16 + x] = 0;
                }
            }
        }
        for y in 9..15 {
            for x in 9..15 {
                if !(11..13).contains(&x) || !(11..13).contains(&y) {
                    buffer.face[y * 16 + x] = 0;
                }
            }
        }
        let first = outline_loops(&buffer, 0.1);
        assert!(first.len() >= 2 && first.iter().all(|l| l.len() >= 4), "{first:?}");
        for _ in 0..5 {
            assert_eq!(outline_loops(&buffer, 0.1), first);
        }
    }
}
