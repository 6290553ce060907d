//! The robust loss a point costs, and the bounds past which a point is off the surface of
//! revolution (a normal out of the meridian plane, a radius no vessel has, a band too small).

/// Largest component of a unit normal across the meridian plane of a point on the surface
/// (the sine of its turn out of that plane) for the point to count as on the surface of
/// revolution: a normal 30 degrees out of the meridian plane belongs to a break face, or
/// the axis is wrong there.
pub const MAX_TANGENTIAL_NORMAL: f64 = 0.5;

/// The cost of a point off the surface of revolution, in the units of the robust loss:
/// that of a residual three loss scales long, so that a break face weighs as a point
/// three scales off its band.
pub const OUTLIER_LOSS: f64 = 0.9;

/// The robust loss of a residual `r`, given by its square, at scale `s` (Geman and
/// McClure): `r^2 / (r^2 + s^2)`, quadratic near zero and bounded by 1, so that no point
/// weighs more than a break.
pub(super) fn robust_loss(r_squared: f64, s: f64) -> f64 {
    let q = r_squared / (s * s);
    q / (1.0 + q)
}

/// The weight of a residual in a reweighted least-squares step on [`robust_loss`].
pub(super) fn robust_weight(r: f64, s: f64) -> f64 {
    1.0 / (1.0 + (r / s).powi(2)).powi(2)
}

/// Points farther from a candidate axis than this are off its surface of revolution, mm.
/// No thrown vessel is a metre wide, and without a bound a flat or nearly flat piece would
/// be a surface of revolution about axes far away on either side (a plane is the limit of
/// cylinders of growing radius) as well as about its true axis, across it.
pub const MAX_RADIUS_MM: f64 = 500.0;

/// Fewest points of a band for its line to be fitted; the points of smaller bands cost
/// as outliers (a wrong axis scatters the points into many small bands).
pub(super) const MIN_BAND_POINTS: usize = 4;
