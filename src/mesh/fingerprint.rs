//! A scan's fingerprint: its counts and a checksum of its geometry, recorded with an axis
//! (`sherd orient --json`, a batch's records) so that an axis given back for drawing or
//! exporting can be checked against the scan it was found on.

use serde::{Deserialize, Serialize};

use crate::mesh::Mesh;

/// What identifies a scan as read from its file, before any repair or unit conversion.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ScanFingerprint {
    /// Number of vertices (points).
    pub vertices: usize,
    /// Number of triangles.
    pub faces: usize,
    /// FNV-1a (64-bit) of the positions' bits and the triangles' indices, as 16 hex digits.
    pub checksum: String,
}

impl ScanFingerprint {
    /// The fingerprint of `mesh`, as read from its file.
    pub fn of(mesh: &Mesh) -> ScanFingerprint {
        const OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
        const PRIME: u64 = 0x0000_0100_0000_01b3;
        let mut hash = OFFSET;
        let mut eat = |bytes: &[u8]| {
            for &byte in bytes {
                hash = (hash ^ byte as u64).wrapping_mul(PRIME);
            }
        };
        for p in &mesh.positions {
            for c in p.coords.iter() {
                eat(&c.to_bits().to_le_bytes());
            }
        }
        for t in &mesh.triangles {
            for i in t {
                eat(&i.to_le_bytes());
            }
        }
        ScanFingerprint { vertices: mesh.vertex_count(), faces: mesh.face_count(), checksum: format!("{hash:016x}") }
    }

    /// `None` when `other` is the same scan, else what differs, in words.
    pub fn difference(&self, other: &ScanFingerprint) -> Option<String> {
        if self == other {
            return None;
        }
        if (self.vertices, self.faces) != (other.vertices, other.faces) {
            return Some(format!(
                "{} vertices and {} faces against {} vertices and {} faces",
                self.vertices, self.faces, other.vertices, other.faces
            ));
        }
        Some(format!("the same counts ({} vertices, {} faces) but other coordinates (checksum {} against {})", self.vertices, self.faces, self.checksum, other.checksum))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Point;

    #[test]
    fn a_moved_vertex_or_another_face_changes_the_fingerprint() {
        let positions = vec![Point::new(0.0, 0.0, 0.0), Point::new(1.0, 0.0, 0.0), Point::new(0.0, 1.0, 0.0), Point::new(0.0, 0.0, 1.0)];
        let mesh = Mesh::new(positions, vec![[0, 1, 2], [0, 2, 3]]);
        let print = ScanFingerprint::of(&mesh);
        assert_eq!(print, ScanFingerprint::of(&mesh.clone()));
        assert!(print.difference(&print).is_none());
        let mut moved = mesh.clone();
        moved.positions[3].z += 1e-9;
        let other = ScanFingerprint::of(&moved);
        assert!(print.difference(&other).unwrap().contains("other coordinates"));
        let mut fewer = mesh;
        fewer.triangles.pop();
        assert!(print.difference(&ScanFingerprint::of(&fewer)).unwrap().contains("1 faces"));
    }
}
