//! The one error type of the library. Every variant maps to one `SherdStatus` code of
//! the C ABI, and every message names what was wrong (file, element, line or byte, value)
//! so that an archaeologist can act on it without reading the source.

use std::path::PathBuf;

/// Result with the library's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What went wrong, with enough context to act on it.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file could not be opened, read or written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file concerned.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// A file's content is malformed. `location` says where (element, line or byte).
    #[error("{file}: {location}: {message}")]
    Parse {
        /// The file (or `"<memory>"` for buffers) being read.
        file: String,
        /// Where in the file: "line 12", "byte 4096 (vertex 17)", "header".
        location: String,
        /// What is wrong there.
        message: String,
    },
    /// A caller passed a value outside what the function accepts.
    #[error("invalid argument: {0}")]
    InvalidArgument(String),
    /// The geometry cannot support the operation (empty, flat, collinear points...).
    #[error("degenerate geometry: {0}")]
    DegenerateGeometry(String),
    /// An optimisation stopped at its bound without meeting its tolerance.
    #[error("not converged: {0}")]
    NotConverged(String),
    /// The data do not determine an axis; a human must give three points.
    #[error("needs manual orientation: {0}")]
    NeedsManualOrientation(String),
}

impl Error {
    /// Shorthand for a [`Error::Parse`].
    pub fn parse(file: impl Into<String>, location: impl Into<String>, message: impl Into<String>) -> Self {
        Error::Parse { file: file.into(), location: location.into(), message: message.into() }
    }

    /// Shorthand for an [`Error::Io`].
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Io { path: path.into(), source }
    }
}
