//! Test fixtures for the mesh processing tests and benches: small meshes with known
//! geometry and topology, deterministic noise, and the pymeshlab bridge.
#![allow(dead_code)]

use std::collections::HashMap;
use std::path::Path;
use std::process::Command;

use sherd::mesh::{Mesh, Point, Vector};

/// A deterministic pseudo-random number in `[-1, 1)` from an integer (SplitMix64), so
/// fixtures are the same on every machine without a random generator's API.
pub fn hash_unit(seed: u64) -> f64 {
    let mut z = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

/// An icosphere of `radius` around `centre`, subdivided `levels` times
/// (20 * 4^levels faces), outward-oriented and watertight.
pub fn icosphere(levels: u32, radius: f64, centre: Point) -> Mesh {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut unit: Vec<Vector> = [
        [-1.0, t, 0.0], [1.0, t, 0.0], [-1.0, -t, 0.0], [1.0, -t, 0.0],
        [0.0, -1.0, t], [0.0, 1.0, t], [0.0, -1.0, -t], [0.0, 1.0, -t],
        [t, 0.0, -1.0], [t, 0.0, 1.0], [-t, 0.0, -1.0], [-t, 0.0, 1.0],
    ]
    .iter()
    .map(|c| Vector::new(c[0], c[1], c[2]).normalize())
    .collect();
    let mut triangles: Vec<[u32; 3]> = vec![
        [0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4],
        [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8],
        [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1],
    ];
    for _ in 0..levels {
        let mut midpoints: HashMap<(u32, u32), u32> = HashMap::new();
        let mut midpoint = |a: u32, b: u32, unit: &mut Vec<Vector>| -> u32 {
            *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
                unit.push((unit[a as usize] + unit[b as usize]).normalize());
                (unit.len() - 1) as u32
            })
        };
        let mut finer = Vec::with_capacity(triangles.len() * 4);
        for [a, b, c] in triangles {
            let ab = midpoint(a, b, &mut unit);
            let bc = midpoint(b, c, &mut unit);
            let ca = midpoint(c, a, &mut unit);
            finer.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        triangles = finer;
    }
    Mesh::new(unit.iter().map(|u| centre + u * radius).collect(), triangles)
}

/// An open `columns x rows` grid of unit squares in the xy-plane (two triangles each),
/// facing +z, with heights `height(x, y)`.
pub fn grid(columns: usize, rows: usize, height: impl Fn(f64, f64) -> f64) -> Mesh {
    let mut positions = Vec::new();
    for j in 0..=rows {
        for i in 0..=columns {
            let (x, y) = (i as f64, j as f64);
            positions.push(Point::new(x, y, height(x, y)));
        }
    }
    let index = |i: usize, j: usize| (j * (columns + 1) + i) as u32;
    let mut triangles = Vec::new();
    for j in 0..rows {
        for i in 0..columns {
            triangles.push([index(i, j), index(i + 1, j), index(i + 1, j + 1)]);
            triangles.push([index(i, j), index(i + 1, j + 1), index(i, j + 1)]);
        }
    }
    Mesh::new(positions, triangles)
}

/// A torus (major radius `major`, tube radius `minor`) with `around x across` quads,
/// its tube radius rippled by `ripple` (relative), outward-oriented and watertight:
/// the 500k-face benchmark mesh is `torus(1000, 250, ...)`.
pub fn torus(around: usize, across: usize, major: f64, minor: f64, ripple: f64) -> Mesh {
    let mut positions = Vec::with_capacity(around * across);
    for i in 0..around {
        let u = i as f64 / around as f64 * std::f64::consts::TAU;
        for j in 0..across {
            let v = j as f64 / across as f64 * std::f64::consts::TAU;
            let r = minor * (1.0 + ripple * (7.0 * u).sin() * (5.0 * v).cos());
            positions.push(Point::new((major + r * v.cos()) * u.cos(), (major + r * v.cos()) * u.sin(), r * v.sin()));
        }
    }
    let index = |i: usize, j: usize| ((i % around) * across + (j % across)) as u32;
    let mut triangles = Vec::with_capacity(2 * around * across);
    for i in 0..around {
        for j in 0..across {
            triangles.push([index(i, j), index(i + 1, j), index(i + 1, j + 1)]);
            triangles.push([index(i, j), index(i + 1, j + 1), index(i, j + 1)]);
        }
    }
    Mesh::new(positions, triangles)
}

