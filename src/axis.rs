//! The rotation axis and the frame it induces: axis on z, rim up.

use nalgebra::{Isometry3, Rotation3, Translation3, Unit, UnitQuaternion};
use serde::{Deserialize, Serialize};

use crate::mesh::{Point, Vector};

/// A vessel's rotation axis in the scan's frame: a point on it and a unit direction
/// pointing from the base towards the rim.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Axis {
    /// A point on the axis. [`Axis::normalized`] moves it to the foot of the
    /// perpendicular from a reference point, so that two equal axes compare equal.
    pub point: Point,
    /// Unit direction, base to rim.
    pub direction: Unit<Vector>,
}

/// The JSON form of an [`Axis`], as `sherd orient --json` and ground-truth files write it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct AxisRecord {
    /// `[x, y, z]` of a point on the axis.
    pub point: [f64; 3],
    /// `[dx, dy, dz]`, unit, base to rim.
    pub direction: [f64; 3],
}

/// Two unit vectors completing `direction` to a right-handed orthonormal frame.
pub fn perpendicular_frame(direction: &Vector) -> (Vector, Vector) {
    let helper = if direction.x.abs() < 0.6 { Vector::x() } else { Vector::y() };
    let e1 = direction.cross(&helper).normalize();
    let e2 = direction.cross(&e1);
    (e1, e2)
}

/// Angle in degrees between two directions (unit or not), from the sine and the cosine:
/// the arc cosine of a unit vector's rounded square norm (1 - 2e-16) is already 1e-6
/// degrees, so a direction measured against itself did not come out 0.
pub fn angle_between_deg(a: &Vector, b: &Vector) -> f64 {
    a.cross(b).norm().atan2(a.dot(b)).to_degrees()
}

impl Axis {
    /// An axis through `point` along `direction` (normalised here).
    pub fn new(point: Point, direction: Vector) -> Self {
        Axis { point, direction: Unit::new_normalize(direction) }
    }

    /// The z axis of the oriented frame.
    pub fn z() -> Self {
        Axis::new(Point::origin(), Vector::z())
    }

    /// The same line with its point moved to the foot of the perpendicular from `reference`.
    pub fn normalized(&self, reference: &Point) -> Self {
        Axis { point: self.closest_point(reference), direction: self.direction }
    }

    /// The point of the axis closest to `p`.
    pub fn closest_point(&self, p: &Point) -> Point {
        let t = (p - self.point).dot(&self.direction);
        self.point + self.direction.into_inner() * t
    }

    /// Distance from `p` to the axis (the radius of `p` in the oriented frame).
    pub fn distance_to(&self, p: &Point) -> f64 {
        let v = p - self.point;
        (v - self.direction.into_inner() * v.dot(&self.direction)).norm()
    }

    /// Height of `p` along the axis, measured from the axis point.
    pub fn height_of(&self, p: &Point) -> f64 {
        (p - self.point).dot(&self.direction)
    }

    /// Angle in degrees between the two directions, taking their sign into account
    /// (180 means the same line pointing the other way).
    pub fn angle_to_deg(&self, other: &Axis) -> f64 {
        angle_between_deg(&self.direction, &other.direction)
    }

    /// Angle in degrees between the two lines, ignoring which way they point.
    pub fn line_angle_to_deg(&self, other: &Axis) -> f64 {
        let other = other.direction.into_inner();
        let facing = if self.direction.dot(&other) < 0.0 { -other } else { other };
        angle_between_deg(&self.direction, &facing)
    }

    /// The same line pointing the other way.
    pub fn flipped(&self) -> Self {
        Axis { point: self.point, direction: -self.direction }
    }

    /// The rigid transform from the scan's frame to the oriented frame: the axis point
    /// goes to the origin and the direction to +z. The rotation about z is chosen so that
    /// `reference` (typically the fragment's centroid) lands on the +x half-plane, where
    /// the drawing puts the exterior view.
    pub fn to_oriented_frame(&self, reference: &Point) -> Isometry3<f64> {
        let align = UnitQuaternion::rotation_between(&self.direction, &Vector::z())
            .unwrap_or_else(|| UnitQuaternion::from_axis_angle(&Vector::x_axis(), std::f64::consts::PI));
        let local = align * (reference - self.point);
        let spin = UnitQuaternion::from_axis_angle(&Vector::z_axis(), -local.y.atan2(local.x));
        let rotation = spin * align;
        Isometry3::from_parts(Translation3::from(-(rotation * self.point.coords)), rotation)
    }

    /// The inverse of [`Axis::to_oriented_frame`]: oriented frame to scan frame.
    pub fn from_oriented_frame(&self, reference: &Point) -> Isometry3<f64> {
        self.to_oriented_frame(reference).inverse()
    }

    /// This axis mapped by a rigid transform (scan frame to another frame).
    pub fn transformed(&self, transform: &Isometry3<f64>) -> Self {
        Axis { point: transform * self.point, direction: Unit::new_unchecked(transform * self.direction.into_inner()) }
    }

    /// Cylindrical coordinates `(radius, height, angle_rad)` of `p` in the frame
    /// `to_oriented_frame(reference)` gives.
    pub fn cylindrical(frame: &Isometry3<f64>, p: &Point) -> (f64, f64, f64) {
        let q = frame * p;
        (q.x.hypot(q.y), q.z, q.y.atan2(q.x))
    }

    /// The record written to JSON.
    pub fn record(&self) -> AxisRecord {
        AxisRecord { point: self.point.coords.into(), direction: self.direction.into_inner().into() }
    }

