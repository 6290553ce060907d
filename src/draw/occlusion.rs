//! Ambient occlusion per vertex (Wilczek et al. 2018, section 2.4.3, after MeshLab's
//! "shadevis"): the share of the sky a vertex sees, weighted by the cosine between its
//! normal and each direction. Visibility is read from orthographic depth maps rendered
//! along many directions evenly spread over the sphere, in parallel: for a 500k-face scan
//! this is one rasterization per direction instead of one ray per vertex and direction.

use rayon::prelude::*;

use super::raster::{floor_to_i64, rasterize_into, OrthographicCamera, ZBuffer};
use crate::mesh::{Mesh, Vector};
use crate::{Error, Result};

/// Settings of [`ambient_occlusion`].
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct OcclusionOptions {
    /// Number of directions over the whole sphere (MeshLab's "requested views").
    pub directions: usize,
    /// Depth-map size in pixels across the mesh's bounding sphere.
    pub resolution: usize,
}

impl Default for OcclusionOptions {
    fn default() -> Self {
        OcclusionOptions { directions: 128, resolution: 1024 }
    }
}

/// Per-vertex ambient light in `[0, 1]`: 1 for a vertex open to the whole hemisphere
/// above it, 0 for one no direction reaches. Computed per face (barycentre, face normal,
/// the sum of cosines over the open directions) and averaged to the vertices weighted by
/// area, as MeshLab does. Errors on a mesh without faces or on zero directions or
/// resolution.
pub fn ambient_occlusion(mesh: &Mesh, options: &OcclusionOptions) -> Result<Vec<f32>> {
    Ok(light_from_directions(mesh, options, None)?.full)
}

/// Ambient light per vertex split by the occluders' distance, for drawings.
#[derive(Clone, Debug, PartialEq)]
pub struct NearAndFarLight {
    /// [`ambient_occlusion`] itself: every occluder counts, at any distance.
    pub full: Vec<f32>,
    /// Obscurance (Zhukov et al. 1998): an occluder darkens fully when it touches the
    /// surface and less with its distance, not at all beyond the reach. Never below `full`.
    pub near: Vec<f32>,
}

/// [`ambient_occlusion`] and, from the same depth maps, the light that occluders within
/// `reach_mm` take away ([`NearAndFarLight::near`]). With a few dozen directions, the far
/// occluders (a sherd's own rims seen across its concave inside) cast hard-edged shadows,
/// one per direction, that show as polygonal patches; the near ones (grooves, creases,
/// rills) are the detail a drawing wants sharp. A drawing keeps `near` and smooths the rest
/// (`full / near`) over the surface. Errors as [`ambient_occlusion`], and on a reach that is
/// not positive.
pub fn near_and_far_light(mesh: &Mesh, options: &OcclusionOptions, reach_mm: f64) -> Result<NearAndFarLight> {
    if !(reach_mm.is_finite() && reach_mm > 0.0) {
        return Err(Error::InvalidArgument(format!("the occlusion reach must be positive, got {reach_mm} mm")));
    }
    light_from_directions(mesh, options, Some(reach_mm as f32))
}

