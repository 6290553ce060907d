//! The page-description writers: EPS (PostScript level 3, the paper's export format) and
//! PDF (1.4, written by hand: Helvetica from the base 14 fonts, Flate-compressed content
//! and images with a soft mask for transparency). Both share the path and text
//! operators, which differ only in spelling.

use std::fmt::Write as _;
use std::io::Write as _;

use flate2::write::ZlibEncoder;
use flate2::Compression;

use crate::draw::model::{helvetica_width_mm, latin1_bytes, Anchor, Drawing, Element, Group, Image, Path, Rgb, Segment};
use crate::{Error, Result};

/// PostScript points per millimetre.
const POINTS_PER_MM: f64 = 72.0 / 25.4;

fn deflate(bytes: &[u8]) -> Result<Vec<u8>> {
    let mut encoder = ZlibEncoder::new(Vec::with_capacity(bytes.len() / 4), Compression::fast());
    encoder.write_all(bytes).and_then(|_| encoder.finish()).map_err(|e| Error::InvalidArgument(format!("compression: {e}")))
}

/// ASCII85 encoding with the `~>` end marker, lines of at most 75 characters.
fn ascii85(bytes: &[u8]) -> String {
    let mut out = String::with_capacity(bytes.len() * 5 / 4 + bytes.len() / 60 + 4);
    let mut column = 0;
    let mut push = |out: &mut String, c: char| {
        out.push(c);
        column += 1;
        if column == 75 {
            out.push('\n');
            column = 0;
        }
    };
    for chunk in bytes.chunks(4) {
        let mut word = [0u8; 4];
        word[..chunk.len()].copy_from_slice(chunk);
        let n = u32::from_be_bytes(word);
        if n == 0 && chunk.len() == 4 {
            push(&mut out, 'z');
            continue;
        }
        let mut digits = [0u8; 5];
        let mut v = n;
        for d in digits.iter_mut().rev() {
            *d = (v % 85) as u8 + b'!';
            v /= 85;
        }
        for &d in &digits[..chunk.len() + 1] {
            push(&mut out, d as char);
        }
    }
    out.push_str("~>\n");
    out
}

/// A PostScript or PDF string literal of Latin-1 bytes.
fn string_literal(text: &str) -> String {
    let mut out = String::from("(");
    for b in latin1_bytes(text) {
        match b {
            b'(' | b')' | b'\\' => {
                out.push('\\');
                out.push(b as char);
            }
            32..=126 => out.push(b as char),
            _ => {
                let _ = write!(out, "\\{b:03o}");
            }
        }
    }
    out.push(')');
    out
}

fn rgb(c: Rgb) -> String {
    format!("{:.3} {:.3} {:.3}", c[0] as f64 / 255.0, c[1] as f64 / 255.0, c[2] as f64 / 255.0)
}

/// Flattens the images to RGB with white where transparent, and an alpha channel.
fn split_alpha(image: &Image) -> (Vec<u8>, Vec<u8>) {
    let mut rgb = Vec::with_capacity(image.rgba.len() / 4 * 3);
    let mut alpha = Vec::with_capacity(image.rgba.len() / 4);
    for px in image.rgba.chunks_exact(4) {
        let a = px[3] as u16;
        for &c in &px[..3] {
            rgb.push(((c as u16 * a + 255 * (255 - a)) / 255) as u8);
        }
        alpha.push(px[3]);
    }
    (rgb, alpha)
}

// ---------------------------------------------------------------- EPS

