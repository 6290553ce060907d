//! The stable C ABI (`include/sherd.h`, generated from this module by cbindgen).
//!
//! Rules: opaque handles with `_free` functions; result structs
//! that begin with a `size` field; every entry point returns a `SherdStatus` and leaves
//! a message for `sherd_last_error_message()`; enum-like inputs are `uint32_t` checked on
//! entry; every pointer is checked for NULL; every body runs inside `catch_unwind`. No
//! algorithm lives here: each entry point converts, calls the Rust API and converts back.

pub mod buffer;
mod builder;
pub mod draw;
pub mod enums;
pub mod error;
pub mod export;
pub mod measure;
pub mod mesh;
pub mod orient;
mod panic;
pub mod pipeline;
pub mod reconstruct;
mod pointers;
pub mod refine;
pub mod status;
pub mod synth;
pub mod version;
pub mod vocabulary;

pub use buffer::*;
pub use draw::*;
pub use enums::*;
pub use error::sherd_last_error_message;
pub use export::*;
pub use measure::*;
pub use mesh::*;
pub use orient::*;
pub use pipeline::*;
pub use reconstruct::*;
pub use refine::*;
pub use status::*;
pub use synth::*;
pub use version::*;
pub use vocabulary::*;
