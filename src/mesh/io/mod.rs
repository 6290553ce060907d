//! Scan readers and writers (PLY, OBJ+MTL+texture, STL, XYZ), all producing one [`crate::mesh::Mesh`].
