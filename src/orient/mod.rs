//! Pre-orientation (Wilczek et al. 2018, section 2.2): the rotation axis of the vessel a
//! fragment came from, from its normals or from three points on a horizontal feature,
//! with an honest verdict when the data do not determine it.
//!
//! Automatic pipeline ([`orient_automatic`]): working copy (decimated, smoothed,
//! area-weighted normals) -> normal lines -> opposite-normal filter (`opposite_normals`)
//! -> whole-sphere search of the directions, each axis placed where the normal lines meet
//! and scored as a surface of revolution ([`revolution_search`]) -> the verdict of its
//! landscape ([`landscape`]) -> sense base to rim ([`direction`]) -> verdict ([`verdict`]).

mod automatic;
pub mod direction;
pub mod landscape;
pub mod line_complex;
mod manual;
pub mod normal_lines;
pub(crate) mod opposite_normals;
mod options;
mod report;
pub mod revolution_search;
mod sense;
pub(crate) mod surfaces;
pub(crate) mod three_points;
pub mod verdict;
mod working;

pub use crate::axis::{angle_between_deg, mean_line_distance_mm, mean_point_distance_mm, Axis, AxisRecord};
pub use automatic::{orient_automatic, orient_automatic_with_decimated};
pub use manual::orient_from_three_points;
pub use options::{ManualOptions, OrientOptions, MAX_SMOOTHING_ITERATIONS};
pub use report::{CompetitorReach, OrientReport, Orientation};
pub use sense::SenseInputs;
pub use surfaces::{segment_surfaces, Skin};
pub use verdict::{Verdict, VerdictThresholds};
pub use working::{decimated_copy, surface_of_revolution_lines, working_copy};
