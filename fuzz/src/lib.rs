//! The fuzz harnesses of sherd, one function per target: each feeds arbitrary bytes to a
//! reader (or builds a small mesh from them and runs the pipeline) and panics only when
//! sherd breaks a promise: a panic inside sherd, a mesh that fails its own validation, an
//! error message that does not name the file. The fuzz targets (`fuzz_targets/`) call
//! these, and `tests/fuzz_regressions.rs` replays the committed corpora and every input a
//! fuzzer ever found through the same functions under plain `cargo test`.

use std::path::{Path, PathBuf};

use sherd::draw::{DrawOptions, Drawing, Format, Style};
use sherd::mesh::io::read_mesh_from_bytes;
use sherd::mesh::{Mesh, Point};
use sherd::orient::{Axis, OrientOptions, orient_automatic};
use sherd::refine::{RefineOptions, refine};

/// A fuzz target's harness: it runs one input.
type Harness = fn(&[u8]);

/// The harness of each fuzz target, by target name.
pub const TARGETS: [(&str, Harness); 6] = [
    ("ply_ascii", ply_ascii),
    ("ply_binary", ply_binary),
    ("obj_mtl", obj_mtl),
    ("stl", stl),
    ("xyz", xyz),
    ("pipeline", pipeline),
];

/// Reads `bytes` as the file `name` and checks what came out.
fn read_and_check(bytes: &[u8], path: &Path) {
    match read_mesh_from_bytes(bytes, path) {
        Ok((mesh, _report)) => {
            if let Err(error) = mesh.validate() {
                panic!("the reader returned an invalid mesh: {error}");
            }
        }
        Err(error) => {
            let message = error.to_string();
            let name = path.file_name().unwrap().to_string_lossy();
            assert!(message.contains(&*name), "the error does not name the file: {message}");
        }
    }
}

/// Whole PLY files, header included: the seeds are ascii files, so mutations explore the
/// header grammar and the text body.
pub fn ply_ascii(data: &[u8]) {
    read_and_check(data, Path::new("fuzz.ply"));
}

/// Binary PLY bodies behind one of a few fixed headers (chosen by the first byte), so
/// that the fuzzer spends its time in the binary body decoder rather than in the header.
pub fn ply_binary(data: &[u8]) {
    const HEADERS: [&str; 4] = [
        "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n",
        "ply\nformat binary_big_endian 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\nproperty float nx\nproperty float ny\nproperty float nz\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face 2\nproperty list uchar uint vertex_indices\nend_header\n",
        "ply\nformat binary_little_endian 1.0\ncomment TextureFile absent.png\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty float quality\nelement face 2\nproperty list uchar int vertex_indices\nproperty list uchar float texcoord\nend_header\n",
        "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty short x\nproperty short y\nproperty short z\nelement junk 3\nproperty list int int stuff\nelement face 2\nproperty list ushort ushort vertex_indices\nproperty uchar flags\nend_header\n",
    ];
    let Some((&choice, body)) = data.split_first() else { return };
    let mut file = HEADERS[choice as usize % HEADERS.len()].as_bytes().to_vec();
    file.extend_from_slice(body);
    read_and_check(&file, Path::new("fuzz.ply"));
}

/// Where the OBJ target writes its MTL file: one folder per process, so that parallel
/// fuzzing jobs do not share it.
fn obj_folder() -> PathBuf {
    let folder = std::env::temp_dir().join(format!("sherd-fuzz-obj-{}", std::process::id()));
    std::fs::create_dir_all(&folder).expect("a temporary folder for the OBJ target");
    folder
}

/// An OBJ file and its material library, separated by a line `#MTL`: the MTL part is
/// written beside as `fuzz.mtl` (which the OBJ part names with `mtllib fuzz.mtl`), so
/// that material parsing and texture lookup run too.
pub fn obj_mtl(data: &[u8]) {
    const SEPARATOR: &[u8] = b"\n#MTL\n";
    let (obj, mtl) = match data.windows(SEPARATOR.len()).position(|w| w == SEPARATOR) {
        Some(at) => (&data[..at], &data[at + SEPARATOR.len()..]),
        None => (data, &[][..]),
    };
    let folder = obj_folder();
    std::fs::write(folder.join("fuzz.mtl"), mtl).expect("writing the MTL part");
    read_and_check(obj, &folder.join("fuzz.obj"));
}

