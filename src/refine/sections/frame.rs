//! A candidate axis: its four parameters relative to the start axis, and the rigid motion
//! into its frame, where the criteria see the axis as z.

use nalgebra::Rotation3;

use crate::mesh::{Point, Vector};

/// A candidate axis as four parameters in the start frame: turns `tilt_x_rad` about x
/// and `tilt_y_rad` about y of the start direction (+z), and the point where the axis
/// crosses z = 0, `(shift_x_mm, shift_y_mm)`. The start axis is all zeros.
pub type AxisParameters = [f64; 4];

/// The rigid motion from the start frame to the frame of a candidate axis.
#[derive(Clone, Copy, Debug)]
pub struct CandidateFrame {
    rotation: Rotation3<f64>,
    shift: Vector,
}

impl CandidateFrame {
    /// The frame of the candidate `parameters`.
    pub fn new(parameters: &AxisParameters) -> Self {
        let rotation = Rotation3::from_axis_angle(&Vector::y_axis(), parameters[1])
            * Rotation3::from_axis_angle(&Vector::x_axis(), parameters[0]);
        CandidateFrame { rotation, shift: Vector::new(parameters[2], parameters[3], 0.0) }
    }

    /// The candidate axis's direction in the start frame.
    pub fn direction(&self) -> Vector {
        self.rotation * Vector::z()
    }

    /// A start-frame point in the candidate frame (axis on z).
    pub fn apply(&self, p: &Point) -> Point {
        Point::from(self.rotation.inverse_transform_vector(&(p.coords - self.shift)))
    }

    /// The height of a start-frame point in the candidate frame: [`CandidateFrame::apply`]'s
    /// `z` alone, computed the same way (the third column of the rotation dotted with the
    /// shifted point), for searches that compare heights of many points.
    #[inline]
    pub fn height(&self, p: &Point) -> f64 {
        self.rotation.matrix().column(2).dot(&(p.coords - self.shift))
    }

    /// A candidate-frame point back in the start frame.
    pub fn to_start(&self, p: &Point) -> Point {
        Point::from(self.rotation * p.coords + self.shift)
    }

    /// A start-frame vector in the candidate frame.
    pub fn apply_vector(&self, v: &Vector) -> Vector {
        self.rotation.inverse_transform_vector(v)
    }

    /// A candidate-frame vector back in the start frame.
    pub fn vector_to_start(&self, v: &Vector) -> Vector {
        self.rotation * v
    }
}

/// The tilts `[about x, about y]` of [`CandidateFrame::new`] whose axis runs along
/// `direction` (start frame, pointing up, any length).
pub fn tilts_along(direction: &Vector) -> [f64; 2] {
    // direction = Ry(b) Rx(a) z = (sin b cos a, -sin a, cos b cos a)
    let norm = direction.norm();
    [(-direction.y / norm).clamp(-1.0, 1.0).asin(), direction.x.atan2(direction.z)]
}

/// The parameters of the axis with tilts `tilts` through the point `centre` at height
/// `height_mm` of the candidate frame with those tilts and no shift.
pub fn axis_through(tilts: [f64; 2], centre: [f64; 2], height_mm: f64) -> AxisParameters {
    let frame = CandidateFrame::new(&[tilts[0], tilts[1], 0.0, 0.0]);
    let direction = frame.direction();
    let on_axis = frame.to_start(&Point::new(centre[0], centre[1], height_mm));
    let crossing = on_axis + direction * (-on_axis.z / direction.z);
    [tilts[0], tilts[1], crossing.x, crossing.y]
}
