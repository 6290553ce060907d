//! Scan readers and writers (PLY, OBJ+MTL+texture, STL, XYZ/PTS), all producing one
//! [`crate::mesh::Mesh`].
//!
//! Every reader refuses broken input with an [`Error::Parse`] naming the file, where it
//! went wrong (header line, body line for text formats, byte offset for binary ones), the
//! element and the offending value, and never allocates more than the file can hold: a
//! header that declares 10^12 vertices in a 2 kB file is refused before any allocation.
//! What was read but not kept (unknown elements, a missing texture, degenerate polygons)
//! is listed in the [`ReadReport`]. The files a scan names (material library, texture)
//! are read only from inside the scan's folder (`file_in_scan_folder`).

mod obj;
mod ply_read;
mod ply_write;
mod points;
mod stl;
mod texture;
mod units;

use std::path::{Component, Path, PathBuf};

use serde::Serialize;

use crate::mesh::Mesh;
use crate::{Error, Result};

pub use ply_read::{read_ply_from, read_ply_from_with_report};
pub use ply_write::{PlyEncoding, write_ply, write_ply_to};
pub use units::{LengthUnit, UnitsGuess, guess_units, unit_declared_in};

/// What a reader did besides producing the mesh: the format it recognised and the
/// warnings about what it skipped or could not load.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ReadReport {
    /// The format as recognised, e.g. `"ply binary_little_endian"`, `"stl ascii"`, `"obj"`.
    pub format: String,
    /// Polygons with more than three corners that were split into triangles (fan).
    pub polygons_triangulated: usize,
    /// Faces with fewer than three distinct corners that were dropped.
    pub degenerate_faces_dropped: usize,
    /// Human-readable warnings: skipped elements and properties, missing texture...
    pub warnings: Vec<String>,
    /// The length unit a comment of the file declares ([`unit_declared_in`]).
    pub declared_unit: Option<LengthUnit>,
}

impl ReadReport {
    fn new(format: impl Into<String>) -> Self {
        ReadReport { format: format.into(), ..Default::default() }
    }

    fn warn(&mut self, message: impl Into<String>) {
        self.warnings.push(message.into());
    }
}

/// Reads a mesh or point cloud, choosing the reader by extension (`.ply`, `.obj`, `.stl`,
/// `.xyz`, `.pts`; case-insensitive). See [`read_mesh_with_report`] for the warnings.
pub fn read_mesh(path: &Path) -> Result<Mesh> {
    read_mesh_with_report(path).map(|(mesh, _)| mesh)
}

/// Reads a mesh or point cloud by extension and says what was skipped or could not be
/// loaded (unknown PLY elements, a texture named by the MTL file but absent...).
pub fn read_mesh_with_report(path: &Path) -> Result<(Mesh, ReadReport)> {
    let bytes = read_regular_file(path, u64::MAX)?;
    read_mesh_from_bytes(&bytes, path)
}

/// Largest material library read: MTL files are a few kilobytes, so a bigger one is not
/// a material library (and must not be loaded whole just to look for `map_Kd`).
const MAX_MATERIAL_LIBRARY_BYTES: u64 = 16 << 20;

/// Largest texture file read, before decoding (whose own limit is on the decoded size).
const MAX_TEXTURE_FILE_BYTES: u64 = 256 << 20;

/// Reads the whole of `path`, refusing what is not a regular file (a FIFO, `/dev/zero` or
/// `/dev/stdin` named by a scan or its material library would block or never end) and a
/// file larger than `max_bytes`, before reading it.
fn read_regular_file(path: &Path, max_bytes: u64) -> Result<Vec<u8>> {
    use std::io::Read;
    let file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
    let metadata = file.metadata().map_err(|e| Error::io(path, e))?;
    let name = path.display().to_string();
    if !metadata.is_file() {
        let kind = if metadata.is_dir() { "a folder" } else { "a device, FIFO or socket" };
        return Err(Error::parse(name, "file", format!("not a regular file but {kind}")));
    }
    if metadata.len() > max_bytes {
        return Err(Error::parse(name, "file", format!("{} bytes, more than the {max_bytes} such a file may have", metadata.len())));
    }
    let mut bytes = Vec::with_capacity(metadata.len() as usize);
    // The file may grow while it is read: never read past the limit either.
    file.take(max_bytes).read_to_end(&mut bytes).map_err(|e| Error::io(path, e))?;
    Ok(bytes)
}

