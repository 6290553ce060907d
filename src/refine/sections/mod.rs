//! The fragment as the refinement criteria see it (Wilczek et al. 2018, section 2.3):
//! its vertices in the frame of the start axis, split into the inner and outer skins,
//! and the horizontal sections (planes perpendicular to a candidate axis) and vertical
//! sections (angular sectors about it) the criteria are defined on.
//!
//! Horizontal sections of a mesh are exact plane cuts of its triangles, each cut segment
//! weighted by its length, so that a criterion is a continuous function of the axis (a
//! slab of vertices gains and loses points as the axis turns, which makes the objective
//! jump). Point clouds without faces fall back to slabs of vertices.
//!
//! One file a part, each using only those before it: `memo` (values derived from the
//! points, made once), `frame` (a candidate axis and its frame), `skins` (which skin a
//! vertex is on), `vertical` (sectors of the preserved arc), `surface` (the fragment
//! prepared around the start axis) and `horizontal` (its cuts).

mod frame;
mod memo;
mod horizontal;
mod skins;
mod surface;
mod vertical;

pub use frame::{axis_through, tilts_along, AxisParameters, CandidateFrame};
pub use horizontal::HorizontalSection;
pub use skins::Surface;
pub use surface::{mean_edge_length, PreparedSurface};
pub(crate) use vertical::largest_angular_gap;
pub use vertical::{sector_angle_rad, vertical_sections};

/// The skin one vertex belongs to: the orientation's segmentation names it. Here a vertex
/// off the skins is `None` rather than `Some(Skin::Other)`, which the refinement never
/// assigns.
pub use crate::orient::Skin;
