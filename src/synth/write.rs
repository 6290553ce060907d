//! Synthetic sherds as files: `NAME.ply` (binary, with normals and colours) beside
//! `NAME.truth.json` (the [`GroundTruth`]), both written atomically, so that the CLI,
//! the batch tool and tests in other languages can use the same test bed.

use std::path::{Path, PathBuf};

use super::{GroundTruth, SynthSherd};
use crate::mesh::atomic::write_atomically;
use crate::mesh::io::{write_ply, PlyEncoding};
use crate::{Error, Result};

/// The file stem of a sherd: `sherd_SEED_PART`, or `vessel_SEED_fragment_K` for a
/// fragment of [`super::generate_vessel`].
pub fn file_stem(truth: &GroundTruth) -> String {
    match truth.fragment_index {
        Some(index) => format!("vessel_{}_fragment_{index:03}", truth.seed),
        None => format!("sherd_{}_{}", truth.seed, truth.part.name()),
    }
}

/// Writes `DIR/NAME.ply` and `DIR/NAME.truth.json` (NAME from [`file_stem`]) and returns
/// the path of the PLY file. `dir` must exist.
pub fn write_sherd(dir: &Path, sherd: &SynthSherd) -> Result<PathBuf> {
    let stem = file_stem(&sherd.truth);
    let mesh_path = dir.join(format!("{stem}.ply"));
    let truth_path = dir.join(format!("{stem}.truth.json"));
    write_ply(&mesh_path, &sherd.mesh, PlyEncoding::BinaryLittleEndian)?;
    write_atomically(&truth_path, |writer| {
        serde_json::to_writer_pretty(&mut *writer, &sherd.truth)
            .map_err(|e| Error::io(&truth_path, std::io::Error::other(e)))?;
        writer.write_all(b"\n").map_err(|e| Error::io(&truth_path, e))
    })?;
    Ok(mesh_path)
}

/// Reads a `NAME.truth.json` written by [`write_sherd`].
pub fn read_truth(path: &Path) -> Result<GroundTruth> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    serde_json::from_str(&text).map_err(|e| {
        Error::parse(path.display().to_string(), format!("line {}, column {}", e.line(), e.column()), e.to_string())
    })
}