/// Where a file that a scan refers to (an OBJ's `mtllib`, a MTL's `map_Kd`, a PLY's
/// `comment TextureFile`) is, provided it lies inside the scan's `folder`: a scan (from a
/// colleague, an archive, the web) must not make sherd read `/etc/passwd`, another user's
/// files or a device. Refused: absolute names (`/...`, `C:/...`, `\\server\...`), `..` that
/// climbs out of the folder, and a name inside the folder that is a symbolic link to
/// somewhere outside it (checked after canonicalisation). A name that does not exist is
/// given back as is: reading it then says it is missing.
///
/// `what` ("texture", "material library") and `referrer` (the file and line naming it) go
/// into the message of a refusal, which callers report as a warning: the geometry is good
/// without the texture.
fn file_in_scan_folder(folder: &Path, named: &str, what: &str, referrer: &str) -> std::result::Result<PathBuf, String> {
    let refuse = |why: String| Err(format!("{referrer}: {what} {named:?} refused, not read: {why}; only files inside the scan's folder are read"));
    // Scans made on Windows separate folders with backslashes.
    let relative = named.replace('\\', "/");
    let bytes = relative.as_bytes();
    let drive_letter = bytes.len() >= 2 && bytes[0].is_ascii_alphabetic() && bytes[1] == b':';
    if relative.starts_with('/') || drive_letter {
        return refuse("it is an absolute path".into());
    }
    let mut depth = 0_i64;
    for component in Path::new(&relative).components() {
        match component {
            Component::Normal(_) => depth += 1,
            Component::ParentDir => depth -= 1,
            Component::CurDir => {}
            Component::RootDir | Component::Prefix(_) => return refuse("it is an absolute path".into()),
        }
        if depth < 0 {
            return refuse("its \"..\" leads out of the scan's folder".into());
        }
    }
    let path = folder.join(&relative);
    // A folder given as "" (a scan named without a folder) is the current one.
    let folder = if folder.as_os_str().is_empty() { Path::new(".") } else { folder };
    if let (Ok(target), Ok(folder)) = (path.canonicalize(), folder.canonicalize()) {
        if !target.starts_with(&folder) {
            return refuse(format!("it is a symbolic link to {}, outside the scan's folder", target.display()));
        }
    }
    Ok(path)
}

/// Parses `bytes` as the content of the file `path`: the extension chooses the reader,
/// the name goes into messages, and the folder is where an OBJ's material library and a
/// texture are looked for. Used by [`read_mesh_with_report`] and by the fuzz targets.
pub fn read_mesh_from_bytes(bytes: &[u8], path: &Path) -> Result<(Mesh, ReadReport)> {
    let name = path.display().to_string();
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    if bytes.is_empty() {
        return Err(Error::parse(name, "byte 0", "the file is empty"));
    }
    if let Some(kind) = foreign_signature(bytes) {
        if !(extension == "png" || extension == "jpg" || extension == "jpeg") {
            return Err(Error::parse(
                name,
                "byte 0",
                format!("this is a {kind}, not a mesh (the extension says .{extension})"),
            ));
        }
    }
    let folder = path.parent();
    let (mesh, report) = match extension.as_str() {
        "ply" => ply_read::parse_ply(bytes, &name, folder)?,
        "obj" => obj::parse_obj(bytes, &name, folder)?,
        "stl" => stl::parse_stl(bytes, &name)?,
        "xyz" | "pts" | "txt" | "asc" => points::parse_points(bytes, &name)?,
        _ => {
            return Err(Error::parse(
                name,
                "file name",
                format!(
                    "unsupported extension {:?}: sherd reads .ply, .obj, .stl, .xyz and .pts",
                    extension
                ),
            ));
        }
    };
    Ok((mesh, report))
}