/// The drawing as Encapsulated PostScript (level 3: Flate-compressed, masked images).
pub fn to_eps(drawing: &Drawing) -> Result<Vec<u8>> {
    let (w, h) = (drawing.width_mm * POINTS_PER_MM, drawing.height_mm * POINTS_PER_MM);
    let mut out = String::with_capacity(1 << 16);
    let _ = write!(
        out,
        "%!PS-Adobe-3.0 EPSF-3.0\n%%BoundingBox: 0 0 {} {}\n%%HiResBoundingBox: 0 0 {w:.3} {h:.3}\n\
         %%Creator: sherd\n%%LanguageLevel: 3\n%%DocumentNeededResources: font Helvetica\n%%Pages: 1\n%%EndComments\n\
         %%BeginProlog\n\
         /Helvetica findfont dup length dict begin {{1 index /FID ne {{def}} {{pop pop}} ifelse}} forall \
         /Encoding ISOLatin1Encoding def currentdict end /Helvetica-Latin1 exch definefont pop\n\
         /D {{ moveto 0 0 rlineto }} bind def\n\
         %%EndProlog\n%%Page: 1 1\nsave\n\
         1 1 1 setrgbcolor 0 0 {w:.3} {h:.3} rectfill\n\
         0 {h:.4} translate {s:.6} {ns:.6} scale\n1 setlinecap 1 setlinejoin\n",
        w.ceil() as i64,
        h.ceil() as i64,
        s = POINTS_PER_MM,
        ns = -POINTS_PER_MM,
    );
    for layer in &drawing.layers {
        let _ = writeln!(out, "%% layer {}", layer.id.replace(['\n', '\r'], " "));
        eps_group(&mut out, layer)?;
    }
    out.push_str("restore\nshowpage\n%%Trailer\n%%EOF\n");
    Ok(out.into_bytes())
}

fn eps_group(out: &mut String, group: &Group) -> Result<()> {
    for element in &group.children {
        match element {
            Element::Path(path) => eps_path(out, path),
            Element::Dots(dots) => {
                // Zero-length segments with round caps are dots: compact and exact.
                let _ = writeln!(out, "gsave {} setrgbcolor {:.4} setlinewidth newpath", rgb(dots.color), 2.0 * dots.radius_mm);
                for (i, c) in dots.centers.iter().enumerate() {
                    let _ = write!(out, "{:.2} {:.2} D{}", c[0], c[1], if i % 8 == 7 { '\n' } else { ' ' });
                }
                out.push_str("\nstroke grestore\n");
            }
            Element::Text(text) => {
                let literal = string_literal(&text.content);
                let shift = match text.anchor {
                    Anchor::Start => "",
                    Anchor::Middle => "dup stringwidth pop -2 div 0 rmoveto ",
                    Anchor::End => "dup stringwidth pop neg 0 rmoveto ",
                };
                let _ = writeln!(
                    out,
                    "gsave {} setrgbcolor /Helvetica-Latin1 findfont {:.3} scalefont setfont {:.3} {:.3} translate 1 -1 scale \
                     0 0 moveto {literal} {shift}show grestore",
                    rgb(text.color),
                    text.size_mm,
                    text.position[0],
                    text.position[1]
                );
            }
            Element::Image(image) => {
                let (rgb_bytes, alpha) = split_alpha(image);
                // Transparent pixels become pure white and white is the masking key;
                // real white pixels are nudged to 254 so that they stay visible.
                let mut keyed = rgb_bytes;
                for (px, &a) in keyed.chunks_exact_mut(3).zip(&alpha) {
                    if a < 128 {
                        px.copy_from_slice(&[255, 255, 255]);
                    } else if px == [255, 255, 255] {
                        px[2] = 254;
                    }
                }
                let data = ascii85(&deflate(&keyed)?);
                let _ = write!(
                    out,
                    "gsave {x:.4} {y:.4} translate {wm:.4} {hm:.4} scale /DeviceRGB setcolorspace\n\
                     << /ImageType 4 /Width {w} /Height {h} /BitsPerComponent 8 /Decode [0 1 0 1 0 1] \
                     /ImageMatrix [{w} 0 0 {h} 0 0] /MaskColor [255 255 255 255 255 255] \
                     /DataSource currentfile /ASCII85Decode filter /FlateDecode filter >> image\n{data}grestore\n",
                    x = image.x_mm,
                    y = image.y_mm,
                    wm = image.width_mm,
                    hm = image.height_mm,
                    w = image.width_px,
                    h = image.height_px,
                );
            }
            Element::Group(inner) => {
                let _ = writeln!(out, "%% group {}", inner.id.replace(['\n', '\r'], " "));
                eps_group(out, inner)?;
            }
        }
    }
    Ok(())
}