/// The light of every face summed over the directions, then averaged to the vertices; the
/// near light only when a reach is given (`near` is then filled, otherwise empty).
fn light_from_directions(mesh: &Mesh, options: &OcclusionOptions, reach_mm: Option<f32>) -> Result<NearAndFarLight> {
    if mesh.triangles.is_empty() {
        return Err(Error::InvalidArgument("ambient occlusion needs a mesh with faces, not a point cloud".into()));
    }
    if options.directions == 0 || options.resolution < 8 {
        return Err(Error::InvalidArgument(format!(
            "ambient occlusion needs directions > 0 and resolution >= 8, got {} and {}",
            options.directions, options.resolution
        )));
    }
    // As MeshLab: per face, from its barycentre along its normal, then the area-weighted
    // mean of the faces around each vertex.
    let face_count = mesh.face_count();
    let near_count = if reach_mm.is_some() { face_count } else { 0 };
    let mut normals = Vec::with_capacity(face_count);
    let mut areas = Vec::with_capacity(face_count);
    for f in 0..face_count {
        let n = mesh.face_normal_scaled(f);
        areas.push(0.5 * n.norm());
        normals.push(n.try_normalize(1e-30).unwrap_or_else(Vector::zeros));
    }
    let (lo, hi) = mesh.bounding_box().expect("a mesh with faces has vertices");
    let diameter = (hi - lo).norm().max(1e-9);
    let pixel_mm = diameter / options.resolution as f64;
    let directions = sphere_directions(options.directions);
    // Each task sums the light its directions bring to every face (all occluders, and
    // near ones only); sums are added at the end.
    let zero = || (vec![0f32; face_count], vec![0f32; near_count]);
    let (full_light, near_light) = directions
        .par_iter()
        .fold(
            || (zero(), None::<ZBuffer>),
            |((mut full, mut near), buffer), sky| {
                // Look from the sky towards the mesh: depth grows away from the sky.
                let camera = OrthographicCamera::fit(&mesh.positions, -sky, any_perpendicular(sky), pixel_mm, 2);
                let mut buffer = match buffer {
                    Some(mut b) if b.width == camera.width && b.height == camera.height => {
                        b.clear();
                        b
                    }
                    _ => ZBuffer::new(camera.width, camera.height),
                };
                // One direction per task already: projecting in parallel too only adds
                // the splitting.
                let projected: Vec<[f32; 3]> = mesh.positions.iter().map(|p| camera.project(p)).collect();
                rasterize_into(&mut buffer, &projected, &mesh.triangles);
                for (f, tri) in mesh.triangles.iter().enumerate() {
                    let cosine = normals[f].dot(sky) as f32;
                    if cosine <= 0.0 {
                        continue;
                    }
                    // Projection is affine: the centre's image is the corners' mean.
                    let [a, b, c] = tri.map(|v| projected[v as usize]);
                    let p = [0, 1, 2].map(|k| (a[k] + b[k] + c[k]) / 3.0);
                    // The face is open if it is itself seen around its centre, or if nothing
                    // stands in front of the interpolated depth there. The small
                    // slope-scaled bias absorbs the map's sampling: larger ones hide the
                    // grazing self-occlusion of rough surfaces that MeshLab's rays see
                    // (tuned on A011 against pymeshlab, tests/occlusion.rs).
                    let around = Neighbourhood::of(&buffer, p[0], p[1]);
                    let occluder_distance_mm = if owns_nearby_pixel(&buffer, &around, f as u32) {
                        f32::INFINITY
                    } else {
                        p[2] - bilinear_depth(&buffer, &around, p[0], p[1])
                    };
                    let open = occluder_distance_mm == f32::INFINITY || {
                        let tangent = (1.0 - cosine * cosine).sqrt() / cosine.max(0.2);
                        occluder_distance_mm <= pixel_mm as f32 * (0.05 + 0.2 * tangent)
                    };
                    if open {
                        full[f] += cosine;
                    }
                    if let Some(reach_mm) = reach_mm {
                        // Smoothstep: a near shadow fades out with the occluder's distance
                        // instead of ending at an edge.
                        let t = if open { 1.0 } else { (occluder_distance_mm / reach_mm).min(1.0) };
                        near[f] += cosine * t * t * (3.0 - 2.0 * t);
                    }
                }
                ((full, near), Some(buffer))
            },
        )
        .map(|(light, _)| light)
        .reduce(zero, |(mut full, mut near), (full2, near2)| {
            full.iter_mut().zip(&full2).for_each(|(a, b)| *a += b);
            near.iter_mut().zip(&near2).for_each(|(a, b)| *a += b);
            (full, near)
        });
    // A face open to its whole hemisphere sums cosines to about directions / 4.
    let full_hemisphere = options.directions as f64 / 4.0;
    let to_vertices = |light: &[f32]| -> Vec<f32> {
        if light.is_empty() {
            return Vec::new();
        }
        let mut sum = vec![0f64; mesh.vertex_count()];
        let mut weight = vec![0f64; mesh.vertex_count()];
        for (f, t) in mesh.triangles.iter().enumerate() {
            for &v in t {
                sum[v as usize] += light[f] as f64 * areas[f];
                weight[v as usize] += areas[f];
            }
        }
        sum.iter().zip(&weight).map(|(&s, &w)| if w > 0.0 { (s / w / full_hemisphere).min(1.0) as f32 } else { 1.0 }).collect()
    };
    Ok(NearAndFarLight { full: to_vertices(&full_light), near: to_vertices(&near_light) })
}

/// The four pixels whose centres surround a point: the top-left one's column and row and,
/// when all four lie in the buffer (as they do but at its border), its index.
struct Neighbourhood {
    x0: i64,
    y0: i64,
    index: Option<usize>,
}

impl Neighbourhood {
    fn of(buffer: &ZBuffer, x: f32, y: f32) -> Self {
        let (x0, y0) = (floor_to_i64(x - 0.5), floor_to_i64(y - 0.5));
        let inside = x0 >= 0 && y0 >= 0 && x0 < buffer.width as i64 - 1 && y0 < buffer.height as i64 - 1;
        Neighbourhood { x0, y0, index: inside.then(|| y0 as usize * buffer.width + x0 as usize) }
    }
}

/// True when one of the four pixel centres around `(x, y)` shows `face`.
fn owns_nearby_pixel(buffer: &ZBuffer, around: &Neighbourhood, face: u32) -> bool {
    if let Some(i) = around.index {
        let w = buffer.width;
        return [i, i + 1, i + w, i + w + 1].iter().any(|&j| buffer.face[j] == face);
    }
    for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
        let (px, py) = (around.x0 + dx, around.y0 + dy);
        if px >= 0 && py >= 0 && px < buffer.width as i64 && py < buffer.height as i64 && buffer.face[py as usize * buffer.width + px as usize] == face {
            return true;
        }
    }
    false
}

