//! Synthetic sherds with known axes: a random vessel profile revolved with wall
//! thickness, deformed, made noisy, broken along a Voronoi diagram and moved by random
//! rigid motions. The test bed of every later layer: its tests know the true axis.
//!
//! * [`synthetic_sherd`] makes one fragment of a requested part ([`SherdPart`]) at a
//!   requested resolution, with its [`GroundTruth`]; [`SherdOptions::hard_case`] gives the
//!   fragments orientation must refuse (flat base piece, near-spherical piece, tiny piece).
//! * [`generate_vessel`] breaks a whole vessel into fragments.
//!
//! Every fragment is a closed, watertight, outward-oriented triangle mesh with
//! area-weighted vertex normals, and the same seed always gives the same bytes.

pub(crate) mod colour;
pub(crate) mod deform;
mod finish;
pub(crate) mod fracture;
pub(crate) mod motion;
mod plan;
pub mod relief;
pub mod shape;
pub(crate) mod shell;
pub mod truth;
pub mod write;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

pub use deform::Deformation;
pub use shape::{BaseForm, ProfileForms, RimForm, VesselProfile, VesselShape};
pub use truth::{GroundTruth, HardCase, RigidMotion, SherdPart, SurfaceKind, VesselTruth};
pub use relief::Relief;
pub use write::{read_truth, write_sherd};

use crate::mesh::Mesh;
use colour::ClayColour;
use finish::{classify, finish, vessel_truth, Surface};
use fracture::{clean_mask, mid_surface_point, RoughVoronoi};
use plan::{cell_at, mesh_planned_fragment, plan_fragment, random_part, surface_areas};
use shell::{build_shell, ParamGrid};

/// How to make one synthetic sherd.
#[derive(Clone, Debug, PartialEq)]
pub struct SherdOptions {
    /// Approximate number of triangles (the result is within about 15 %).
    pub target_faces: usize,
    /// Standard deviation of the Gaussian noise added to every coordinate, mm.
    pub noise_mm: f64,
    /// Slow undulation of the surface along its normals, neighbours moving together.
    pub relief: Relief,
    /// The part wanted; `None` draws rim, body, base or complete profile at random.
    pub part: Option<SherdPart>,
    /// Range of the circumference angle the fragment should span, degrees (clamped to
    /// 3-150; the break lines' roughness makes the result differ by a few degrees).
    pub sector_deg: [f64; 2],
    /// The vessel family; `None` draws an ordinary one at random.
    pub shape: Option<VesselShape>,
    /// Size of the hand-made irregularities (ovality, rim tilt, wobble): 0 gives an
    /// ideal surface of revolution, 1 a carefully thrown vessel.
    pub deformation_scale: f64,
    /// How far the break lines wander from straight, mm.
    pub roughness_mm: f64,
    /// Move the fragment by a random rigid motion (otherwise it stays in the vessel
    /// frame: axis on z, standing plane z = 0).
    pub random_motion: bool,
    /// Make one of the fragments orientation must refuse (overrides `part` and, for
    /// near-spherical pieces, `shape`).
    pub hard_case: Option<HardCase>,
    /// Give the vertices fired-clay colours.
    pub colours: bool,
    /// The lip and base forms the vessel is drawn from.
    pub forms: ProfileForms,
}

impl Default for SherdOptions {
    fn default() -> Self {
        SherdOptions {
            target_faces: 20_000,
            noise_mm: 0.02,
            relief: Relief::default(),
            part: None,
            sector_deg: [15.0, 60.0],
            shape: None,
            deformation_scale: 1.0,
            roughness_mm: 1.5,
            random_motion: true,
            hard_case: None,
            colours: true,
            forms: ProfileForms::default(),
        }
    }
}

impl SherdOptions {
    /// Default options for a fragment of `part`.
    pub fn for_part(part: SherdPart) -> Self {
        SherdOptions { part: Some(part), ..Default::default() }
    }

    /// Default options for one of the hard cases.
    pub fn hard_case(case: HardCase) -> Self {
        SherdOptions { hard_case: Some(case), ..Default::default() }
    }

    /// An ideal fragment: no deformation, no noise (for tests of exact recovery).
    pub fn ideal(self) -> Self {
        SherdOptions { noise_mm: 0.0, relief: Relief::default(), deformation_scale: 0.0, ..self }
    }
}

