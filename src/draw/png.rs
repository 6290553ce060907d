//! PNG writer: the drawing rasterized with tiny-skia at a chosen resolution, text in the
//! built-in stroke font, the resolution recorded in the file (pHYs) so that printing at
//! 100% gives the publication scale.

use tiny_skia::{
    FillRule, FilterQuality, LineCap, LineJoin, Paint, PathBuilder, Pixmap, PixmapMut, PixmapPaint, Transform,
};

use rayon::prelude::*;

use crate::draw::font;
use crate::draw::model::{Anchor, Drawing, Element, Group, Path, Rgb, Segment, Stroke};
use crate::{Error, Result};

/// Pixel size of `drawing` at `dpi`: its paper size times the resolution.
pub fn pixel_size(drawing: &Drawing, dpi: f64) -> (u32, u32) {
    let per_mm = dpi / 25.4;
    ((drawing.width_mm * per_mm).round().max(1.0) as u32, (drawing.height_mm * per_mm).round().max(1.0) as u32)
}

/// The drawing rendered at `dpi` on a white background, as PNG bytes.
pub fn to_png(drawing: &Drawing, dpi: f64) -> Result<Vec<u8>> {
    encode_pixmap(&render(drawing, dpi)?, Some(dpi))
}

/// A rendered pixmap as PNG bytes, recording `dpi` when given. A page on its white background
/// is opaque: it is written as RGB, a quarter less to compress than RGBA and no demultiplying.
pub fn encode_pixmap(pixmap: &Pixmap, dpi: Option<f64>) -> Result<Vec<u8>> {
    let data = pixmap.data();
    if data.chunks_exact(4).all(|px| px[3] == 255) {
        let rgb: Vec<u8> = data.chunks_exact(4).flat_map(|px| [px[0], px[1], px[2]]).collect();
        encode_png(pixmap.width(), pixmap.height(), &rgb, png::ColorType::Rgb, dpi)
    } else {
        encode_rgba_png(pixmap.width(), pixmap.height(), &demultiply(data), dpi)
    }
}

/// The drawing rendered at `dpi` (premultiplied RGBA pixmap).
///
/// The page is cut into horizontal bands rendered in parallel, each straight into its rows
/// of the one pixmap; a band is given only the subpaths and dots whose bounds reach it, so
/// the thousands of short crease strokes of a linear drawing are rasterized once, not once
/// per band.
pub fn render(drawing: &Drawing, dpi: f64) -> Result<Pixmap> {
    if !(dpi.is_finite() && dpi > 0.0) {
        return Err(Error::InvalidArgument(format!("resolution must be a positive number of dpi, got {dpi}")));
    }
    let (width, height) = pixel_size(drawing, dpi);
    if width as u64 * height as u64 > 400_000_000 {
        return Err(Error::InvalidArgument(format!(
            "a {width} x {height} pixel image is too large; lower the resolution ({dpi} dpi)"
        )));
    }
    // A few bands per thread balance the uneven work (the views are not spread evenly over
    // the page); each band at least 64 rows so the per-band culling stays cheap.
    let band_count = (rayon::current_num_threads() * 4).min(height as usize / 64).max(1);
    render_in_bands(drawing, dpi, band_count)
}

/// [`render`] with the page cut into `band_count` bands (at least one).
fn render_in_bands(drawing: &Drawing, dpi: f64, band_count: usize) -> Result<Pixmap> {
    let (width, height) = pixel_size(drawing, dpi);
    let mut pixmap = Pixmap::new(width, height).ok_or_else(|| Error::InvalidArgument("empty image".into()))?;
    pixmap.fill(tiny_skia::Color::WHITE);
    let pixels_per_mm = (dpi / 25.4) as f32;
    let band_count = band_count.clamp(1, height as usize);
    let band_rows = (height as usize).div_ceil(band_count);
    let row_bytes = width as usize * 4;
    pixmap.data_mut().par_chunks_mut(band_rows * row_bytes).enumerate().try_for_each(|(band, bytes)| {
        let rows = (bytes.len() / row_bytes) as u32;
        let mut target = PixmapMut::from_bytes(bytes, width, rows)
            .ok_or_else(|| Error::InvalidArgument("empty image band".into()))?;
        let top_px = (band * band_rows) as f32;
        let band = Band { top_mm: top_px / pixels_per_mm, bottom_mm: (top_px + rows as f32) / pixels_per_mm };
        let transform = Transform::from_scale(pixels_per_mm, pixels_per_mm).post_translate(0.0, -top_px);
        for layer in &drawing.layers {
            draw_group(&mut target, layer, transform, band)?;
        }
        Ok(())
    })?;
    Ok(pixmap)
}

