use std::time::Instant;
use sherd::orient::{orient_automatic, OrientOptions};
use sherd::refine::{refine, RefineOptions};
use sherd::synth::{synthetic_sherd, SherdOptions, SherdPart};
fn main() {
    let body = synthetic_sherd(3, &SherdOptions { target_faces: 20_000, ..SherdOptions::for_part(SherdPart::Body) });
    let n = 20;
    let (mut o_ms, mut r_ms) = (0.0, 0.0);
    let mut last = None;
    for _ in 0..n {
        let t = Instant::now();
        let orientation = orient_automatic(&body.mesh, &OrientOptions::default()).unwrap();
        o_ms += t.elapsed().as_secs_f64() * 1e3;
        let t = Instant::now();
        let r = refine(&body.mesh, &orientation.axis, &RefineOptions::default()).unwrap();
        r_ms += t.elapsed().as_secs_f64() * 1e3;
        last = Some((orientation, r));
    }
    let (o, r) = last.unwrap();
    println!("orient {:.1} ms refine {:.1} ms; orient timings {:?}", o_ms / n as f64, r_ms / n as f64, o.report.timings_ms);
    println!("angle to truth {:.4} deg, distance {:.4} mm", r.axis.line_angle_to_deg(&body.truth.axis), sherd::orient::mean_point_distance_mm(&body.mesh.positions, &r.axis, &body.truth.axis));
    println!("refine report iterations {} prepare {:.1} search {:.1} sections {} method {:?}", r.report.iterations, r.report.timings.prepare_ms, r.report.timings.search_ms, r.report.section_count, r.report.method);
}