/// Moves every vertex by up to `amplitude` along each axis, deterministically from `seed`.
pub fn add_noise(mesh: &mut Mesh, amplitude: f64, seed: u64) {
    for (i, p) in mesh.positions.iter_mut().enumerate() {
        let base = seed.wrapping_mul(1_000_003).wrapping_add(3 * i as u64);
        *p += Vector::new(hash_unit(base), hash_unit(base + 1), hash_unit(base + 2)) * amplitude;
    }
}

/// The mesh as a triangle soup: every face gets its own three vertices (what STL files
/// and some exporters give), attributes copied along.
pub fn triangle_soup(mesh: &Mesh) -> Mesh {
    let corners: Vec<u32> = mesh.triangles.iter().flatten().copied().collect();
    fn pick<T: Copy>(values: &[T], corners: &[u32]) -> Vec<T> {
        corners.iter().map(|&c| values[c as usize]).collect()
    }
    Mesh {
        positions: corners.iter().map(|&c| mesh.positions[c as usize]).collect(),
        triangles: (0..mesh.triangles.len() as u32).map(|f| [3 * f, 3 * f + 1, 3 * f + 2]).collect(),
        normals: mesh.normals.as_deref().map(|v| pick(v, &corners)),
        colors: mesh.colors.as_deref().map(|v| pick(v, &corners)),
        quality: mesh.quality.as_deref().map(|v| pick(v, &corners)),
        corner_uvs: mesh.corner_uvs.clone(),
        texture: mesh.texture.clone(),
    }
}

/// The real scan `relative` (under `../shared/data`), or `None` with a printed SKIPPED
/// message when the shared data folder is absent.
pub fn shared_data_file(test: &str, relative: &str) -> Option<std::path::PathBuf> {
    let path = repo_root().join("../shared/data").join(relative);
    if path.is_file() {
        Some(path)
    } else {
        eprintln!("SKIPPED {test}: {} is absent", path.display());
        None
    }
}

/// Runs a Python snippet with `arguments` (as `sys.argv[1:]`) and returns its standard
/// output; panics with its standard error when it fails.
pub fn python_output(code: &str, arguments: &[&std::ffi::OsStr]) -> String {
    let run = Command::new("python3").arg("-c").arg(code).args(arguments).output().expect("python3 runs");
    assert!(run.status.success(), "python failed: {}", String::from_utf8_lossy(&run.stderr));
    String::from_utf8(run.stdout).unwrap()
}

/// True when `python3 -c "import pymeshlab"` works. When it does not: panics if
/// `SHERD_REQUIRE_PYMESHLAB=1` (the full test suite must really compare), otherwise
/// prints why the comparison is skipped and returns false.
pub fn pymeshlab_available(test: &str) -> bool {
    let works = Command::new("python3")
        .args(["-c", "import pymeshlab"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !works {
        if std::env::var("SHERD_REQUIRE_PYMESHLAB").is_ok_and(|v| v == "1") {
            panic!("{test}: pymeshlab is required (SHERD_REQUIRE_PYMESHLAB=1) but `import pymeshlab` fails");
        }
        eprintln!("SKIPPED {test}: pymeshlab is not installed (pip install pymeshlab)");
    }
    works
}

/// Vertex positions from a text file of `x y z` rows (what the pymeshlab scripts write).
pub fn read_positions(path: &Path) -> Vec<Point> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let c: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            Point::new(c[0], c[1], c[2])
        })
        .collect()
}

/// The repository's root (where Cargo.toml is).
pub fn repo_root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}