/// The page rows of one band, in millimetres from the top.
#[derive(Clone, Copy)]
struct Band {
    top_mm: f32,
    bottom_mm: f32,
}

impl Band {
    /// True when something spanning `low..=high` (mm), widened by `margin_mm`, reaches
    /// the band.
    fn reaches(&self, low: f32, high: f32, margin_mm: f32) -> bool {
        high + margin_mm >= self.top_mm && low - margin_mm <= self.bottom_mm
    }
}

/// Half a pixel of anti-aliasing at any resolution above 50 dpi, in millimetres.
const ANTIALIAS_MARGIN_MM: f32 = 0.5;

fn draw_group(pixmap: &mut PixmapMut, group: &Group, transform: Transform, band: Band) -> Result<()> {
    for element in &group.children {
        match element {
            Element::Path(path) => draw_path(pixmap, path, transform, band),
            Element::Dots(dots) => {
                let radius = dots.radius_mm as f32;
                let mut builder = PathBuilder::new();
                for c in &dots.centers {
                    let y = c[1] as f32;
                    if band.reaches(y, y, radius + ANTIALIAS_MARGIN_MM) {
                        builder.push_circle(c[0] as f32, y, radius);
                    }
                }
                if let Some(path) = builder.finish() {
                    pixmap.fill_path(&path, &paint(dots.color), FillRule::Winding, transform, None);
                }
            }
            Element::Text(text) => {
                let width = font::text_width_mm(&text.content, text.size_mm);
                let x = match text.anchor {
                    Anchor::Start => text.position[0],
                    Anchor::Middle => text.position[0] - width / 2.0,
                    Anchor::End => text.position[0] - width,
                };
                let stroke = Stroke { color: text.color, width_mm: text.size_mm * 0.08, dash_mm: vec![] };
                for line in font::text_strokes(&text.content, text.size_mm, [x, text.position[1]]) {
                    draw_path(pixmap, &Path::polyline(&line, false, None, Some(stroke.clone())), transform, band);
                }
            }
            Element::Image(image) => {
                let (top, bottom) = (image.y_mm as f32, (image.y_mm + image.height_mm) as f32);
                if !band.reaches(top.min(bottom), top.max(bottom), ANTIALIAS_MARGIN_MM) {
                    continue;
                }
                let mut premultiplied = image.rgba.clone();
                for px in premultiplied.chunks_exact_mut(4) {
                    let a = px[3] as u16;
                    for c in &mut px[..3] {
                        *c = ((*c as u16 * a + 127) / 255) as u8;
                    }
                }
                let size = tiny_skia::IntSize::from_wh(image.width_px, image.height_px)
                    .ok_or_else(|| Error::InvalidArgument("empty raster image".into()))?;
                let source = Pixmap::from_vec(premultiplied, size)
                    .ok_or_else(|| Error::InvalidArgument("raster image size does not match its data".into()))?;
                let placement = transform.pre_translate(image.x_mm as f32, image.y_mm as f32).pre_scale(
                    (image.width_mm / image.width_px as f64) as f32,
                    (image.height_mm / image.height_px as f64) as f32,
                );
                let paint = PixmapPaint { quality: FilterQuality::Bilinear, ..PixmapPaint::default() };
                pixmap.draw_pixmap(0, 0, source.as_ref(), &paint, placement, None);
            }
            Element::Group(inner) => draw_group(pixmap, inner, transform, band)?,
        }
    }
    Ok(())
}