    /// An axis from its JSON record; `None` if the direction is zero or not finite.
    pub fn from_record(record: &AxisRecord) -> Option<Self> {
        let direction = Vector::from(record.direction);
        let point = Point::from(record.point);
        if !direction.iter().chain(point.iter()).all(|c| c.is_finite()) || direction.norm() < 1e-12 {
            return None;
        }
        Some(Axis::new(point, direction))
    }

    /// A rotation taking +z onto this axis's direction (useful to build test data).
    pub fn rotation_from_z(&self) -> Rotation3<f64> {
        Rotation3::rotation_between(&Vector::z(), &self.direction)
            .unwrap_or_else(|| Rotation3::from_axis_angle(&Vector::x_axis(), std::f64::consts::PI))
    }
}

/// The paper's accuracy measure (Wilczek et al. 2018, section 3): the mean distance in
/// millimetres between the fragment's points placed in the oriented frame by `estimated`
/// and by `truth`, after the best shift along and turn about the axis (neither is
/// determined by an axis, so neither counts as error). The fit is closed-form: the
/// shift is the mean height difference, the turn the 2D Procrustes angle.
pub fn mean_point_distance_mm(points: &[Point], estimated: &Axis, truth: &Axis) -> f64 {
    if points.is_empty() {
        return 0.0;
    }
    let reference = points[0];
    let estimated_frame = estimated.to_oriented_frame(&reference);
    let true_frame = truth.to_oriented_frame(&reference);
    let pairs: Vec<(Point, Point)> = points.iter().map(|p| (estimated_frame * p, true_frame * p)).collect();
    let n = pairs.len() as f64;
    let shift = pairs.iter().map(|(e, t)| t.z - e.z).sum::<f64>() / n;
    let (mut cosine_sum, mut sine_sum) = (0.0, 0.0);
    for (e, t) in &pairs {
        cosine_sum += e.x * t.x + e.y * t.y;
        sine_sum += e.x * t.y - e.y * t.x;
    }
    let turn = sine_sum.atan2(cosine_sum);
    let (sin, cos) = turn.sin_cos();
    pairs
        .iter()
        .map(|(e, t)| {
            let placed = Point::new(cos * e.x - sin * e.y, sin * e.x + cos * e.y, e.z + shift);
            (placed - t).norm()
        })
        .sum::<f64>()
        / n
}

/// [`mean_point_distance_mm`] with up and down aside: the nearer of `estimated` and its
/// flip, how far the estimated line lies from the true one.
pub fn mean_line_distance_mm(points: &[Point], estimated: &Axis, truth: &Axis) -> f64 {
    mean_point_distance_mm(points, estimated, truth).min(mean_point_distance_mm(points, &estimated.flipped(), truth))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn oriented_frame_puts_axis_on_z_and_reference_on_plus_x() {
        let axis = Axis::new(Point::new(3.0, -2.0, 5.0), Vector::new(0.3, -0.5, 0.8));
        let reference = Point::new(10.0, 4.0, 1.0);
        let frame = axis.to_oriented_frame(&reference);
        let on_axis = axis.point + axis.direction.into_inner() * 7.0;
        let mapped = frame * on_axis;
        assert!(mapped.x.abs() < 1e-12 && mapped.y.abs() < 1e-12 && (mapped.z - 7.0).abs() < 1e-12);
        let r = frame * reference;
        assert!(r.x > 0.0 && r.y.abs() < 1e-12);
        assert!((r.x - axis.distance_to(&reference)).abs() < 1e-12);
        let back = axis.from_oriented_frame(&reference) * r;
        assert!((back - reference).norm() < 1e-12);
    }

    #[test]
    fn antiparallel_direction_still_maps_to_plus_z() {
        let axis = Axis::new(Point::origin(), -Vector::z());
        let frame = axis.to_oriented_frame(&Point::new(1.0, 0.0, 0.0));
        let d = frame * axis.direction.into_inner();
        assert!((d - Vector::z()).norm() < 1e-12);
    }

    #[test]
    fn mean_point_distance_ignores_shift_and_turn_but_not_tilt() {
        let truth = Axis::new(Point::new(1.0, 2.0, 3.0), Vector::new(0.1, 0.2, 1.0));
        let points: Vec<Point> = (0..50)
            .map(|i| {
                let a = i as f64 * 0.05;
                truth.point + Vector::new(80.0 * a.cos(), 80.0 * a.sin(), i as f64)
            })
            .collect();
        let shifted = Axis::new(truth.point + truth.direction.into_inner() * 17.0, truth.direction.into_inner());
        assert!(mean_point_distance_mm(&points, &shifted, &truth) < 1e-9);
        let tilted = Axis::new(truth.point, truth.rotation_from_z() * Vector::new(0.05, 0.0, 1.0));
        let error = mean_point_distance_mm(&points, &tilted, &truth);
        assert!(error > 0.5, "a 3 degree tilt must show, got {error}");
        let flipped = truth.flipped();
        assert!(mean_point_distance_mm(&points, &flipped, &truth) > 10.0);
    }

    #[test]
    fn angles_and_records() {
        let a = Axis::new(Point::origin(), Vector::z());
        let b = Axis::new(Point::new(1.0, 0.0, 0.0), -Vector::z());
        assert!((a.angle_to_deg(&b) - 180.0).abs() < 1e-9);
        assert!(a.line_angle_to_deg(&b).abs() < 1e-6);
        let round = Axis::from_record(&b.record()).unwrap();
        assert_eq!(round, b);
        assert!(Axis::from_record(&AxisRecord { point: [0.0; 3], direction: [0.0; 3] }).is_none());
    }
}
