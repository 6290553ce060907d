//! What becomes of a synthetic shell once it is built: its part, colour, noise and rigid
//! motion, its normals, and the ground truth written beside it.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use super::colour::ClayColour;
use super::deform::Deformation;
use super::shell::Shell;
use super::{motion, truth, GroundTruth, HardCase, RigidMotion, SherdPart, SurfaceKind, SynthSherd, VesselProfile, VesselTruth, PROFILE_STEP_MM};
use crate::axis::Axis;
use crate::mesh::normals::{compute_vertex_normals, NormalWeighting};
use crate::mesh::{Mesh, Point, Vector};

/// The part a shell is, from the arc-length band its cells cover and whether it has rim.
pub(super) fn classify(profile: &VesselProfile, shell: &Shell) -> SherdPart {
    let edge = profile.base_edge_s_mm();
    let has_base = shell.s_range_mm[0] < edge;
    match (shell.has_rim, has_base) {
        (true, true) => SherdPart::RimToBase,
        (true, false) => SherdPart::Rim,
        (false, true) if shell.s_range_mm[1] <= edge => SherdPart::Flat,
        (false, true) => SherdPart::Base,
        (false, false) => SherdPart::Body,
    }
}

pub(super) fn vessel_truth(profile: &VesselProfile, deformation: &Deformation) -> VesselTruth {
    VesselTruth {
        shape: profile.shape,
        rim_radius_mm: profile.rim_radius_mm(),
        base_radius_mm: profile.base_radius_mm(),
        height_mm: profile.height_mm(),
        wall_thickness_mm: profile.wall_thickness_mm,
        rim_form: profile.rim_form,
        base_form: profile.base_form,
        deformation: deformation.clone(),
    }
}

/// Outer-skin extent (mm) below which a fragment counts as too small to orient.
const TINY_EXTENT_MM: f64 = 25.0;

/// The hard case a fragment is, when it was not asked for but came out so (a vessel's
/// base pieces, slivers, pieces of a globular body): a flat base piece, a piece whose
/// outer skin is under 25 mm across, or a piece lying wholly on a spherical zone.
fn inferred_hard_case(profile: &VesselProfile, shell: &Shell, part: SherdPart) -> Option<HardCase> {
    if part == SherdPart::Flat {
        return Some(HardCase::FlatBase);
    }
    let outer = shell.positions.iter().zip(&shell.vertex_kinds).filter(|(_, kind)| **kind == SurfaceKind::Outer);
    let (low, high) = outer.fold((Point::from([f64::INFINITY; 3]), Point::from([f64::NEG_INFINITY; 3])), |(low, high), (p, _)| (low.inf(p), high.sup(p)));
    if (high - low).norm() < TINY_EXTENT_MM {
        return Some(HardCase::Tiny);
    }
    let [band_low, band_high] = profile.spherical_band_s_mm()?;
    (shell.s_range_mm[0] >= band_low && shell.s_range_mm[1] <= band_high).then_some(HardCase::NearSpherical)
}

/// What happens to a shell after it is built: colour, noise, motion.
pub(super) struct Surface {
    pub(super) noise_mm: f64,
    pub(super) relief: super::Relief,
    pub(super) noise_seed: u64,
    /// `None`: stay in the vessel frame.
    pub(super) motion_seed: Option<u64>,
    pub(super) colour: Option<ClayColour>,
    pub(super) hard_case: Option<HardCase>,
    pub(super) fragment_index: Option<usize>,
}

/// Colours, noise, motion, normals and truth for a shell.
pub(super) fn finish(seed: u64, shell: Shell, profile: &VesselProfile, deformation: &Deformation, part: SherdPart, surface: &Surface) -> SynthSherd {
    let hard_case = surface.hard_case.or_else(|| inferred_hard_case(profile, &shell, part));
    let Shell { positions, triangles, vertex_kinds, face_kinds, .. } = shell;
    let mut mesh = Mesh::new(positions, triangles);
    if let Some(colour) = &surface.colour {
        mesh.colors = Some(mesh.positions.par_iter().zip(&vertex_kinds).map(|(p, kind)| colour.at(p, *kind)).collect());
    }
    super::relief::add_relief(&mut mesh, &surface.relief, seed);
    motion::add_noise(&mut mesh.positions, surface.noise_mm, surface.noise_seed);
    let isometry = match surface.motion_seed {
        Some(motion_seed) => {
            let centroid = mesh.centroid().unwrap_or_else(Point::origin);
            motion::random_motion(&mut ChaCha8Rng::seed_from_u64(motion_seed), &centroid, 30.0)
        }
        None => nalgebra::Isometry3::identity(),
    };
    mesh.transform(&isometry);
    mesh.normals = Some(compute_vertex_normals(&mesh, NormalWeighting::Area));
    let axis = Axis::new(isometry * Point::origin(), isometry * Vector::z());
    let rim_points: Vec<Point> = mesh
        .triangles
        .iter()
        .zip(&face_kinds)
        .filter(|(_, kind)| **kind == SurfaceKind::Rim)
        .flat_map(|(triangle, _)| triangle.map(|v| mesh.positions[v as usize]))
        .collect();
    let heights = mesh.positions.iter().map(|p| axis.height_of(p));
    let (low, high) = heights.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), h| (lo.min(h), hi.max(h)));
    let truth = GroundTruth {
        axis,
        rim_radius_mm: matches!(part, SherdPart::Rim | SherdPart::RimToBase).then(|| profile.rim_radius_mm()),
        base_radius_mm: matches!(part, SherdPart::Base | SherdPart::RimToBase).then(|| profile.base_radius_mm()),
        sector_angle_deg: truth::sector_angle_deg(&mesh.positions, &axis),
        rim_sector_angle_deg: (!rim_points.is_empty()).then(|| truth::sector_angle_deg(&rim_points, &axis)),
        height_mm: (high - low).max(0.0),
        profile: profile.skin_polyline(1.0, PROFILE_STEP_MM),
        inner_profile: profile.skin_polyline(-1.0, PROFILE_STEP_MM),
        part,
        hard_case,
        noise_mm: surface.noise_mm,
        relief: surface.relief,
        fragment_index: surface.fragment_index,
        deformation_bound_mm: deformation.bound_mm(profile.max_radius_mm()),
        vessel: vessel_truth(profile, deformation),
        motion: RigidMotion::from_isometry(&isometry),
        seed,
    };
    SynthSherd { mesh, truth, vertex_kinds, face_kinds }
}