/// A synthetic sherd: a closed mesh with vertex normals, in the scan frame, and the truth.
#[derive(Clone, Debug)]
pub struct SynthSherd {
    /// The fragment's surface (positions, outward triangles, vertex normals), mm.
    pub mesh: Mesh,
    /// What the fragment really is.
    pub truth: GroundTruth,
    /// Outer or inner skin, per vertex.
    pub vertex_kinds: Vec<SurfaceKind>,
    /// Outer skin, inner skin, fracture or rim (top or rounding), per face.
    pub face_kinds: Vec<SurfaceKind>,
}

/// How to break a whole vessel.
#[derive(Clone, Debug, PartialEq)]
pub struct VesselOptions {
    /// The vessel family; `None` draws an ordinary one at random.
    pub shape: Option<VesselShape>,
    /// Number of Voronoi seeds (fragments), at least 2.
    pub fragment_count: usize,
    /// Size of the mesh cells, mm (each cell gives four triangles).
    pub cell_size_mm: f64,
    /// Standard deviation of the Gaussian noise added to every coordinate, mm.
    pub noise_mm: f64,
    /// Slow undulation of the surface along its normals, neighbours moving together.
    pub relief: Relief,
    /// As [`SherdOptions::deformation_scale`].
    pub deformation_scale: f64,
    /// How far the break lines wander from straight, mm.
    pub roughness_mm: f64,
    /// Move each fragment by its own random rigid motion; otherwise they stay in the
    /// vessel frame and fit together.
    pub random_motion: bool,
    /// Give the vertices fired-clay colours.
    pub colours: bool,
    /// The lip and base forms the vessel is drawn from.
    pub forms: ProfileForms,
}

impl Default for VesselOptions {
    fn default() -> Self {
        VesselOptions {
            shape: None,
            fragment_count: 24,
            cell_size_mm: 2.0,
            noise_mm: 0.02,
            relief: Relief::default(),
            deformation_scale: 1.0,
            roughness_mm: 1.5,
            random_motion: false,
            colours: true,
            forms: ProfileForms::default(),
        }
    }
}

/// A whole broken vessel.
#[derive(Clone, Debug)]
pub struct SynthVessel {
    /// The fragments, one per Voronoi cell, in seed order.
    pub fragments: Vec<SynthSherd>,
    /// The vessel's outer profile `[r, z]` from the base centre to the rim, mm.
    pub profile: Vec<[f64; 2]>,
    /// The vessel's measurements and deformation.
    pub vessel: VesselTruth,
}

/// Attempts at drawing a vessel and a fragment plan before settling for what came out.
const MAX_ATTEMPTS: usize = 24;
/// Spacing of the points of the truth profiles, mm.
pub(super) const PROFILE_STEP_MM: f64 = 0.5;

/// Most triangles a synthetic sherd may be asked for: ten times a large real scan. The
/// command line and the C ABI refuse more, and the mesher never plans more.
pub const MAX_TARGET_FACES: usize = 10_000_000;

/// The finest mesh tried when the resolution asked for cannot hold a fragment: past the
/// default (20,000 faces), at which every fragment plan is meshed.
const MAX_FALLBACK_TARGET_FACES: usize = 80_000;

/// One synthetic sherd for `seed` (deterministic: the same seed and options give the
/// same mesh, whatever the number of threads).
pub fn synthetic_sherd(seed: u64, options: &SherdOptions) -> SynthSherd {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let wanted_part = match options.hard_case {
        Some(HardCase::FlatBase) => SherdPart::Flat,
        Some(HardCase::NearSpherical) | Some(HardCase::Tiny) => SherdPart::Body,
        None => options.part.unwrap_or_else(|| random_part(&mut rng)),
    };
    let shape_of = |rng: &mut ChaCha8Rng| match options.hard_case {
        Some(HardCase::NearSpherical) => VesselShape::Globular,
        _ => options.shape.unwrap_or_else(|| VesselShape::random(rng)),
    };
    // A mesh asked for a few dozen faces may be too coarse to hold any fragment's outline;
    // then finer ones are tried, up to past the default resolution, where every plan
    // holds its own seed.
    let mut target_faces = options.target_faces;
    let fallback = loop {
        let mut fallback = None;
        for attempt in 0..MAX_ATTEMPTS {
            let profile = VesselProfile::random(shape_of(&mut rng), &options.forms, &mut rng);
            let deformation = Deformation::random(&mut rng, options.deformation_scale, profile.height_mm());
            let Some(plan) = plan_fragment(&profile, wanted_part, options, &mut rng) else {
                continue;
            };
            let voronoi = RoughVoronoi::new(plan.seeds.clone(), options.roughness_mm, &mut rng);
            let Some(shell) = mesh_planned_fragment(&profile, &deformation, &voronoi, &plan, target_faces) else {
                continue;
            };
            let part = classify(&profile, &shell);
            let surface = Surface {
                noise_mm: options.noise_mm,
                relief: options.relief,
                noise_seed: rng.random(),
                motion_seed: options.random_motion.then(|| rng.random()),
                colour: options.colours.then(|| ClayColour::random(&mut rng)),
                hard_case: options.hard_case,
                fragment_index: None,
            };
            if part == wanted_part || attempt + 1 == MAX_ATTEMPTS {
                return finish(seed, shell, &profile, &deformation, part, &surface);
            }
            fallback.get_or_insert((shell, profile, deformation, part, surface));
        }
        if fallback.is_some() || target_faces >= MAX_FALLBACK_TARGET_FACES {
            break fallback;
        }
        target_faces = (target_faces.max(64) * 4).min(MAX_FALLBACK_TARGET_FACES);
    };
    // Only reached when no attempt gave the wanted part: the truth says what it is.
    let (shell, profile, deformation, part, surface) =
        fallback.expect("some attempt yields a fragment at the default resolution: every plan contains its own seed");
    finish(seed, shell, &profile, &deformation, part, &surface)
}

