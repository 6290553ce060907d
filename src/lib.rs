//! sherd: orient 3D scans of archaeological pottery fragments and draw them as
//! archaeological illustrations.
//!
//! The crate is a pipeline of layers, each depending only on the ones listed before it
//! (`tests/layers.rs` checks every `crate::` path against this order, and that no two
//! modules use each other):
//!
//! * [`error`]: the error type every layer returns.
//! * [`statistics`]: the order statistics the layers share.
//! * [`mesh`]: the [`mesh::Mesh`] type, scan readers and writers, repair, normals,
//!   decimation, smoothing, spatial queries.
//! * [`axis`]: the rotation axis ([`axis::Axis`]), its JSON form and the distances
//!   between axes, shared by the layers after it.
//! * [`synth`]: synthetic sherds with known axes, the test bed of every later layer.
//! * [`orient`]: the rotation axis from normals or three points
//!   (Wilczek et al. 2018, section 2.2).
//! * [`refine`]: refinement criteria (section 2.3): circles, Pareto, profile, tangent.
//! * [`profile`]: sections in the rz-plane, measurements, revolution, regularity.
//! * [`draw`]: the archaeological illustration (section 2.4) and its writers.
//! * [`pipeline`]: the layers chained for one scan (read, repair, orient, refine,
//!   measure, draw), as the command-line tool, the C ABI and batch runs use them.
//! * [`ffi`]: the stable C ABI; no algorithm lives there.
//!
//! Beside the layers, [`mod@vocabulary`] declares every named choice (criteria, styles,
//! statuses...) once, for the layers, the command line, the C ABI and the bindings.

// `!(x >= limit)` is how the crate writes a test that a NaN must fail: `x < limit` would
// let a NaN pass, and `partial_cmp` would hide the intent in an `Option`.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod error;
#[macro_use]
pub mod vocabulary;
pub mod statistics;
pub mod mesh;
pub mod axis;
pub mod synth;
pub mod orient;
pub mod refine;
pub mod profile;
pub mod draw;
pub mod pipeline;
pub mod ffi;

pub use error::{Error, Result};
