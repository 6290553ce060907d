//! Ambient occlusion against MeshLab's (pymeshlab `compute_scalar_ambient_occlusion`) on
//! the same mesh: the per-vertex ranks must agree (Spearman >= 0.9).
//!
//! Skips when python3/pymeshlab is missing, unless SHERD_REQUIRE_PYMESHLAB=1 (then fails).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use sherd::mesh::io::{read_mesh, write_ply, PlyEncoding};
use sherd::draw::occlusion::{ambient_occlusion, OcclusionOptions};

fn shared_data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data")
}

mod support;

/// Ranks with ties averaged.
fn ranks(values: &[f64]) -> Vec<f64> {
    let mut order: Vec<usize> = (0..values.len()).collect();
    order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
    let mut ranks = vec![0.0; values.len()];
    let mut i = 0;
    while i < order.len() {
        let mut j = i;
        while j + 1 < order.len() && values[order[j + 1]] == values[order[i]] {
            j += 1;
        }
        let average = (i + j) as f64 / 2.0;
        for k in i..=j {
            ranks[order[k]] = average;
        }
        i = j + 1;
    }
    ranks
}

fn spearman(a: &[f64], b: &[f64]) -> f64 {
    let (ra, rb) = (ranks(a), ranks(b));
    let n = ra.len() as f64;
    let (ma, mb) = (ra.iter().sum::<f64>() / n, rb.iter().sum::<f64>() / n);
    let (mut sab, mut saa, mut sbb) = (0.0, 0.0, 0.0);
    for (x, y) in ra.iter().zip(&rb) {
        sab += (x - ma) * (y - mb);
        saa += (x - ma) * (x - ma);
        sbb += (y - mb) * (y - mb);
    }
    sab / (saa * sbb).sqrt()
}

#[test]
fn spearman_of_identical_and_reversed_orders() {
    let a = [1.0, 2.0, 2.0, 5.0, 7.0];
    assert!((spearman(&a, &a) - 1.0).abs() < 1e-12);
    let reversed: Vec<f64> = a.iter().map(|x| -x).collect();
    assert!((spearman(&a, &reversed) + 1.0).abs() < 1e-12);
}

#[test]
fn occlusion_ranks_agree_with_meshlab_on_a_real_sherd() {
    let scan = shared_data().join("dacord/A011.ply");
    if !scan.exists() {
        println!("SKIP: {} is absent", scan.display());
        return;
    }
    if !support::pymeshlab_available("occlusion") {
        println!("SKIP: pymeshlab is not installed (set SHERD_REQUIRE_PYMESHLAB=1 to fail instead)");
        return;
    }
    let mesh = read_mesh(&scan).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("in.ply");
    let output = dir.path().join("meshlab_ao.txt");
    // pymeshlab may reorder nothing on load of a binary PLY we wrote: vertex i stays i.
    let mut plain = mesh.clone();
    plain.colors = None;
    plain.quality = None;
    write_ply(&input, &plain, PlyEncoding::BinaryLittleEndian).unwrap();
    let script = format!(
        "import pymeshlab, numpy, time\n\
         ms = pymeshlab.MeshSet()\n\
         ms.load_new_mesh({input:?})\n\
         t = time.time()\n\
         ms.compute_scalar_ambient_occlusion(rays=512)\n\
         print('meshlab_seconds', time.time() - t)\n\
         m = ms.current_mesh()\n\
         assert m.vertex_number() == {count}\n\
         numpy.savetxt({output:?}, m.vertex_scalar_array())\n",
        input = input.to_str().unwrap(),
        output = output.to_str().unwrap(),
        count = mesh.vertex_count()
    );
    let run = Command::new("python3").args(["-c", &script]).output().unwrap();
    assert!(run.status.success(), "pymeshlab failed: {}", String::from_utf8_lossy(&run.stderr));
    println!("{}", String::from_utf8_lossy(&run.stdout).trim());
    let meshlab: Vec<f64> =
        std::fs::read_to_string(&output).unwrap().lines().map(|l| l.trim().parse::<f64>().unwrap()).collect();
    assert_eq!(meshlab.len(), mesh.vertex_count());

    let start = Instant::now();
    let ours = ambient_occlusion(&mesh, &OcclusionOptions::default()).unwrap();
    println!("sherd_seconds {:.3} (build profile of this test)", start.elapsed().as_secs_f64());
    let ours: Vec<f64> = ours.iter().map(|&v| v as f64).collect();
    let rho = spearman(&ours, &meshlab);
    println!("spearman {rho:.4} over {} vertices", ours.len());
    assert!(rho >= 0.9, "rank correlation with MeshLab's ambient occlusion is {rho:.3}");
}
