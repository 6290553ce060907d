//! Sections in the rz-plane, measurements (rim/base radius, sector angle, height, wall
//! thickness, capacity), revolution into a 3D reconstruction, and vessel regularity.

pub mod measure;
pub mod regularity;
pub mod revolve;
pub mod rills;
pub mod section;
