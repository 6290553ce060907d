//! Whole-sphere search for the axis (the pre-orientation's first step): every direction of
//! an even cover of the hemisphere is scored by how well the fragment is a surface of
//! revolution about the best axis of that direction, the lowest valleys of that landscape
//! are followed down, and the valleys are returned best first for the verdict to compare.
//!
//! The score of an axis is the paper's two zeroth-order properties of a surface of
//! revolution at once (Wilczek et al. 2018, Fig. 1 b and c): horizontal sections are
//! circles about the axis (Eq. 2) and the profiles of all vertical sections superpose
//! (Eq. 5). Each point is put in the rz half-plane of the axis, with its normal's radial
//! and axial parts; a point whose normal is mostly radial (a wall) belongs to the band of
//! points of its skin at its height, one whose normal is mostly axial (a floor, a flat
//! lip, a plate) to the band of its side at its radius, and each band is a short straight
//! piece of the profile: the score is the robust mean of the points' distances to their
//! band's total-least-squares line. Equation 2 is the wall bands with the line held
//! vertical; the line's slope lets a flaring wall's band be as thin as a vertical one, and
//! the radial bands let the floors and lips that Eq. 2 cannot use speak. A point whose
//! normal turns away from the meridian plane by more than [`MAX_TANGENTIAL_NORMAL`]
//! (a break face, or any point under a wrong axis) costs as much as a large residual.
//!
//! For a given direction the axis's position is solved, not searched: first where the
//! normal lines projected on the horizontal plane meet (Halíř 1999, Eq. 1 of the paper),
//! then by the linearised circle condition of the wall bands (Kåsa's fit shared by all
//! bands, each with its own radius and slope), which is exact for a surface of revolution
//! and needs no start. Only the two angles of the direction are searched.
//!
//! Files, each importing only those before it: `loss` (the robust loss, and what puts a
//! point off the surface of revolution), `samples` (the points scored, and their view from
//! a direction), `bands` (the score of an axis), `position` (the best axis of a direction)
//! and `search` (the landscape of directions and its valleys).

mod bands;
mod loss;
mod position;
mod samples;
mod search;
#[cfg(test)]
mod test_patch;

pub use bands::point_losses;
pub use loss::{MAX_RADIUS_MM, MAX_TANGENTIAL_NORMAL, OUTLIER_LOSS};
pub use position::{fit_direction, DirectionFit};
pub use samples::RevolutionSamples;
pub use search::{descend, hemisphere_directions, search, Landscape, SearchOptions, Valley};
