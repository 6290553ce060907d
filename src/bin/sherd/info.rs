//! `sherd info SCAN [--json]`: what a scan file holds, before any processing.

use std::path::PathBuf;

use serde::Serialize;
use sherd::Result;
use sherd::mesh::io::{ReadReport, UnitsGuess, guess_units, read_mesh_with_report};
use sherd::mesh::repair::{RepairOptions, RepairReport, repair};

/// Arguments of `sherd info`.
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  sherd info A011.ply\n  sherd info scan.obj --json | jq .repair\n  sherd info scan.ply --merge-tolerance-mm 0.01 --keep-largest-component\n\n\
The scan is described as read (counts, bounding box, units guess, normals, colours,\n\
texture), then repaired as every processing command repairs it, and what repair\n\
changed is listed. A file that cannot be read exits with 1 and says where it broke."
)]
pub struct InfoArgs {
    /// The scan: .ply, .obj, .stl, .xyz or .pts.
    pub scan: PathBuf,
    /// Print one JSON object on stdout instead of text.
    #[arg(long)]
    pub json: bool,
    /// Also merge vertices closer than this (file units) when repairing.
    #[arg(long, value_name = "DISTANCE")]
    pub merge_tolerance_mm: Option<f64>,
    /// Keep only the largest connected component when repairing.
    #[arg(long)]
    pub keep_largest_component: bool,
}

/// Everything `sherd info` reports, in the JSON form scripts read.
#[derive(Serialize)]
struct Info {
    file: String,
    format: String,
    vertex_count: usize,
    face_count: usize,
    point_cloud: bool,
    bounding_box: Option<BoundingBox>,
    units_guess: Option<UnitsGuess>,
    has_normals: bool,
    has_colours: bool,
    has_quality: bool,
    has_texture_coordinates: bool,
    /// `[width, height]` of the loaded texture image.
    texture_size: Option<[u32; 2]>,
    /// Closed and 2-manifold after repair; `null` for a point cloud.
    watertight: Option<bool>,
    read: ReadReport,
    /// What repair (as every processing command applies it) changed and found.
    repair: RepairReport,
}

#[derive(Serialize)]
struct BoundingBox {
    min: [f64; 3],
    max: [f64; 3],
    size: [f64; 3],
}

pub fn run(arguments: &InfoArgs) -> Result<()> {
    if let Some(tolerance) = arguments.merge_tolerance_mm {
        if !(tolerance.is_finite() && tolerance >= 0.0) {
            return Err(sherd::Error::InvalidArgument(format!("--merge-tolerance-mm must be a non-negative distance, not {tolerance}")));
        }
    }
    let (mut mesh, read) = read_mesh_with_report(&arguments.scan)?;
    let bounding_box = mesh.bounding_box().map(|(low, high)| BoundingBox {
        min: low.coords.into(),
        max: high.coords.into(),
        size: (high - low).into(),
    });
    let mut info = Info {
        file: arguments.scan.display().to_string(),
        format: read.format.clone(),
        vertex_count: mesh.vertex_count(),
        face_count: mesh.face_count(),
        point_cloud: mesh.is_point_cloud(),
        bounding_box,
        units_guess: guess_units(&mesh),
        has_normals: mesh.normals.is_some(),
        has_colours: mesh.colors.is_some(),
        has_quality: mesh.quality.is_some(),
        has_texture_coordinates: mesh.corner_uvs.is_some(),
        texture_size: mesh.texture.as_ref().map(|t| [t.width, t.height]),
        watertight: None,
        read,
        repair: RepairReport::default(),
    };
    // Described as read; repaired in place afterwards (no copy of a 500k-face scan).
    info.repair = repair(
        &mut mesh,
        &RepairOptions { merge_tolerance_mm: arguments.merge_tolerance_mm, keep_largest_component: arguments.keep_largest_component },
    );
    info.watertight = (!info.point_cloud).then_some(info.repair.watertight);
    if arguments.json {
        println!("{}", serde_json::to_string_pretty(&info).expect("the report is plain data"));
    } else {
        print!("{}", text(&info));
    }
    Ok(())
}

fn yes_no(value: bool) -> &'static str {
    if value { "yes" } else { "no" }
}

fn text(info: &Info) -> String {
    let mut out = format!("file:       {} ({})\n", info.file, info.format);
    out += &format!("vertices:   {}\n", info.vertex_count);
    out += &format!("faces:      {}{}\n", info.face_count, if info.point_cloud { " (point cloud)" } else { "" });
    if let Some(bounds) = &info.bounding_box {
        let triple = |v: [f64; 3]| format!("({:.3}, {:.3}, {:.3})", v[0], v[1], v[2]);
        out += &format!("bounds:     {} to {}\n", triple(bounds.min), triple(bounds.max));
        out += &format!("size:       {:.3} x {:.3} x {:.3}\n", bounds.size[0], bounds.size[1], bounds.size[2]);
    }
    match (info.read.declared_unit, &info.units_guess) {
        (Some(unit), _) => out += &format!("units:      {} (declared in the file)\n", unit.symbol()),
        (None, Some(units)) => out += &format!("units:      {} (guess; {})\n", units.unit.symbol(), units.reason),
        (None, None) => {}
    }
    out += &format!("normals:    {}\n", yes_no(info.has_normals));
    out += &format!("colours:    {}\n", yes_no(info.has_colours));
    out += &format!("quality:    {}\n", yes_no(info.has_quality));
    let texture = match info.texture_size {
        Some([w, h]) => format!("yes ({w} x {h})"),
        None if info.has_texture_coordinates => "coordinates only (image not loaded)".into(),
        None => "no".into(),
    };
    out += &format!("texture:    {texture}\n");
    let repair = &info.repair;
    if let Some(watertight) = info.watertight {
        out += &format!(
            "watertight: {} ({} boundary edges, {} non-manifold edges, {} non-manifold vertices, {} components)\n",
            yes_no(watertight),
            repair.boundary_edge_count,
            repair.non_manifold_edge_count,
            repair.non_manifold_vertex_count,
            repair.component_face_counts.len()
        );
    }
    let changes: Vec<String> = [
        (repair.duplicate_vertices_merged, "duplicate vertices merged"),
        (repair.close_vertices_merged, "close vertices merged"),
        (repair.degenerate_faces_removed, "degenerate faces removed"),
        (repair.duplicate_faces_removed, "duplicate faces removed"),
        (repair.components_removed, "small components removed"),
        (repair.unreferenced_vertices_removed, "unreferenced vertices removed"),
    ]
    .iter()
    .filter(|(count, _)| *count > 0)
    .map(|(count, what)| format!("{count} {what}"))
    .collect();
    if changes.is_empty() {
        out += "repair:     nothing to repair\n";
    } else {
        out += &format!(
            "repair:     {}; {} vertices, {} faces after\n",
            changes.join(", "),
            repair.vertices_after,
            repair.faces_after
        );
    }
    if info.read.polygons_triangulated > 0 {
        out += &format!("polygons:   {} triangulated\n", info.read.polygons_triangulated);
    }
    for warning in &info.read.warnings {
        out += &format!("warning:    {warning}\n");
    }
    out
}
