//! Which skin of the fragment a vertex is on: the surface choice, and the classification
//! by the vertex's normal and by the smooth region around it.

use nalgebra::Vector2;
use serde::{Deserialize, Serialize};

use crate::mesh::topology::{Topology, UnionFind};
use crate::mesh::{Mesh, Point, Vector};
use crate::orient::Skin;
use crate::{Error, Result};

crate::vocabulary! {
    /// Which skin of the fragment a criterion uses (the paper's "surface choice").
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
    pub enum Surface: "surface", "surfaces" {
        /// The inside of the vessel (normals towards the axis).
        Inner = "inner" => "Inner surface only",
        /// The outside of the vessel (normals away from the axis).
        Outer = "outer" => "Outer surface only",
        /// Both skins, each section of each skin treated on its own.
        #[default]
        Both = "both" => "Inner and outer surface",
    }
}

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

/// Vertex normals: the mesh's own, or area-weighted face normals when it has none.
pub(super) fn vertex_normals(mesh: &Mesh) -> Result<Vec<Vector>> {
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
pub(super) fn skin_by_normal(p: &Point, n: &Vector) -> Option<Skin> {
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
pub(super) fn skins_by_smooth_regions(mesh: &Mesh, points: &[Point]) -> Vec<Option<Skin>> {
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
