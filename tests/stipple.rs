//! Stipple on the real scan A011 (`../shared/data`): the dots' density follows the shading
//! the light style shows, so that its wheel rills stay readable. Skips with a message
//! where the data are absent.

mod support;

use sherd::draw::{DrawOptions, Drawing, Element, Style};

/// Every element of the drawing, groups opened.
fn elements(drawing: &Drawing) -> Vec<&Element> {
    fn walk<'a>(children: &'a [Element], out: &mut Vec<&'a Element>) {
        for child in children {
            match child {
                Element::Group(group) => walk(&group.children, out),
                other => out.push(other),
            }
        }
    }
    let mut out = Vec::new();
    for layer in &drawing.layers {
        walk(&layer.children, &mut out);
    }
    out
}

/// Pearson's correlation of two equally long series.
fn correlation(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len() as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let cov: f64 = a.iter().zip(b).map(|(x, y)| (x - ma) * (y - mb)).sum();
    let (va, vb): (f64, f64) = (a.iter().map(|x| (x - ma).powi(2)).sum(), b.iter().map(|y| (y - mb).powi(2)).sum());
    cov / (va * vb).sqrt()
}

#[test]
fn a011_stipple_density_follows_the_light_styles_shading() {
    let Some(path) = support::shared_data_file("a011_stipple_density_follows_the_light_styles_shading", "dacord/A011.ply") else {
        println!("SKIP: ../shared/data/dacord/A011.ply is absent");
        return;
    };
    let points = [[30.508, -66.920, 39.363], [18.614, -75.548, 43.705], [8.663, -86.138, 42.986]]
        .map(|[x, y, z]| sherd::mesh::Point::new(x, y, z));
    let options = sherd::pipeline::PipelineOptions { manual_points: Some(points), ..Default::default() };
    let analysis = sherd::pipeline::analyse_file(&path, &options).unwrap();
    let draw = |style: &str| {
        let options = DrawOptions { style: Style::parse(style).unwrap(), dpi: 300.0, ..Default::default() };
        Drawing::build(&analysis.mesh, analysis.axis(), &options).unwrap()
    };
    let (shaded, stippled) = (draw("light,occlusion"), draw("stipple"));
    let dots: Vec<[f64; 2]> = elements(&stippled)
        .into_iter()
        .filter_map(|e| if let Element::Dots(d) = e { Some(d.centers.clone()) } else { None })
        .flatten()
        .collect();
    // Blocks of 1.5 mm over each shaded view: the mean darkness the light style shows
    // there, and the dots the stipple puts there (the two drawings share their layout).
    const BLOCK_MM: f64 = 1.5;
    let mut views = Vec::new();
    for element in elements(&shaded) {
        let Element::Image(image) = element else { continue };
        let (mut darkness, mut density) = (Vec::new(), Vec::new());
        let (w, h) = (image.width_px as usize, image.height_px as usize);
        let pixel_mm = image.width_mm / w as f64;
        let block_px = (BLOCK_MM / pixel_mm).round() as usize;
        for by in (0..h).step_by(block_px) {
            for bx in (0..w).step_by(block_px) {
                let (mut sum, mut covered, mut total) = (0.0, 0usize, 0usize);
                for y in by..(by + block_px).min(h) {
                    for x in bx..(bx + block_px).min(w) {
                        total += 1;
                        let p = &image.rgba[4 * (y * w + x)..][..4];
                        if p[3] == 255 {
                            covered += 1;
                            sum += 1.0 - (0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64) / 255.0;
                        }
                    }
                }
                // Whole blocks inside the sherd only: the outline is no tone.
                if total != block_px * block_px || covered != total {
                    continue;
                }
                let (x0, y0) = (image.x_mm + bx as f64 * pixel_mm, image.y_mm + by as f64 * pixel_mm);
                let (x1, y1) = (x0 + block_px as f64 * pixel_mm, y0 + block_px as f64 * pixel_mm);
                let inside = dots.iter().filter(|d| d[0] >= x0 && d[0] < x1 && d[1] >= y0 && d[1] < y1).count();
                darkness.push(sum / covered as f64);
                density.push(inside as f64);
            }
        }
        views.push((darkness, density));
    }
    // Within the view whose shading varies most (the exterior, with the rills): the two
    // views are shaded apart, and comparing across them would hide a flat stipple.
    let spread = |v: &[f64]| {
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / v.len() as f64
    };
    let (darkness, density) = views
        .into_iter()
        .filter(|(darkness, _)| darkness.len() > 100)
        .max_by(|a, b| spread(&a.0).total_cmp(&spread(&b.0)))
        .expect("a shaded view");
    let r = correlation(&darkness, &density);
    // The darkest and the lightest fifth of the blocks, by the light style's tone.
    let mut order: Vec<usize> = (0..darkness.len()).collect();
    order.sort_by(|&a, &b| darkness[a].total_cmp(&darkness[b]));
    let fifth = order.len() / 5;
    let mean = |indices: &[usize]| indices.iter().map(|&i| density[i]).sum::<f64>() / indices.len() as f64;
    let (light, dark) = (mean(&order[..fifth]), mean(&order[order.len() - fifth..]));
    println!("A011, exterior view: {} blocks, correlation {r:.2}, dots per block {light:.1} (lightest fifth) to {dark:.1} (darkest)", darkness.len());
    // Uniform dots give a correlation near 0 and a ratio near 1.
    assert!(r > 0.5, "the dots' density follows the shading with a correlation of {r:.2} only");
    assert!(dark > 2.5 * light, "the darkest fifth has {dark:.1} dots per block, the lightest {light:.1}");
}