/// Draws the subpaths of `path` that reach `band`. A subpath wholly above or below the
/// band neither covers its pixels nor changes their winding, and dashes restart with each
/// subpath, so leaving it out changes nothing in the band.
fn draw_path(pixmap: &mut PixmapMut, path: &Path, transform: Transform, band: Band) {
    let margin_mm = path.stroke.as_ref().map_or(0.0, |s| s.width_mm as f32) + ANTIALIAS_MARGIN_MM;
    let mut builder = PathBuilder::new();
    let mut subpath: Vec<Segment> = Vec::new();
    let flush = |subpath: &mut Vec<Segment>, builder: &mut PathBuilder| {
        let (mut low, mut high) = (f32::INFINITY, f32::NEG_INFINITY);
        for segment in subpath.iter() {
            if let Segment::MoveTo(p) | Segment::LineTo(p) = segment {
                (low, high) = (low.min(p[1] as f32), high.max(p[1] as f32));
            }
        }
        if band.reaches(low, high, margin_mm) {
            for segment in subpath.iter() {
                match *segment {
                    Segment::MoveTo(p) => builder.move_to(p[0] as f32, p[1] as f32),
                    Segment::LineTo(p) => builder.line_to(p[0] as f32, p[1] as f32),
                    Segment::Close => builder.close(),
                }
            }
        }
        subpath.clear();
    };
    for segment in &path.segments {
        if matches!(segment, Segment::MoveTo(_)) && !subpath.is_empty() {
            flush(&mut subpath, &mut builder);
        }
        subpath.push(*segment);
    }
    flush(&mut subpath, &mut builder);
    let Some(skia_path) = builder.finish() else { return };
    if let Some(color) = path.fill {
        pixmap.fill_path(&skia_path, &paint(color), FillRule::EvenOdd, transform, None);
    }
    if let Some(stroke) = &path.stroke {
        let mut style = tiny_skia::Stroke {
            width: stroke.width_mm as f32,
            line_cap: LineCap::Round,
            line_join: LineJoin::Round,
            ..Default::default()
        };
        if stroke.dash_mm.len() >= 2 {
            style.dash = tiny_skia::StrokeDash::new(stroke.dash_mm.iter().map(|&d| d as f32).collect(), 0.0);
        }
        pixmap.stroke_path(&skia_path, &paint(stroke.color), &style, transform, None);
    }
}

fn paint(color: Rgb) -> Paint<'static> {
    let mut paint = Paint::default();
    paint.set_color_rgba8(color[0], color[1], color[2], 255);
    paint.anti_alias = true;
    paint
}

fn demultiply(premultiplied: &[u8]) -> Vec<u8> {
    let mut out = premultiplied.to_vec();
    for px in out.chunks_exact_mut(4) {
        let a = px[3] as u32;
        if a > 0 && a < 255 {
            for c in &mut px[..3] {
                *c = ((*c as u32 * 255 + a / 2) / a).min(255) as u8;
            }
        }
    }
    out
}

/// Encodes straight-alpha RGBA as PNG, recording `dpi` (pHYs) when given.
pub fn encode_rgba_png(width: u32, height: u32, rgba: &[u8], dpi: Option<f64>) -> Result<Vec<u8>> {
    encode_png(width, height, rgba, png::ColorType::Rgba, dpi)
}