fn eps_path(out: &mut String, path: &Path) {
    let mut outline = String::from("newpath ");
    for (i, segment) in path.segments.iter().enumerate() {
        match segment {
            Segment::MoveTo(p) => {
                let _ = write!(outline, "{:.3} {:.3} moveto ", p[0], p[1]);
            }
            Segment::LineTo(p) => {
                let _ = write!(outline, "{:.3} {:.3} lineto ", p[0], p[1]);
            }
            Segment::Close => outline.push_str("closepath "),
        }
        if i % 6 == 5 {
            outline.push('\n');
        }
    }
    if let Some(color) = path.fill {
        let _ = writeln!(out, "gsave {} setrgbcolor {outline}eofill grestore", rgb(color));
    }
    if let Some(stroke) = &path.stroke {
        let dash: Vec<String> = stroke.dash_mm.iter().map(|d| format!("{d:.3}")).collect();
        let _ = writeln!(
            out,
            "gsave {} setrgbcolor {:.4} setlinewidth [{}] 0 setdash {outline}stroke grestore",
            rgb(stroke.color),
            stroke.width_mm,
            dash.join(" ")
        );
    }
}

// ---------------------------------------------------------------- PDF

/// The drawing as a one-page PDF.
pub fn to_pdf(drawing: &Drawing) -> Result<Vec<u8>> {
    let (w, h) = (drawing.width_mm * POINTS_PER_MM, drawing.height_mm * POINTS_PER_MM);
    // Objects: 1 catalog, 2 pages, 3 page, 4 content, 5 font, then two per image.
    let mut images = Vec::new();
    let mut content = String::with_capacity(1 << 16);
    let _ = write!(content, "1 1 1 rg 0 0 {w:.3} {h:.3} re f\n{s:.6} 0 0 {ns:.6} 0 {h:.4} cm 1 J 1 j\n", s = POINTS_PER_MM, ns = -POINTS_PER_MM);
    for layer in &drawing.layers {
        let _ = writeln!(content, "% layer {}", layer.id.replace(['\n', '\r'], " "));
        pdf_group(&mut content, layer, &mut images);
    }
    let mut objects: Vec<Vec<u8>> = Vec::new();
    objects.push(b"<< /Type /Catalog /Pages 2 0 R >>".to_vec());
    objects.push(b"<< /Type /Pages /Kids [3 0 R] /Count 1 >>".to_vec());
    let mut xobjects = String::new();
    for i in 0..images.len() {
        let _ = write!(xobjects, "/Im{i} {} 0 R ", 6 + 2 * i);
    }
    objects.push(
        format!(
            "<< /Type /Page /Parent 2 0 R /MediaBox [0 0 {w:.3} {h:.3}] /Contents 4 0 R \
             /Resources << /Font << /F1 5 0 R >> /XObject << {xobjects}>> >> >>"
        )
        .into_bytes(),
    );
    objects.push(stream_object("", &deflate(content.as_bytes())?));
    objects.push(b"<< /Type /Font /Subtype /Type1 /BaseFont /Helvetica /Encoding /WinAnsiEncoding >>".to_vec());
    for (i, image) in images.iter().enumerate() {
        let (rgb_bytes, alpha) = split_alpha(image);
        objects.push(stream_object(
            &format!(
                "/Type /XObject /Subtype /Image /Width {} /Height {} /ColorSpace /DeviceRGB /BitsPerComponent 8 /SMask {} 0 R",
                image.width_px,
                image.height_px,
                7 + 2 * i
            ),
            &deflate(&rgb_bytes)?,
        ));
        objects.push(stream_object(
            &format!(
                "/Type /XObject /Subtype /Image /Width {} /Height {} /ColorSpace /DeviceGray /BitsPerComponent 8",
                image.width_px, image.height_px
            ),
            &deflate(&alpha)?,
        ));
    }
    let mut pdf: Vec<u8> = b"%PDF-1.4\n%\xe2\xe3\xcf\xd3\n".to_vec();
    let mut offsets = Vec::with_capacity(objects.len());
    for (i, object) in objects.iter().enumerate() {
        offsets.push(pdf.len());
        pdf.extend_from_slice(format!("{} 0 obj\n", i + 1).as_bytes());
        pdf.extend_from_slice(object);
        pdf.extend_from_slice(b"\nendobj\n");
    }
    let xref = pdf.len();
    pdf.extend_from_slice(format!("xref\n0 {}\n0000000000 65535 f \n", objects.len() + 1).as_bytes());
    for offset in offsets {
        pdf.extend_from_slice(format!("{offset:010} 00000 n \n").as_bytes());
    }
    pdf.extend_from_slice(
        format!("trailer\n<< /Size {} /Root 1 0 R >>\nstartxref\n{xref}\n%%EOF\n", objects.len() + 1).as_bytes(),
    );
    Ok(pdf)
}