/// Recognises files that are certainly not meshes (images, archives, PDF) by their first
/// bytes, so that "a PNG where a PLY should be" gets a message saying so.
fn foreign_signature(bytes: &[u8]) -> Option<&'static str> {
    const SIGNATURES: [(&[u8], &str); 6] = [
        (b"\x89PNG\r\n\x1a\n", "PNG image"),
        (b"\xff\xd8\xff", "JPEG image"),
        (b"PK\x03\x04", "ZIP archive"),
        (b"%PDF", "PDF document"),
        (b"\x1f\x8b", "gzip-compressed file"),
        (b"GIF8", "GIF image"),
    ];
    SIGNATURES.iter().find(|(magic, _)| bytes.starts_with(magic)).map(|(_, kind)| *kind)
}

/// Splits a polygon into a fan of triangles `(0, i, i+1)`, the triangulation MeshLab and
/// Blender apply to the convex polygons scanners write. Returns the corner positions
/// (indices into `corners`) of each triangle.
fn fan_triangles(corner_count: usize) -> impl Iterator<Item = [usize; 3]> {
    (1..corner_count.saturating_sub(1)).map(|i| [0, i, i + 1])
}

/// Shows a token of a text file in a message, escaping what is not printable and
/// shortening what is long, so that a binary file read as text gives a readable error.
fn show_token(token: &[u8]) -> String {
    let shown: String = String::from_utf8_lossy(&token[..token.len().min(40)]).escape_debug().collect();
    if token.len() > 40 { format!("\"{shown}...\"") } else { format!("\"{shown}\"") }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fan_of_a_pentagon_has_three_triangles_sharing_the_first_corner() {
        let triangles: Vec<_> = fan_triangles(5).collect();
        assert_eq!(triangles, vec![[0, 1, 2], [0, 2, 3], [0, 3, 4]]);
        assert_eq!(fan_triangles(2).count(), 0);
        assert_eq!(fan_triangles(0).count(), 0);
    }

    #[test]
    fn foreign_files_are_named() {
        assert_eq!(foreign_signature(b"\x89PNG\r\n\x1a\nrest"), Some("PNG image"));
        assert_eq!(foreign_signature(b"ply\nformat ascii 1.0\n"), None);
    }

    #[test]
    fn only_files_inside_the_scan_folder_are_given() {
        let scan = tempfile::tempdir().unwrap();
        let outside = tempfile::tempdir().unwrap();
        std::fs::create_dir(scan.path().join("textures")).unwrap();
        std::fs::write(scan.path().join("textures/skin.png"), b"x").unwrap();
        std::fs::write(outside.path().join("secret.png"), b"x").unwrap();
        std::os::unix::fs::symlink(outside.path().join("secret.png"), scan.path().join("link.png")).unwrap();
        std::os::unix::fs::symlink(scan.path().join("textures/skin.png"), scan.path().join("inner_link.png")).unwrap();
        let check = |named: &str| file_in_scan_folder(scan.path(), named, "texture", "scan.obj line 3");
        for inside in ["textures/skin.png", "./textures/../textures/skin.png", "inner_link.png", "absent.png", "textures\\skin.png"] {
            assert!(check(inside).is_ok(), "{inside}: {:?}", check(inside));
        }
        for (hostile, why) in [
            ("/etc/passwd", "absolute path"),
            ("C:/Users/me/skin.png", "absolute path"),
            ("\\\\server\\share\\skin.png", "absolute path"),
            ("../../etc/passwd", "leads out"),
            ("textures/../../skin.png", "leads out"),
            ("..\\..\\skin.png", "leads out"),
            ("link.png", "symbolic link to"),
        ] {
            let message = check(hostile).unwrap_err();
            assert!(message.contains(why) && message.contains("scan.obj line 3") && message.contains(hostile.replace('\\', "\\\\").as_str()), "{hostile}: {message}");
        }
    }
}