/// The depth bilinearly interpolated at `(x, y)`; infinite (open sky) next to an empty
/// pixel or the border.
fn bilinear_depth(buffer: &ZBuffer, around: &Neighbourhood, x: f32, y: f32) -> f32 {
    let Some(i) = around.index else { return f32::INFINITY };
    let w = buffer.width;
    let (tx, ty) = ((x - 0.5) - around.x0 as f32, (y - 0.5) - around.y0 as f32);
    let weights = [(1.0 - tx) * (1.0 - ty), tx * (1.0 - ty), (1.0 - tx) * ty, tx * ty];
    let mut sum = 0.0;
    for (j, weight) in [i, i + 1, i + w, i + w + 1].into_iter().zip(weights) {
        let d = buffer.depth[j];
        if !d.is_finite() {
            return f32::INFINITY;
        }
        sum += weight * d;
    }
    sum
}

/// `count` unit vectors evenly spread over the sphere (Fibonacci spiral).
pub fn sphere_directions(count: usize) -> Vec<Vector> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..count)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / count as f64;
            let r = (1.0 - z * z).sqrt();
            let theta = golden * i as f64;
            Vector::new(r * theta.cos(), r * theta.sin(), z)
        })
        .collect()
}

fn any_perpendicular(v: &Vector) -> Vector {
    let other = if v.x.abs() < 0.9 { Vector::x() } else { Vector::y() };
    v.cross(&other).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Point;


    /// A flat square floor (many vertices) with a wall standing on half of its edge.
    fn floor_with_wall() -> Mesh {
        let n = 21;
        let mut positions = Vec::new();
        let mut triangles = Vec::new();
        for j in 0..n {
            for i in 0..n {
                positions.push(Point::new(i as f64, j as f64, 0.0));
            }
        }
        for j in 0..n - 1 {
            for i in 0..n - 1 {
                let v = (j * n + i) as u32;
                triangles.push([v, v + 1, v + n as u32 + 1]);
                triangles.push([v, v + n as u32 + 1, v + n as u32]);
            }
        }
        // Wall along x = 0..20 at y = 0 (the floor's edge), 20 high, facing +y.
        let base = positions.len() as u32;
        positions.extend([Point::new(0.0, 0.0, 0.0), Point::new(20.0, 0.0, 0.0), Point::new(20.0, 0.0, 20.0), Point::new(0.0, 0.0, 20.0)]);
        triangles.push([base, base + 2, base + 1]);
        triangles.push([base, base + 3, base + 2]);
        let mut mesh = Mesh::new(positions, triangles);
        let mut normals = vec![Vector::z(); mesh.vertex_count()];
        for n in &mut normals[base as usize..] {
            *n = Vector::y();
        }
        mesh.normals = Some(normals);
        mesh
    }

    #[test]
    fn open_floor_is_lit_and_the_corner_by_the_wall_is_darker() {
        let mesh = floor_with_wall();
        let ao = ambient_occlusion(&mesh, &OcclusionOptions { directions: 256, resolution: 256 }).unwrap();
        let at = |x: usize, y: usize| ao[y * 21 + x];
        // Far from the wall the floor sees most of its hemisphere; next to the wall
        // (height 20) about half of it (cosine-weighted: a bit more than half).
        assert!(at(10, 20) > 0.85, "open floor {}", at(10, 20));
        assert!(at(10, 1) < 0.7, "by the wall {}", at(10, 1));
        assert!(at(10, 1) < at(10, 5) && at(10, 5) < at(10, 20));
    }

    #[test]
    fn near_light_drops_only_what_near_occluders_take() {
        let mesh = floor_with_wall();
        let options = OcclusionOptions { directions: 256, resolution: 256 };
        let light = near_and_far_light(&mesh, &options, 3.0).unwrap();
        // The same light (up to the order rayon adds the directions' sums in).
        let alone = ambient_occlusion(&mesh, &options).unwrap();
        assert!(light.full.iter().zip(&alone).all(|(a, b)| (a - b).abs() < 1e-5));
        assert!(light.near.iter().zip(&light.full).all(|(n, f)| n >= f), "near light below the full light");
        let near = |x: usize, y: usize| light.near[y * 21 + x];
        let full = |x: usize, y: usize| light.full[y * 21 + x];
        // 10 mm from the wall, beyond the 3 mm reach: the wall takes light from the full
        // field only; 1 mm from it, from the near field too.
        assert!(near(10, 10) > 0.97 && full(10, 10) < near(10, 10) - 0.05, "near {} full {}", near(10, 10), full(10, 10));
        assert!(near(10, 1) < near(10, 10) - 0.1, "by the wall {} vs {}", near(10, 1), near(10, 10));
        for reach in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(near_and_far_light(&mesh, &options, reach).is_err(), "reach {reach} accepted");
        }
    }

    #[test]
    fn directions_are_unit_and_balanced() {
        let d = sphere_directions(100);
        assert!(d.iter().all(|v| (v.norm() - 1.0).abs() < 1e-12));
        let sum: Vector = d.iter().sum();
        assert!(sum.norm() < 1.0, "{sum:?}");
        assert!(ambient_occlusion(&Mesh::new(vec![Point::origin()], vec![]), &OcclusionOptions::default()).is_err());
    }
}
