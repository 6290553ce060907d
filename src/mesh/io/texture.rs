//! Texture images referenced by OBJ (`map_Kd`) and PLY (`comment TextureFile`) files:
//! PNG through the png crate, JPEG through zune-jpeg, both converted to RGBA8.

use std::path::Path;

use crate::mesh::Texture;
use crate::{Error, Result};

/// Largest image accepted, in decoded bytes: a 8192 x 8192 RGBA texture. A bigger one
/// would break the memory budget of a whole pipeline run (300 MB).
const MAX_DECODED_BYTES: usize = 8192 * 8192 * 4;

/// Reads a PNG or JPEG texture (chosen by content, not by extension, since exporters
/// mislabel them) as RGBA8.
pub(super) fn load_texture(path: &Path) -> Result<Texture> {
    let bytes = super::read_regular_file(path, super::MAX_TEXTURE_FILE_BYTES)?;
    let name = path.display().to_string();
    let (width, height, rgba) = if bytes.starts_with(b"\x89PNG") {
        decode_png(&bytes, &name)?
    } else if bytes.starts_with(b"\xff\xd8") {
        decode_jpeg(&bytes, &name)?
    } else {
        return Err(Error::parse(name, "byte 0", "texture is neither a PNG nor a JPEG image"));
    };
    Ok(Texture { width, height, rgba, source: Some(path.to_path_buf()) })
}

fn decode_png(bytes: &[u8], name: &str) -> Result<(u32, u32, Vec<u8>)> {
    let fail = |e: png::DecodingError| Error::parse(name, "PNG data", e.to_string());
    let mut decoder = png::Decoder::new_with_limits(bytes, png::Limits { bytes: MAX_DECODED_BYTES });
    decoder.set_transformations(png::Transformations::normalize_to_color8());
    let mut reader = decoder.read_info().map_err(fail)?;
    // The decoder's limit covers its own buffers, not the frame the caller allocates: a
    // header declaring 100000 x 100000 pixels is refused here, before that allocation.
    let (width, height) = (reader.info().width, reader.info().height);
    if width as u64 * height as u64 * 4 > MAX_DECODED_BYTES as u64 {
        return Err(Error::parse(
            name,
            "PNG header",
            format!("{width} x {height} pixels is larger than the 8192 x 8192 a texture may have"),
        ));
    }
    let mut buffer = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buffer).map_err(fail)?;
    buffer.truncate(info.buffer_size());
    let rgba = match info.color_type {
        png::ColorType::Rgba => buffer,
        png::ColorType::Rgb => buffer.chunks_exact(3).flat_map(|p| [p[0], p[1], p[2], 255]).collect(),
        png::ColorType::Grayscale => buffer.iter().flat_map(|&g| [g, g, g, 255]).collect(),
        png::ColorType::GrayscaleAlpha => buffer.chunks_exact(2).flat_map(|p| [p[0], p[0], p[0], p[1]]).collect(),
        png::ColorType::Indexed => return Err(Error::parse(name, "PNG header", "palette image was not expanded")),
    };
    Ok((info.width, info.height, rgba))
}

fn decode_jpeg(bytes: &[u8], name: &str) -> Result<(u32, u32, Vec<u8>)> {
    use zune_jpeg::zune_core::colorspace::ColorSpace;
    use zune_jpeg::zune_core::options::DecoderOptions;
    let options = DecoderOptions::default()
        .jpeg_set_out_colorspace(ColorSpace::RGBA)
        .set_max_width(8192)
        .set_max_height(8192);
    let mut decoder = zune_jpeg::JpegDecoder::new_with_options(bytes, options);
    let rgba = decoder.decode().map_err(|e| Error::parse(name, "JPEG data", format!("{e:?}")))?;
    let info = decoder.info().ok_or_else(|| Error::parse(name, "JPEG header", "no image information"))?;
    let (width, height) = (info.width as u32, info.height as u32);
    if rgba.len() != width as usize * height as usize * 4 {
        return Err(Error::parse(name, "JPEG data", format!("decoded {} bytes for a {width} x {height} image", rgba.len())));
    }
    Ok((width, height, rgba))
}

/// Encodes an RGBA8 texture as PNG, for writers that put the texture beside the mesh.
pub(super) fn encode_png(texture: &Texture, writer: &mut dyn std::io::Write) -> Result<()> {
    let fail = |e: png::EncodingError| Error::InvalidArgument(format!("texture cannot be encoded as PNG: {e}"));
    let mut encoder = png::Encoder::new(writer, texture.width, texture.height);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().map_err(fail)?;
    writer.write_image_data(&texture.rgba).map_err(fail)?;
    writer.finish().map_err(fail)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn png_round_trip_keeps_pixels() {
        let texture = Texture { width: 2, height: 1, rgba: vec![255, 0, 0, 255, 0, 0, 255, 128], source: None };
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.png");
        let mut bytes = Vec::new();
        encode_png(&texture, &mut bytes).unwrap();
        std::fs::write(&path, bytes).unwrap();
        let read = load_texture(&path).unwrap();
        assert_eq!((read.width, read.height), (2, 1));
        assert_eq!(read.rgba, texture.rgba);
    }

    #[test]
    fn text_file_is_not_a_texture() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.png");
        std::fs::write(&path, "hello").unwrap();
        let message = load_texture(&path).unwrap_err().to_string();
        assert!(message.contains("neither a PNG nor a JPEG"), "{message}");
    }
}
