//! SVG writer: one Inkscape layer per drawing layer, paths and text as editable vector
//! elements, raster views as embedded PNG images. Units are millimetres.

use std::fmt::Write as _;

use crate::draw::model::{Anchor, Drawing, Element, Group, Image, Path, Rgb, Segment, Stroke};
use crate::Result;

/// The drawing as an SVG document.
pub fn to_svg(drawing: &Drawing) -> Result<Vec<u8>> {
    let mut out = String::with_capacity(1 << 16);
    let _ = write!(
        out,
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n\
         <svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" \
         xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\" \
         width=\"{w:.3}mm\" height=\"{h:.3}mm\" viewBox=\"0 0 {w:.3} {h:.3}\">\n\
         <rect x=\"0\" y=\"0\" width=\"{w:.3}\" height=\"{h:.3}\" fill=\"#ffffff\"/>\n",
        w = drawing.width_mm,
        h = drawing.height_mm
    );
    for layer in &drawing.layers {
        let _ = writeln!(
            out,
            "<g id=\"{id}\" inkscape:groupmode=\"layer\" inkscape:label=\"{id}\">",
            id = escape(&layer.id)
        );
        write_children(&mut out, layer)?;
        out.push_str("</g>\n");
    }
    out.push_str("</svg>\n");
    Ok(out.into_bytes())
}

fn write_children(out: &mut String, group: &Group) -> Result<()> {
    for element in &group.children {
        match element {
            Element::Path(path) => write_path(out, path),
            Element::Dots(dots) => {
                let _ = writeln!(out, "<g fill=\"{}\">", hex(dots.color));
                for c in &dots.centers {
                    let _ = writeln!(out, "<circle cx=\"{:.3}\" cy=\"{:.3}\" r=\"{:.3}\"/>", c[0], c[1], dots.radius_mm);
                }
                out.push_str("</g>\n");
            }
            Element::Text(text) => {
                let anchor = match text.anchor {
                    Anchor::Start => "start",
                    Anchor::Middle => "middle",
                    Anchor::End => "end",
                };
                let _ = writeln!(
                    out,
                    "<text x=\"{:.3}\" y=\"{:.3}\" font-family=\"Helvetica, Arial, sans-serif\" font-size=\"{:.3}\" \
                     text-anchor=\"{anchor}\" fill=\"{}\">{}</text>",
                    text.position[0],
                    text.position[1],
                    text.size_mm,
                    hex(text.color),
                    escape(&text.content)
                );
            }
            Element::Image(image) => write_image(out, image)?,
            Element::Group(inner) => {
                // Labelled like the layers: Inkscape's Objects panel shows the label.
                let _ = writeln!(out, "<g id=\"{id}\" inkscape:label=\"{id}\">", id = escape(&inner.id));
                write_children(out, inner)?;
                out.push_str("</g>\n");
            }
        }
    }
    Ok(())
}

fn write_path(out: &mut String, path: &Path) {
    out.push_str("<path d=\"");
    for segment in &path.segments {
        match segment {
            Segment::MoveTo(p) => {
                let _ = write!(out, "M{:.3} {:.3}", p[0], p[1]);
            }
            Segment::LineTo(p) => {
                let _ = write!(out, "L{:.3} {:.3}", p[0], p[1]);
            }
            Segment::Close => out.push('Z'),
        }
    }
    out.push('"');
    match path.fill {
        Some(color) => {
            let _ = write!(out, " fill=\"{}\" fill-rule=\"evenodd\"", hex(color));
        }
        None => out.push_str(" fill=\"none\""),
    }
    if let Some(Stroke { color, width_mm, dash_mm }) = &path.stroke {
        let _ = write!(out, " stroke=\"{}\" stroke-width=\"{width_mm:.3}\" stroke-linejoin=\"round\" stroke-linecap=\"round\"", hex(*color));
        if !dash_mm.is_empty() {
            let dashes: Vec<String> = dash_mm.iter().map(|d| format!("{d:.3}")).collect();
            let _ = write!(out, " stroke-dasharray=\"{}\"", dashes.join(","));
        }
    }
    out.push_str("/>\n");
}

fn write_image(out: &mut String, image: &Image) -> Result<()> {
    let png = crate::draw::png::encode_rgba_png(image.width_px, image.height_px, &image.rgba, None)?;
    let _ = write!(
        out,
        "<image x=\"{:.3}\" y=\"{:.3}\" width=\"{:.3}\" height=\"{:.3}\" preserveAspectRatio=\"none\" \
         xlink:href=\"data:image/png;base64,",
        image.x_mm, image.y_mm, image.width_mm, image.height_mm
    );
    base64_into(&png, out);
    out.push_str("\"/>\n");
    Ok(())
}

fn hex(c: Rgb) -> String {
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

/// XML text and attribute escaping.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// Standard base64 (RFC 4648) with padding.
fn base64_into(bytes: &[u8], out: &mut String) {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for chunk in bytes.chunks(3) {
        let b = [chunk[0], *chunk.get(1).unwrap_or(&0), *chunk.get(2).unwrap_or(&0)];
        let n = (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32;
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(ALPHABET[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc_4648_vectors() {
        for (input, expected) in [("", ""), ("f", "Zg=="), ("fo", "Zm8="), ("foo", "Zm9v"), ("foobar", "Zm9vYmFy")] {
            let mut out = String::new();
            base64_into(input.as_bytes(), &mut out);
            assert_eq!(out, expected);
        }
        assert_eq!(escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
    }
}
