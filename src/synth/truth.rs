//! What a synthetic sherd really is: its axis in the scan frame, the vessel's profile and
//! measurements, which part of the vessel it is and how much of the circumference it
//! preserves. Everything a later layer estimates is here to compare against.

use serde::{Deserialize, Serialize};

use super::deform::Deformation;
pub use super::shape::distance_to_polyline;
use super::shape::{BaseForm, RimForm, VesselShape};
use crate::mesh::Point;
use crate::axis::{Axis, AxisRecord};

/// Which part of the vessel a fragment comes from (the archaeologist's classification).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SherdPart {
    /// Includes part of the rim, not the base.
    Rim,
    /// Wall only: neither rim nor base.
    Body,
    /// Includes the base's edge and some wall, not the rim.
    Base,
    /// A complete profile: rim and base.
    RimToBase,
    /// A piece of the flat base only: its axis direction is known, its position is not.
    Flat,
}

impl SherdPart {
    /// Every part, in a fixed order.
    pub const ALL: [SherdPart; 5] = [SherdPart::Rim, SherdPart::Body, SherdPart::Base, SherdPart::RimToBase, SherdPart::Flat];

    /// The lower-case name used on the command line and in JSON.
    pub fn name(self) -> &'static str {
        match self {
            SherdPart::Rim => "rim",
            SherdPart::Body => "body",
            SherdPart::Base => "base",
            SherdPart::RimToBase => "rim_to_base",
            SherdPart::Flat => "flat",
        }
    }
}

impl std::str::FromStr for SherdPart {
    type Err = crate::Error;

    fn from_str(text: &str) -> crate::Result<Self> {
        super::parse_name(text, &SherdPart::ALL, SherdPart::name, "sherd part")
    }
}

/// The fragments the orientation must refuse honestly (NEEDS_MANUAL_ORIENTATION).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum HardCase {
    /// A piece of the flat base: every normal is parallel, the axis position is free.
    FlatBase,
    /// A piece of a spherical body zone: every line through the sphere's centre is an axis.
    NearSpherical,
    /// A piece about 15 mm across: too little curvature to measure.
    Tiny,
}

impl HardCase {
    /// Every hard case, in a fixed order.
    pub const ALL: [HardCase; 3] = [HardCase::FlatBase, HardCase::NearSpherical, HardCase::Tiny];

    /// The lower-case name used on the command line and in JSON.
    pub fn name(self) -> &'static str {
        match self {
            HardCase::FlatBase => "flat_base",
            HardCase::NearSpherical => "near_spherical",
            HardCase::Tiny => "tiny",
        }
    }
}

impl std::str::FromStr for HardCase {
    type Err = crate::Error;

    fn from_str(text: &str) -> crate::Result<Self> {
        super::parse_name(text, &HardCase::ALL, HardCase::name, "hard case")
    }
}

/// What a vertex or face of a synthetic sherd lies on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SurfaceKind {
    /// The vessel's outside.
    Outer,
    /// The vessel's inside.
    Inner,
    /// A break face across the wall.
    Fracture,
    /// The rim: its flat top across the wall, or its rounding.
    Rim,
}

/// The rigid motion from the vessel frame (axis on z, standing plane z = 0) to the scan frame.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct RigidMotion {
    /// Rotation as a unit quaternion `[w, x, y, z]`.
    pub rotation_wxyz: [f64; 4],
    /// Translation, mm.
    pub translation_mm: [f64; 3],
}

impl RigidMotion {
    /// The identity.
    pub fn identity() -> Self {
        RigidMotion { rotation_wxyz: [1.0, 0.0, 0.0, 0.0], translation_mm: [0.0; 3] }
    }

    /// As an isometry.
    pub fn isometry(&self) -> nalgebra::Isometry3<f64> {
        let [w, i, j, k] = self.rotation_wxyz;
        let rotation = nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, i, j, k));
        nalgebra::Isometry3::from_parts(nalgebra::Translation3::from(nalgebra::Vector3::from(self.translation_mm)), rotation)
    }

    /// From an isometry.
    pub fn from_isometry(isometry: &nalgebra::Isometry3<f64>) -> Self {
        let q = isometry.rotation.quaternion();
        RigidMotion { rotation_wxyz: [q.w, q.i, q.j, q.k], translation_mm: isometry.translation.vector.into() }
    }
}

