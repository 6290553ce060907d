//! Reading a 500k-face binary PLY (the layout MeshLab and scanners write: float x y z,
//! float normals, uchar RGBA, `uchar int vertex_indices`): sherd's hand-written reader
//! against ply-rs-bw, both its generic `DefaultElement` parse and its fastest form
//! (parsing into typed structs), to show why sherd has its own reader.
//!
//! cargo bench --bench ply

use std::hint::black_box;
use std::io::Cursor;

use criterion::{Criterion, criterion_group, criterion_main};
use ply_rs_bw::ply::{DefaultElement, Property, PropertyAccess, PropertyAccessResult};
use sherd::mesh::io::read_ply_from;

/// A `side x side` grid of vertices with two triangles per cell: side 501 gives 251,001
/// vertices and 500,000 triangles, written in A011.ply's binary layout.
fn grid_ply(side: usize) -> Vec<u8> {
    let vertex_count = side * side;
    let face_count = 2 * (side - 1) * (side - 1);
    let mut bytes = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex {vertex_count}\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\nelement face {face_count}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    .into_bytes();
    for row in 0..side {
        for column in 0..side {
            let (x, y) = (column as f32 * 0.2, row as f32 * 0.2);
            let z = (x * 0.1).sin() * (y * 0.1).cos() * 5.0;
            for value in [x, y, z, 0.0, 0.0, 1.0] {
                bytes.extend(value.to_le_bytes());
            }
            bytes.extend([(row % 256) as u8, (column % 256) as u8, 128, 255]);
        }
    }
    for row in 0..side - 1 {
        for column in 0..side - 1 {
            let corner = (row * side + column) as i32;
            let side = side as i32;
            for triangle in [[corner, corner + 1, corner + side + 1], [corner, corner + side + 1, corner + side]] {
                bytes.push(3);
                for index in triangle {
                    bytes.extend(index.to_le_bytes());
                }
            }
        }
    }
    bytes
}

/// ply-rs-bw's fastest use: straight into typed structs (still one call per property,
/// dispatched by name).
struct TypedVertex([f32; 6], [u8; 4]);

impl PropertyAccess for TypedVertex {
    fn new() -> Self {
        TypedVertex([0.0; 6], [0; 4])
    }
    fn set_property(&mut self, key: &str, property: Property) -> PropertyAccessResult {
        let slot = ["x", "y", "z", "nx", "ny", "nz"].iter().position(|k| *k == key);
        match (slot, property) {
            (Some(i), Property::Float(v)) => self.0[i] = v,
            (None, Property::UChar(v)) => {
                let channel = ["red", "green", "blue", "alpha"].iter().position(|k| *k == key).unwrap_or(3);
                self.1[channel] = v;
            }
            _ => return PropertyAccessResult::Ignored,
        }
        PropertyAccessResult::Set
    }
}

struct TypedFace(Vec<i32>);

impl PropertyAccess for TypedFace {
    fn new() -> Self {
        TypedFace(Vec::new())
    }
    fn set_property(&mut self, _key: &str, property: Property) -> PropertyAccessResult {
        match property {
            Property::ListInt(indices) => {
                self.0 = indices;
                PropertyAccessResult::Set
            }
            _ => PropertyAccessResult::Ignored,
        }
    }
}

fn read_typed_with_ply_rs(bytes: &[u8]) -> (Vec<TypedVertex>, Vec<TypedFace>) {
    let mut reader = ply_rs_bw::parser::Reader::new(std::io::BufReader::new(Cursor::new(bytes)));
    let vertex_parser = ply_rs_bw::parser::Parser::<TypedVertex>::new();
    let face_parser = ply_rs_bw::parser::Parser::<TypedFace>::new();
    let header = vertex_parser.read_header(&mut reader).expect("header");
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    for element in header.elements.values() {
        match element.name.as_str() {
            "vertex" => vertices = vertex_parser.read_payload_for_element(&mut reader, element, &header).expect("vertices"),
            "face" => faces = face_parser.read_payload_for_element(&mut reader, element, &header).expect("faces"),
            _ => {}
        }
    }
    (vertices, faces)
}

fn ply_reading(c: &mut Criterion) {
    let bytes = grid_ply(501);
    let mut group = c.benchmark_group("read binary PLY, 500k faces");
    group.sample_size(10);
    group.bench_function("sherd (hand-written)", |b| {
        b.iter(|| {
            let mesh = read_ply_from(&mut Cursor::new(black_box(&bytes[..])), "grid.ply").expect("valid PLY");
            assert_eq!(mesh.face_count(), 500_000);
            mesh
        })
    });
    group.bench_function("ply-rs-bw typed structs", |b| {
        b.iter(|| {
            let (vertices, faces) = read_typed_with_ply_rs(black_box(&bytes));
            assert_eq!(faces.len(), 500_000);
            (vertices, faces)
        })
    });
    group.bench_function("ply-rs-bw DefaultElement", |b| {
        b.iter(|| {
            let parser = ply_rs_bw::parser::Parser::<DefaultElement>::new();
            parser.read_ply(&mut Cursor::new(black_box(&bytes[..]))).expect("valid PLY")
        })
    });
    group.finish();
}

criterion_group!(benches, ply_reading);
criterion_main!(benches);
