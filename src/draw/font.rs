//! A small built-in stroke font for PNG output, where no font file can be assumed:
//! digits, capitals (lower case drawn as small capitals) and the few symbols the labels
//! use, as polylines on a 4 x 6 grid. Vector formats use real Helvetica instead.

/// Strokes of one glyph: polylines in glyph units (x 0..4, y 0..6 up from the baseline).
fn glyph(c: char) -> &'static str {
    match c {
        '0' => "0,1 0,5 1,6 3,6 4,5 4,1 3,0 1,0 0,1; 4,5 0,1",
        '1' => "1,5 2,6 2,0; 1,0 3,0",
        '2' => "0,5 1,6 3,6 4,5 4,4 0,0 4,0",
        '3' => "0,5 1,6 3,6 4,5 4,4 3,3 4,2 4,1 3,0 1,0 0,1; 1,3 3,3",
        '4' => "3,0 3,6 0,2 4,2",
        '5' => "4,6 0,6 0,3 3,3 4,2 4,1 3,0 0,0",
        '6' => "4,5 3,6 1,6 0,5 0,1 1,0 3,0 4,1 4,2 3,3 0,3",
        '7' => "0,6 4,6 1,0",
        '8' => "1,3 0,4 0,5 1,6 3,6 4,5 4,4 3,3 1,3 0,2 0,1 1,0 3,0 4,1 4,2 3,3",
        '9' => "4,3 1,3 0,4 0,5 1,6 3,6 4,5 4,1 3,0 1,0",
        'A' => "0,0 0,4 2,6 4,4 4,0; 0,3 4,3",
        'B' => "0,0 0,6 3,6 4,5 4,4 3,3 0,3; 3,3 4,2 4,1 3,0 0,0",
        'C' => "4,5 3,6 1,6 0,5 0,1 1,0 3,0 4,1",
        'D' => "0,0 0,6 3,6 4,5 4,1 3,0 0,0",
        'E' => "4,6 0,6 0,0 4,0; 0,3 3,3",
        'F' => "4,6 0,6 0,0; 0,3 3,3",
        'G' => "4,5 3,6 1,6 0,5 0,1 1,0 3,0 4,1 4,3 2,3",
        'H' => "0,0 0,6; 4,0 4,6; 0,3 4,3",
        'I' => "1,6 3,6; 2,6 2,0; 1,0 3,0",
        'J' => "4,6 4,1 3,0 1,0 0,1",
        'K' => "0,0 0,6; 4,6 0,2; 1,3 4,0",
        'L' => "0,6 0,0 4,0",
        'M' => "0,0 0,6 2,3 4,6 4,0",
        'N' => "0,0 0,6 4,0 4,6",
        'O' => "1,0 0,1 0,5 1,6 3,6 4,5 4,1 3,0 1,0",
        'P' => "0,0 0,6 3,6 4,5 4,4 3,3 0,3",
        'Q' => "1,0 0,1 0,5 1,6 3,6 4,5 4,1 3,0 1,0; 2,2 4,0",
        'R' => "0,0 0,6 3,6 4,5 4,4 3,3 0,3; 2,3 4,0",
        'S' => "4,5 3,6 1,6 0,5 0,4 1,3 3,3 4,2 4,1 3,0 1,0 0,1",
        'T' => "0,6 4,6; 2,6 2,0",
        'U' => "0,6 0,1 1,0 3,0 4,1 4,6",
        'V' => "0,6 2,0 4,6",
        'W' => "0,6 1,0 2,4 3,0 4,6",
        'X' => "0,0 4,6; 0,6 4,0",
        'Y' => "0,6 2,3 4,6; 2,3 2,0",
        'Z' => "0,6 4,6 0,0 4,0",
        '.' => "1.8,0 2.2,0 2.2,0.4 1.8,0.4 1.8,0",
        ',' => "2,0.4 2,0 1.5,-1",
        ':' => "2,0 2,0.4; 2,3 2,3.4",
        '-' => "1,3 3,3",
        '+' => "0.5,3 3.5,3; 2,1.5 2,4.5",
        '/' => "0,0 4,6",
        '%' => "0,0 4,6; 0,6 0,5 1,5 1,6 0,6; 3,0 3,1 4,1 4,0 3,0",
        '(' => "3,6 2,5 2,1 3,0",
        ')' => "1,6 2,5 2,1 1,0",
        '=' => "0.5,2 3.5,2; 0.5,4 3.5,4",
        '°' => "1,6 2,6 2,5 1,5 1,6",
        'Ø' => "1,0 0,1 0,5 1,6 3,6 4,5 4,1 3,0 1,0; 0,-0.5 4,6.5",
        '±' => "0.5,3.5 3.5,3.5; 2,2 2,5; 0.5,1 3.5,1",
        '×' => "0.5,1.5 3.5,4.5; 0.5,4.5 3.5,1.5",
        _ => "",
    }
}

/// Advance of one glyph in glyph units (4 wide plus 1.5 spacing).
const ADVANCE: f64 = 5.5;

/// The strokes of `text` at `size_mm` (the height of capitals is `0.7 * size_mm`, as in
/// Helvetica), starting at `origin` on the baseline, in paper coordinates (y down).
pub fn text_strokes(text: &str, size_mm: f64, origin: [f64; 2]) -> Vec<Vec<[f64; 2]>> {
    let unit = 0.7 * size_mm / 6.0;
    let mut strokes = Vec::new();
    let mut x = origin[0];
    for c in text.chars() {
        let (shape, height): (char, f64) = if c.is_ascii_lowercase() { (c.to_ascii_uppercase(), 0.72) } else { (c, 1.0) };
        for stroke in glyph(shape).split(';') {
            let points: Vec<[f64; 2]> = stroke
                .split_whitespace()
                .filter_map(|p| {
                    let (gx, gy) = p.split_once(',')?;
                    let (gx, gy) = (gx.parse::<f64>().ok()?, gy.parse::<f64>().ok()?);
                    Some([x + gx * unit * height.max(0.85), origin[1] - gy * unit * height])
                })
                .collect();
            if points.len() >= 2 {
                strokes.push(points);
            }
        }
        x += ADVANCE * unit * if c == ' ' { 0.8 } else if c.is_ascii_lowercase() { 0.9 } else { 1.0 };
    }
    strokes
}

/// Width of `text` in the stroke font at `size_mm`.
pub fn text_width_mm(text: &str, size_mm: f64) -> f64 {
    let unit = 0.7 * size_mm / 6.0;
    text.chars()
        .map(|c| ADVANCE * unit * if c == ' ' { 0.8 } else if c.is_ascii_lowercase() { 0.9 } else { 1.0 })
        .sum::<f64>()
        - 1.5 * unit
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_label_character_has_strokes() {
        for c in "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ.,:-+/%()=°Ø±×".chars() {
            assert!(!text_strokes(&c.to_string(), 10.0, [0.0, 0.0]).is_empty(), "{c}");
        }
        let strokes = text_strokes("10 mm", 3.5, [5.0, 20.0]);
        let (lo, hi) = strokes.iter().flatten().fold((f64::MAX, f64::MIN), |(lo, hi), p| (lo.min(p[1]), hi.max(p[1])));
        assert!((hi - 20.0).abs() < 1e-9 && (20.0 - lo - 0.7 * 3.5).abs() < 1e-9);
        assert!(text_width_mm("10 mm", 3.5) > 0.0);
    }
}
