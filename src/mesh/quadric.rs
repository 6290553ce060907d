//! Error quadrics (Garland and Heckbert 1997, "Surface simplification using quadric
//! error metrics", section 5).
//!
//! A quadric `Q = (A, b, c)` measures the weighted sum of squared distances of a point
//! `x` to a set of planes: `Q(x) = xᵀ A x + 2 bᵀ x + c` (their equation 2, with the 4x4
//! matrix split into its blocks). A plane `n·x + d = 0` with unit `n` and weight `w`
//! contributes `A = w n nᵀ`, `b = w d n`, `c = w d²`; quadrics of several planes add.
//! The optimal position of a contracted pair minimises `Q`, i.e. solves `A x = -b`
//! (section 4, "the optimal position").

use crate::mesh::Vector;

/// A symmetric error quadric, stored as the 10 distinct coefficients of its 4x4 matrix.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Quadric {
    /// Upper triangle of `A`: `a00, a01, a02, a11, a12, a22`.
    a: [f64; 6],
    /// The linear term `b`.
    b: [f64; 3],
    /// The constant term `c`.
    c: f64,
}

impl Quadric {
    /// The quadric of the plane `{x : normal·x + offset = 0}` (unit `normal`), times `weight`.
    pub fn from_plane(normal: &Vector, offset: f64, weight: f64) -> Self {
        let [x, y, z] = [normal.x, normal.y, normal.z];
        Quadric {
            a: [
                weight * x * x,
                weight * x * y,
                weight * x * z,
                weight * y * y,
                weight * y * z,
                weight * z * z,
            ],
            b: [weight * offset * x, weight * offset * y, weight * offset * z],
            c: weight * offset * offset,
        }
    }

    /// The quadric of the plane through `point` with unit `normal`, times `weight`.
    pub fn from_plane_through(point: &Vector, normal: &Vector, weight: f64) -> Self {
        Self::from_plane(normal, -normal.dot(point), weight)
    }

    /// Weighted squared distance of `point` to the planes: `Q(point)`, never negative
    /// (rounding can make the exact expression slightly so).
    pub fn error_at(&self, point: &Vector) -> f64 {
        let [x, y, z] = [point.x, point.y, point.z];
        let a = &self.a;
        let quadratic = a[0] * x * x
            + a[3] * y * y
            + a[5] * z * z
            + 2.0 * (a[1] * x * y + a[2] * x * z + a[4] * y * z);
        let linear = 2.0 * (self.b[0] * x + self.b[1] * y + self.b[2] * z);
        (quadratic + linear + self.c).max(0.0)
    }

    /// `A v` for the quadratic block `A`.
    fn apply(&self, v: &Vector) -> Vector {
        let a = &self.a;
        Vector::new(
            a[0] * v.x + a[1] * v.y + a[2] * v.z,
            a[1] * v.x + a[3] * v.y + a[4] * v.z,
            a[2] * v.x + a[4] * v.y + a[5] * v.z,
        )
    }

    /// The point minimising `Q` (the solution of `A x = -b`), or `None` when `A` is
    /// too close to singular for the minimum to be well defined: on a flat or
    /// cylindrical patch every point of a plane or line is optimal, and the solve
    /// would pick one far away by rounding. The test is `det(A) <= 1e-12 trace(A)³`,
    /// i.e. the smallest principal curvature of `Q` is negligible beside the largest.
    pub fn minimizer(&self) -> Option<Vector> {
        let a = &self.a;
        // Cofactors of the symmetric matrix [[a0 a1 a2] [a1 a3 a4] [a2 a4 a5]].
        let c00 = a[3] * a[5] - a[4] * a[4];
        let c01 = a[2] * a[4] - a[1] * a[5];
        let c02 = a[1] * a[4] - a[2] * a[3];
        let c11 = a[0] * a[5] - a[2] * a[2];
        let c12 = a[1] * a[2] - a[0] * a[4];
        let c22 = a[0] * a[3] - a[1] * a[1];
        let det = a[0] * c00 + a[1] * c01 + a[2] * c02;
        let trace = a[0] + a[3] + a[5];
        if det.is_nan() || det <= 1e-12 * trace * trace * trace {
            return None;
        }
        let [bx, by, bz] = self.b;
        let solution = -Vector::new(
            c00 * bx + c01 * by + c02 * bz,
            c01 * bx + c11 * by + c12 * bz,
            c02 * bx + c12 * by + c22 * bz,
        ) / det;
        solution.iter().all(|c| c.is_finite()).then_some(solution)
    }