/// The vessel a fragment came from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct VesselTruth {
    /// Family.
    pub shape: VesselShape,
    /// Outer radius at the rim, mm.
    pub rim_radius_mm: f64,
    /// Outer radius where the base leaves the standing plane (rises 1 mm), mm.
    pub base_radius_mm: f64,
    /// Height above the standing plane, mm.
    pub height_mm: f64,
    /// Wall thickness, mm.
    pub wall_thickness_mm: f64,
    /// How the wall ends at the rim.
    pub rim_form: RimForm,
    /// How the base meets the ground.
    #[serde(default = "flat_base")]
    pub base_form: BaseForm,
    /// The deformation applied (ovality, rim tilt, wobble).
    pub deformation: Deformation,
}

/// The base form of a truth file written before ring feet were made.
fn flat_base() -> BaseForm {
    BaseForm::Flat
}

/// The ground truth of a synthetic sherd.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GroundTruth {
    /// The vessel's rotation axis in the scan frame, pointing from base to rim; its point
    /// is the centre of the vessel's standing plane, so the heights of `profile` are
    /// measured from it.
    #[serde(with = "axis_as_record")]
    pub axis: Axis,
    /// Outer rim radius, mm, when the fragment preserves part of the rim.
    pub rim_radius_mm: Option<f64>,
    /// Base radius (outer radius where the base leaves the standing plane), mm, when the
    /// fragment preserves the base's edge.
    pub base_radius_mm: Option<f64>,
    /// Angle of the circumference the fragment's points span about the axis, degrees
    /// (360 when it surrounds the axis).
    pub sector_angle_deg: f64,
    /// Angle of the rim the fragment preserves (the sector its rim faces span), degrees,
    /// when it has rim: what "12 % of the rim" in a publication measures.
    pub rim_sector_angle_deg: Option<f64>,
    /// Extent of the fragment along the axis, mm.
    pub height_mm: f64,
    /// The vessel's outer profile `[r, z]` (oriented frame, mm) from the base centre to
    /// the rim's outer edge.
    pub profile: Vec<[f64; 2]>,
    /// The vessel's inner profile `[r, z]`, same frame.
    pub inner_profile: Vec<[f64; 2]>,
    /// Which part of the vessel the fragment is.
    pub part: SherdPart,
    /// Set when the fragment is one the orientation must refuse: asked for, or come out
    /// so (every flat base piece; a piece under 25 mm across; a piece lying wholly on a
    /// globular vessel's spherical zone).
    pub hard_case: Option<HardCase>,
    /// Standard deviation of the Gaussian noise on every coordinate, mm.
    pub noise_mm: f64,
    /// The surface's relief (none in truth files written without it).
    #[serde(default)]
    pub relief: super::Relief,
    /// Upper bound of how far the deformation moved any point of the fragment, mm.
    pub deformation_bound_mm: f64,
    /// The vessel.
    pub vessel: VesselTruth,
    /// Vessel frame to scan frame.
    pub motion: RigidMotion,
    /// The seed the sherd (or its vessel) was generated from.
    pub seed: u64,
    /// The fragment's index among its vessel's fragments ([`super::generate_vessel`]).
    pub fragment_index: Option<usize>,
}

mod axis_as_record {
    use super::*;

    pub fn serialize<S: serde::Serializer>(axis: &Axis, serializer: S) -> Result<S::Ok, S::Error> {
        axis.record().serialize(serializer)
    }

    pub fn deserialize<'de, D: serde::Deserializer<'de>>(deserializer: D) -> Result<Axis, D::Error> {
        let record = AxisRecord::deserialize(deserializer)?;
        Axis::from_record(&record).ok_or_else(|| serde::de::Error::custom("axis direction is zero or not finite"))
    }
}

/// The angle (degrees) of the smallest sector about `axis` containing all `points`: 360
/// minus the largest angular gap between them.
pub fn sector_angle_deg(points: &[Point], axis: &Axis) -> f64 {
    let Some(reference) = points.iter().find(|p| axis.distance_to(p) > 1e-6) else {
        return 0.0;
    };
    let frame = axis.to_oriented_frame(reference);
    let mut angles: Vec<f64> = points
        .iter()
        .filter(|p| axis.distance_to(p) > 1e-6)
        .map(|p| Axis::cylindrical(&frame, p).2)
        .collect();
    if angles.len() < 2 {
        return 0.0;
    }
    angles.sort_unstable_by(f64::total_cmp);
    let wrap_gap = angles[0] + std::f64::consts::TAU - angles[angles.len() - 1];
    let largest_gap = angles.windows(2).map(|w| w[1] - w[0]).fold(wrap_gap, f64::max);
    (std::f64::consts::TAU - largest_gap).to_degrees()
}