/// STL files, ascii and binary (the reader tells them apart by content).
pub fn stl(data: &[u8]) {
    read_and_check(data, Path::new("fuzz.stl"));
}

/// XYZ and PTS point clouds (the first byte chooses the extension).
pub fn xyz(data: &[u8]) {
    let Some((&choice, text)) = data.split_first() else { return };
    let name = if choice % 2 == 0 { "fuzz.xyz" } else { "fuzz.pts" };
    read_and_check(text, Path::new(name));
}

/// Little-endian reader of the pipeline target's bytes; reads zeros past the end.
struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn u8(&mut self) -> u8 {
        let Some((&first, rest)) = self.0.split_first() else { return 0 };
        self.0 = rest;
        first
    }

    fn i16(&mut self) -> i16 {
        i16::from_le_bytes([self.u8(), self.u8()])
    }
}

/// A small mesh from bytes: up to 67 vertices on a 0.1 mm grid within about 3 m, and up to
/// 130 triangles whose corners index them (repeated corners and all), then automatic
/// orientation, refinement on the axis found, and a drawing (SVG, in memory) along it,
/// whatever the verdict. Errors are answers; only panics, hangs and blow-ups are findings.
pub fn pipeline(data: &[u8]) {
    let mut bytes = Bytes(data);
    let vertex_count = 3 + bytes.u8() as usize % 64;
    let triangle_count = 1 + bytes.u8() as usize % 130;
    let positions: Vec<Point> = (0..vertex_count)
        .map(|_| Point::new(bytes.i16() as f64 * 0.1, bytes.i16() as f64 * 0.1, bytes.i16() as f64 * 0.1))
        .collect();
    let triangles: Vec<[u32; 3]> = (0..triangle_count)
        .map(|_| [0; 3].map(|_: u32| (bytes.u8() as usize % vertex_count) as u32))
        .collect();
    let mesh = Mesh::new(positions, triangles);
    let orient_options = OrientOptions::default();
    let Ok(orientation) = orient_automatic(&mesh, &orient_options) else { return };
    let axis = orientation.axis;
    let refine_options = RefineOptions::default();
    let axis = match refine(&mesh, &axis, &refine_options) {
        Ok(refinement) => refinement.axis,
        Err(_) => axis,
    };
    let style = bytes.u8();
    draw(&mesh, &axis, style);
    // A drawing along an arbitrary axis too: the drawing code must cope with any axis the
    // user gives, not only with those the orientation finds.
    let direction = [bytes.i16(), bytes.i16(), bytes.i16()].map(|c| c as f64);
    if direction.iter().any(|&c| c != 0.0) {
        let point = Point::new(bytes.i16() as f64 * 0.1, bytes.i16() as f64 * 0.1, bytes.i16() as f64 * 0.1);
        draw(&mesh, &Axis::new(point, direction.into()), style);
    }
}

/// Draws with the styles of the bits of `style` (all six when none is set), at the lowest
/// resolution (10 dpi) and at 1:5, so that a view of a mesh 3 m across stays a fraction
/// of a megapixel: at 50 dpi such views (bounded at 50 million pixels by the library, so
/// not a hang) took over 10 s each under AddressSanitizer, and at 10 dpi and 1:1 a hundred
/// overlapping triangles each filling a 1300-pixel view still took 0.9 s natively and 33 s
/// under AddressSanitizer (`fuzz/regressions/pipeline/timeout-*-large-triangles-*`):
/// the fuzzer's time went to filling pixels instead of to new inputs.
fn draw(mesh: &Mesh, axis: &Axis, style: u8) {
    let bit = |n: u8| style & (1 << n) != 0 || style & 63 == 0;
    let style = Style { linear: bit(0), colour: bit(1), light: bit(2), occlusion: bit(3), stipple: bit(4), regularity: bit(5) };
    let options = DrawOptions { style, dpi: 10.0, scale_denominator: 5, ..DrawOptions::default() };
    if let Ok(drawing) = Drawing::build(mesh, axis, &options) {
        let _ = drawing.to_bytes(Format::Svg);
    }
}