fn encode_png(width: u32, height: u32, pixels: &[u8], color: png::ColorType, dpi: Option<f64>) -> Result<Vec<u8>> {
    let mut bytes = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut bytes, width, height);
        encoder.set_color(color);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::Fast);
        if let Some(dpi) = dpi {
            let per_metre = (dpi / 0.0254).round() as u32;
            encoder.set_pixel_dims(Some(png::PixelDimensions { xppu: per_metre, yppu: per_metre, unit: png::Unit::Meter }));
        }
        let mut writer = encoder.write_header().map_err(|e| Error::InvalidArgument(format!("PNG encoding: {e}")))?;
        writer.write_image_data(pixels).map_err(|e| Error::InvalidArgument(format!("PNG encoding: {e}")))?;
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::draw::model::{Dots, Text};

    fn colour_type_and_pixels(bytes: &[u8]) -> (png::ColorType, Vec<u8>) {
        let mut reader = png::Decoder::new(std::io::Cursor::new(bytes)).read_info().unwrap();
        let mut pixels = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut pixels).unwrap();
        pixels.truncate(info.buffer_size());
        (info.color_type, pixels)
    }

    #[test]
    fn a_page_rendered_in_bands_is_the_page_rendered_in_one_pass() {
        // Strokes, dashes, fills, dots, text and an image, many of them across the
        // boundaries of 7 bands of a 40 x 30 mm page at 300 dpi (71 rows per band).
        let mut children = Vec::new();
        for k in 0..12 {
            let y = 1.0 + 2.4 * k as f64;
            let stroke = Stroke { color: [0, 0, 0], width_mm: 0.12 + 0.1 * (k % 3) as f64, dash_mm: if k % 4 == 0 { vec![1.5, 1.0] } else { vec![] } };
            children.push(Element::Path(Path::polyline(&[[2.0, y], [20.0, y + 5.0], [38.0, y - 1.0]], false, None, Some(stroke))));
        }
        children.push(Element::Path(Path::polyline(&[[5.0, 3.0], [15.0, 27.0], [25.0, 4.0]], true, Some([200, 40, 40]), None)));
        children.push(Element::Dots(Dots {
            centers: (0..300).map(|i| [1.0 + (i % 30) as f64 * 1.3, 1.0 + (i / 30) as f64 * 2.9]).collect(),
            radius_mm: 0.2,
            color: [0, 0, 0],
        }));
        children.push(Element::Text(Text { position: [20.0, 15.3], content: "0 10 cm".into(), size_mm: 4.0, anchor: Anchor::Middle, color: [0, 0, 0] }));
        children.push(Element::Image(crate::draw::model::Image {
            x_mm: 24.0,
            y_mm: 10.0,
            width_mm: 12.0,
            height_mm: 15.0,
            width_px: 4,
            height_px: 5,
            rgba: (0..20).flat_map(|i| [(i * 12) as u8, 90, 200, 255]).collect(),
        }));
        let drawing = Drawing { width_mm: 40.0, height_mm: 30.0, dpi: 300.0, layers: vec![Group { id: "test".into(), children }] };
        let whole = render_in_bands(&drawing, 300.0, 1).unwrap();
        let banded = render_in_bands(&drawing, 300.0, 7).unwrap();
        assert_eq!((whole.width(), whole.height()), (banded.width(), banded.height()));
        let differences: Vec<u8> = whole.data().iter().zip(banded.data()).map(|(a, b)| a.abs_diff(*b)).collect();
        let differing = differences.iter().filter(|&&d| d > 0).count();
        // Transformed coordinates round differently in each band: a few edge pixels
        // differ by a few levels, nothing is missing or doubled.
        assert!(differences.iter().all(|&d| d <= 32), "largest difference {:?}", differences.iter().max());
        assert!(differing * 1000 < differences.len(), "{differing} of {} bytes differ", differences.len());
        assert!(whole.data().chunks_exact(4).filter(|px| px[0] < 128).count() > 5000, "the page has ink");
    }

    #[test]
    fn an_opaque_page_is_written_as_rgb_and_a_transparent_one_keeps_its_alpha() {
        let mut pixmap = Pixmap::new(2, 1).unwrap();
        pixmap.fill(tiny_skia::Color::from_rgba8(10, 20, 30, 255));
        let (colour, pixels) = colour_type_and_pixels(&encode_pixmap(&pixmap, Some(300.0)).unwrap());
        assert_eq!((colour, pixels), (png::ColorType::Rgb, vec![10, 20, 30, 10, 20, 30]));
        // Half-transparent grey comes back demultiplied (within the rounding of 8 bits).
        pixmap.fill(tiny_skia::Color::from_rgba8(127, 127, 127, 128));
        let (colour, pixels) = colour_type_and_pixels(&encode_pixmap(&pixmap, None).unwrap());
        assert_eq!(colour, png::ColorType::Rgba);
        assert_eq!(pixels[3], 128);
        assert!(pixels[..3].iter().all(|&c| c.abs_diff(127) <= 1), "{pixels:?}");
    }
}
