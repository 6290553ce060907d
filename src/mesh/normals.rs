//! Vertex normals, angle- or area-weighted, oriented outward.