    /// The point of the segment `start..end` minimising `Q` and its parameter
    /// `t` in `[0, 1]` (`start + t (end - start)`): the fallback placement where
    /// [`Quadric::minimizer`] is undefined. Where `Q` is constant along the segment,
    /// the midpoint (it keeps triangles best shaped).
    pub fn minimizer_on_segment(&self, start: &Vector, end: &Vector) -> (Vector, f64) {
        let direction = end - start;
        // Q(start + t d) = t² dᵀAd + 2t dᵀ(A start + b) + Q(start).
        let curvature = direction.dot(&self.apply(&direction));
        let slope = direction.dot(&(self.apply(start) + Vector::from(self.b)));
        let t = if curvature > 1e-14 * (slope.abs() + self.c.abs()) && curvature > 0.0 {
            (-slope / curvature).clamp(0.0, 1.0)
        } else {
            0.5
        };
        (start + direction * t, t)
    }
}

impl std::ops::Add for Quadric {
    type Output = Quadric;
    fn add(mut self, other: Quadric) -> Quadric {
        self += other;
        self
    }
}

impl std::ops::AddAssign for Quadric {
    fn add_assign(&mut self, other: Quadric) {
        for (mine, theirs) in self.a.iter_mut().zip(other.a) {
            *mine += theirs;
        }
        for (mine, theirs) in self.b.iter_mut().zip(other.b) {
            *mine += theirs;
        }
        self.c += other.c;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plane_quadric_is_squared_distance() {
        let normal = Vector::new(1.0, 2.0, 2.0) / 3.0;
        let q = Quadric::from_plane_through(&Vector::new(1.0, 0.0, 0.0), &normal, 2.0);
        let p = Vector::new(1.0, 0.0, 0.0) + normal * 0.5 + Vector::new(2.0, -1.0, 0.0);
        assert!((q.error_at(&p) - 2.0 * 0.25).abs() < 1e-12);
    }

    #[test]
    fn three_planes_meet_at_the_minimizer() {
        let corner = Vector::new(0.5, -2.0, 3.0);
        let q = Quadric::from_plane_through(&corner, &Vector::x(), 1.0)
            + Quadric::from_plane_through(&corner, &Vector::y(), 3.0)
            + Quadric::from_plane_through(&corner, &Vector::new(0.0, 0.6, 0.8), 0.5);
        let found = q.minimizer().expect("three independent planes");
        assert!((found - corner).norm() < 1e-9, "{found:?}");
        assert!(q.error_at(&found) < 1e-12);
    }

    #[test]
    fn parallel_planes_have_no_minimizer_but_a_segment_one() {
        let q = Quadric::from_plane(&Vector::z(), -1.0, 1.0) + Quadric::from_plane(&Vector::z(), -3.0, 1.0);
        assert!(q.minimizer().is_none());
        let (point, t) = q.minimizer_on_segment(&Vector::new(0.0, 0.0, 0.0), &Vector::new(4.0, 0.0, 4.0));
        assert!((t - 0.5).abs() < 1e-12 && (point.z - 2.0).abs() < 1e-12);
        // Along a line inside the plane the error is constant: the midpoint is taken.
        let (point, _) = q.minimizer_on_segment(&Vector::new(0.0, 0.0, 2.0), &Vector::new(2.0, 0.0, 2.0));
        assert!((point.x - 1.0).abs() < 1e-12);
    }
}