fn stream_object(dictionary: &str, compressed: &[u8]) -> Vec<u8> {
    let mut object = format!("<< {dictionary} /Length {} /Filter /FlateDecode >>\nstream\n", compressed.len()).into_bytes();
    object.extend_from_slice(compressed);
    object.extend_from_slice(b"\nendstream");
    object
}

fn pdf_group<'a>(content: &mut String, group: &'a Group, images: &mut Vec<&'a Image>) {
    for element in &group.children {
        match element {
            Element::Path(path) => {
                let mut outline = String::new();
                for segment in &path.segments {
                    match segment {
                        Segment::MoveTo(p) => {
                            let _ = write!(outline, "{:.3} {:.3} m ", p[0], p[1]);
                        }
                        Segment::LineTo(p) => {
                            let _ = write!(outline, "{:.3} {:.3} l ", p[0], p[1]);
                        }
                        Segment::Close => outline.push_str("h "),
                    }
                }
                if let Some(color) = path.fill {
                    let _ = writeln!(content, "{} rg {outline}f*", rgb(color));
                }
                if let Some(stroke) = &path.stroke {
                    let dash: Vec<String> = stroke.dash_mm.iter().map(|d| format!("{d:.3}")).collect();
                    let _ = writeln!(
                        content,
                        "{} RG {:.4} w [{}] 0 d {outline}S",
                        rgb(stroke.color),
                        stroke.width_mm,
                        dash.join(" ")
                    );
                }
            }
            Element::Dots(dots) => {
                let _ = writeln!(content, "{} RG {:.4} w [] 0 d", rgb(dots.color), 2.0 * dots.radius_mm);
                for (i, c) in dots.centers.iter().enumerate() {
                    let _ = write!(content, "{x:.2} {y:.2} m {x:.2} {y:.2} l{}", if i % 6 == 5 { '\n' } else { ' ' }, x = c[0], y = c[1]);
                }
                content.push_str("S\n");
            }
            Element::Text(text) => {
                let width = helvetica_width_mm(&text.content, text.size_mm);
                let x = match text.anchor {
                    Anchor::Start => text.position[0],
                    Anchor::Middle => text.position[0] - width / 2.0,
                    Anchor::End => text.position[0] - width,
                };
                let _ = writeln!(
                    content,
                    "BT {} rg /F1 {:.3} Tf 1 0 0 -1 {x:.3} {:.3} Tm {} Tj ET",
                    rgb(text.color),
                    text.size_mm,
                    text.position[1],
                    string_literal(&text.content)
                );
            }
            Element::Image(image) => {
                // The unit square maps to the image with its first row at the top: in this
                // y-down page frame the image matrix needs no flip.
                let _ = writeln!(
                    content,
                    "q {:.4} 0 0 {:.4} {:.4} {:.4} cm 1 0 0 -1 0 1 cm /Im{} Do Q",
                    image.width_mm,
                    image.height_mm,
                    image.x_mm,
                    image.y_mm,
                    images.len()
                );
                images.push(image);
            }
            Element::Group(inner) => pdf_group(content, inner, images),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ascii85_matches_known_encodings() {
        assert_eq!(ascii85(b"Man "), "9jqo^~>\n");
        assert_eq!(ascii85(&[0, 0, 0, 0]), "z~>\n");
        assert_eq!(ascii85(b"M"), "9`~>\n");
        assert_eq!(string_literal("Ø (a)\\"), "(\\330 \\(a\\)\\\\)");
    }
}
