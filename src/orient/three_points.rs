//! Manual pre-orientation from three (or more) points on one horizontal feature (Wilczek
//! et al. 2018, section 2.2.1, Fig. 2): the plane through them gives the axis direction,
//! the least-squares circle in that plane (Kåsa's algebraic fit) its position.

use nalgebra::{Matrix3, Vector3};

use crate::mesh::{Point, Vector};
use crate::{Error, Result};

/// A circle in space.
#[derive(Clone, Copy, Debug)]
pub struct Circle {
    /// Centre.
    pub center: Point,
    /// Unit normal of its plane (sign arbitrary).
    pub normal: Vector,
    /// Radius, same unit as the points.
    pub radius_mm: f64,
}

/// The least-squares circle through `points` (at least 3): the plane of least squares,
/// then Kåsa's fit `x² + y² = 2ax + 2by + c` in it. Coincident or collinear points are
/// an error naming the points.
pub fn fit_circle(points: &[Point]) -> Result<Circle> {
    if points.len() < 3 {
        return Err(Error::InvalidArgument(format!("a circle needs at least 3 points, got {}", points.len())));
    }
    if let Some((i, p)) = points.iter().enumerate().find(|(_, p)| !p.iter().all(|c| c.is_finite())) {
        return Err(Error::InvalidArgument(format!("point {} is not finite: ({}, {}, {})", i + 1, p.x, p.y, p.z)));
    }
    let n = points.len() as f64;
    let centroid = Point::from(points.iter().fold(Vector::zeros(), |s, p| s + p.coords) / n);
    let spread = points.iter().map(|p| (p - centroid).norm()).fold(0.0, f64::max);
    for i in 0..points.len() {
        for j in i + 1..points.len() {
            if (points[i] - points[j]).norm() <= 1e-9 * (1.0 + spread) {
                return Err(Error::InvalidArgument(format!(
                    "points {} and {} coincide at ({}, {}, {}): pick three distinct points on the feature",
                    i + 1,
                    j + 1,
                    points[i].x,
                    points[i].y,
                    points[i].z
                )));
            }
        }
    }
    let (_, [_, middle, largest], [normal, _, u]) = crate::statistics::principal_axes(points.iter().map(|p| (p, 1.0)))
        .ok_or_else(|| Error::InvalidArgument("the points define no plane".into()))?;
    // Collinear: the second principal extent vanishes next to the first (points within
    // 1e-4 of the spread from a line).
    if middle <= largest * 1e-8 {
        return Err(Error::InvalidArgument(
            "the points are collinear: they define no circle; pick them spread along the feature".into(),
        ));
    }
    let (normal, u) = (normal.normalize(), u.normalize());
    let v = normal.cross(&u);
    // Kåsa: linear least squares in the plane's coordinates.
    let mut normal_matrix = Matrix3::zeros();
    let mut rhs = Vector3::zeros();
    for p in points {
        let d = p - centroid;
        let (x, y) = (d.dot(&u), d.dot(&v));
        let row = Vector3::new(2.0 * x, 2.0 * y, 1.0);
        normal_matrix += row * row.transpose();
        rhs += row * (x * x + y * y);
    }
    let solution = normal_matrix
        .try_inverse()
        .map(|inv| inv * rhs)
        .ok_or_else(|| Error::DegenerateGeometry("the circle fit is singular".into()))?;
    let (a, b, c) = (solution.x, solution.y, solution.z);
    let radius_squared = c + a * a + b * b;
    if !(radius_squared > 0.0) || !radius_squared.is_finite() {
        return Err(Error::DegenerateGeometry("the points define no real circle".into()));
    }
    Ok(Circle { center: centroid + u * a + v * b, normal, radius_mm: radius_squared.sqrt() })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circle_through_three_points_in_a_tilted_plane() {
        let axis = Vector::new(0.2, -0.3, 1.0).normalize();
        let (e1, e2) = crate::axis::perpendicular_frame(&axis);
        let center = Point::new(5.0, -7.0, 12.0);
        let points: Vec<Point> =
            [0.1f64, 0.9, 2.0].iter().map(|t| center + (e1 * t.cos() + e2 * t.sin()) * 80.0).collect();
        let circle = fit_circle(&points).unwrap();
        assert!((circle.center - center).norm() < 1e-9);
        assert!((circle.radius_mm - 80.0).abs() < 1e-9);
        assert!(circle.normal.dot(&axis).abs() > 1.0 - 1e-12);
    }

    #[test]
    fn collinear_and_coincident_points_are_errors() {
        let line = [Point::new(0.0, 0.0, 0.0), Point::new(1.0, 1.0, 1.0), Point::new(2.0, 2.0, 2.0)];
        assert!(fit_circle(&line).unwrap_err().to_string().contains("collinear"));
        let same = [Point::new(1.0, 0.0, 0.0), Point::new(1.0, 0.0, 0.0), Point::new(0.0, 1.0, 0.0)];
        assert!(fit_circle(&same).unwrap_err().to_string().contains("coincide"));
        let nan = [Point::new(f64::NAN, 0.0, 0.0), Point::new(1.0, 0.0, 0.0), Point::new(0.0, 1.0, 0.0)];
        assert!(fit_circle(&nan).unwrap_err().to_string().contains("not finite"));
    }
}
