//! Pre-orientation (Wilczek et al. 2018, section 2.2): the rotation axis of the vessel a
//! fragment came from, from its normals or from three points on a horizontal feature,
//! with an honest verdict when the data do not determine it.

pub mod axis;

pub use axis::{mean_point_distance_mm, Axis, AxisRecord};