/// A whole vessel broken into `options.fragment_count` fragments by a rough Voronoi
/// diagram of seeds spread uniformly over its surface.
pub fn generate_vessel(seed: u64, options: &VesselOptions) -> SynthVessel {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let shape = options.shape.unwrap_or_else(|| VesselShape::random(&mut rng));
    let profile = VesselProfile::random(shape, &options.forms, &mut rng);
    let deformation = Deformation::random(&mut rng, options.deformation_scale, profile.height_mm());
    let length = profile.length_mm();
    let max_radius = profile.max_radius_mm();
    let mut seed_params = Vec::new();
    while seed_params.len() < options.fragment_count.max(2) {
        // Uniform over the surface: accept an arc length with probability r / r_max.
        let s = rng.random_range(0.0..length);
        if rng.random_range(0.0..max_radius) < profile.mid_radius_mm(s) {
            seed_params.push((rng.random_range(0.0..std::f64::consts::TAU), s));
        }
    }
    let seeds = seed_params.iter().map(|&(theta, s)| mid_surface_point(&profile, theta, s)).collect();
    let voronoi = RoughVoronoi::new(seeds, options.roughness_mm, &mut rng);
    let (area, parameter_area) = surface_areas(&profile);
    let grid = ParamGrid::covering(None, [0.0, length], length, options.cell_size_mm.max(0.05), area / parameter_area);
    let labels = voronoi.label_grid(&grid, &profile);
    let colour = options.colours.then(|| ClayColour::random(&mut rng));
    let fragment_seeds: Vec<(u64, u64)> = seed_params.iter().map(|_| (rng.random(), rng.random())).collect();
    let fragments = seed_params
        .par_iter()
        .enumerate()
        .filter_map(|(k, &(theta, s))| {
            let mut mask: Vec<bool> = labels.iter().map(|&l| l == k as u32).collect();
            if !clean_mask(&grid, &mut mask, cell_at(&grid, theta, s)) {
                return None;
            }
            let shell = build_shell(&grid, &mask, &profile, &deformation);
            let part = classify(&profile, &shell);
            let (noise_seed, motion_seed) = fragment_seeds[k];
            let surface = Surface {
                noise_mm: options.noise_mm,
                relief: options.relief,
                noise_seed,
                motion_seed: options.random_motion.then_some(motion_seed),
                colour: colour.clone(),
                hard_case: None,
                fragment_index: Some(k),
            };
            Some(finish(seed, shell, &profile, &deformation, part, &surface))
        })
        .collect();
    SynthVessel {
        fragments,
        profile: profile.skin_polyline(1.0, PROFILE_STEP_MM),
        vessel: vessel_truth(&profile, &deformation),
    }
}

/// The value of `all` whose `name` is `text` (case and `-`/`_` ignored), or an error
/// listing the names.
pub(crate) fn parse_name<T: Copy>(text: &str, all: &[T], name: fn(T) -> &'static str, what: &str) -> crate::Result<T> {
    let wanted = text.trim().to_ascii_lowercase().replace('-', "_");
    all.iter().copied().find(|&value| name(value) == wanted).ok_or_else(|| {
        let names: Vec<&str> = all.iter().map(|&value| name(value)).collect();
        crate::Error::InvalidArgument(format!("unknown {what} {text:?}: expected one of {}", names.join(", ")))
    })
}
