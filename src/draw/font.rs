//! A small built-in stroke font for PNG output, where no font file can be assumed:
//! digits, capitals, lower case letters and the symbols the labels use, as polylines on
//! a 4 x 6 grid, so that a label reads as it is written ("mm", "cm", "1:2", "12%",
//! "±"). Vector formats use real Helvetica instead.

/// Strokes of one glyph: polylines in glyph units (x 0..4, y up from the baseline:
/// capitals and ascenders reach 6, the lower case's x-height is 4, descenders go to -2).
fn glyph(c: char) -> &'static str {
    match c {
        'a' => "4,4 4,0; 4,3 3,4 1,4 0,3 0,1 1,0 3,0 4,1",
        'b' => "0,6 0,0; 0,1 1,0 3,0 4,1 4,3 3,4 1,4 0,3",
        'c' => "4,3.2 3,4 1,4 0,3 0,1 1,0 3,0 4,0.8",
        'd' => "4,6 4,0; 4,3 3,4 1,4 0,3 0,1 1,0 3,0 4,1",
        'e' => "0,2 4,2 4,3 3,4 1,4 0,3 0,1 1,0 3,0 4,0.8",
        'f' => "3.5,6 2.5,6 1.5,5 1.5,0; 0,4 3,4",
        'g' => "4,4 4,-1 3,-2 1,-2 0,-1.2; 4,3 3,4 1,4 0,3 0,1 1,0 3,0 4,1",
        'h' => "0,6 0,0; 0,3 1,4 3,4 4,3 4,0",
        'i' => "2,4 2,0; 2,5.4 2,6",
        'j' => "3,4 3,-1 2,-2 1,-2; 3,5.4 3,6",
        'k' => "0,6 0,0; 4,4 0,1.5; 1.5,2.5 4,0",
        'l' => "1.5,6 1.5,1 2.5,0 3,0",
        'm' => "0,4 0,0; 0,3 0.8,4 1.4,4 2,3 2,0; 2,3 2.8,4 3.4,4 4,3 4,0",
        'n' => "0,4 0,0; 0,3 1,4 3,4 4,3 4,0",
        'o' => "1,0 0,1 0,3 1,4 3,4 4,3 4,1 3,0 1,0",
        'p' => "0,4 0,-2; 0,3 1,4 3,4 4,3 4,1 3,0 1,0 0,1",
        'q' => "4,4 4,-2; 4,3 3,4 1,4 0,3 0,1 1,0 3,0 4,1",
        'r' => "0,4 0,0; 0,2.5 1.5,4 3,4 4,3.5",
        's' => "4,3.5 3,4 1,4 0,3.5 0,2.5 1,2 3,2 4,1.5 4,0.5 3,0 1,0 0,0.5",
        't' => "1.5,5.5 1.5,1 2.5,0 3.5,0; 0,4 3.5,4",
        'u' => "0,4 0,1 1,0 3,0 4,1; 4,4 4,0",
        'v' => "0,4 2,0 4,4",
        'w' => "0,4 1,0 2,3 3,0 4,4",
        'x' => "0,0 4,4; 0,4 4,0",
        'y' => "0,4 2,0; 4,4 1,-2 0,-2",
        'z' => "0,4 4,4 0,0 4,0",
        'µ' => "0,4 0,-2; 0,1 1,0 3,0 4,1; 4,4 4,0",
        '\'' => "2,6 2,4.5",
        '[' => "3,6.5 2,6.5 2,-0.5 3,-0.5",
        ']' => "1,6.5 2,6.5 2,-0.5 1,-0.5",
        '<' => "4,5 0,3 4,1",
        '>' => "0,5 4,3 0,1",
        '~' => "0,3 1,3.6 3,2.4 4,3",
        '_' => "0,-0.5 4,-0.5",
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

/// Space between glyphs, glyph units.
const GAP: f64 = 1.5;

/// Advance of a digit (digits are tabular: columns of figures line up) and of a glyph
/// the font lacks, glyph units.
const DIGIT_ADVANCE: f64 = 4.0 + GAP;

/// Advance of a space, glyph units.
const SPACE_ADVANCE: f64 = 4.4;

/// The parsed strokes of `c`, moved so that its left edge is at x = 0 (digits keep their
/// cell), and its advance, in glyph units.
fn shaped(c: char) -> (Vec<Vec<[f64; 2]>>, f64) {
    let strokes: Vec<Vec<[f64; 2]>> = glyph(c)
        .split(';')
        .map(|stroke| {
            stroke
                .split_whitespace()
                .filter_map(|p| {
                    let (gx, gy) = p.split_once(',')?;
                    Some([gx.parse::<f64>().ok()?, gy.parse::<f64>().ok()?])
                })
                .collect::<Vec<_>>()
        })
        .filter(|points| points.len() >= 2)
        .collect();
    if c == ' ' {
        return (strokes, SPACE_ADVANCE);
    }
    if strokes.is_empty() || c.is_ascii_digit() {
        return (strokes, DIGIT_ADVANCE);
    }
    // Proportional letters and signs: "i" and "." narrow, "m" and "w" wide.
    let (lo, hi) = strokes.iter().flatten().fold((f64::MAX, f64::MIN), |(lo, hi), p| (lo.min(p[0]), hi.max(p[0])));
    let moved = strokes.into_iter().map(|s| s.into_iter().map(|p| [p[0] - lo, p[1]]).collect()).collect();
    (moved, (hi - lo).max(1.0) + GAP)
}

/// The strokes of `text` at `size_mm` (the height of capitals is `0.7 * size_mm`, as in
/// Helvetica), starting at `origin` on the baseline, in paper coordinates (y down).
pub fn text_strokes(text: &str, size_mm: f64, origin: [f64; 2]) -> Vec<Vec<[f64; 2]>> {
    let unit = 0.7 * size_mm / 6.0;
    let mut strokes = Vec::new();
    let mut x = origin[0];
    for c in text.chars() {
        let (glyph_strokes, advance) = shaped(c);
        strokes.extend(
            glyph_strokes.into_iter().map(|s| s.into_iter().map(|p| [x + p[0] * unit, origin[1] - p[1] * unit]).collect()),
        );
        x += advance * unit;
    }
    strokes
}

/// Width of `text` in the stroke font at `size_mm`.
pub fn text_width_mm(text: &str, size_mm: f64) -> f64 {
    let unit = 0.7 * size_mm / 6.0;
    let advances: f64 = text.chars().map(|c| shaped(c).1).sum();
    ((advances - GAP) * unit).max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Lowest and highest y of the strokes, in glyph units above the baseline at 0.
    fn vertical_extent(text: &str) -> (f64, f64) {
        let strokes = text_strokes(text, 6.0 / 0.7, [0.0, 0.0]);
        strokes.iter().flatten().fold((f64::MAX, f64::MIN), |(lo, hi), p| (lo.min(-p[1]), hi.max(-p[1])))
    }

    #[test]
    fn every_label_character_has_strokes() {
        for c in "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz.,:-+/%()=°Ø±×µ'[]<>~_".chars() {
            assert!(!text_strokes(&c.to_string(), 10.0, [0.0, 0.0]).is_empty(), "{c}");
        }
        let strokes = text_strokes("10 MM", 3.5, [5.0, 20.0]);
        let (lo, hi) = strokes.iter().flatten().fold((f64::MAX, f64::MIN), |(lo, hi), p| (lo.min(p[1]), hi.max(p[1])));
        assert!((hi - 20.0).abs() < 1e-9 && (20.0 - lo - 0.7 * 3.5).abs() < 1e-9);
        assert!(text_width_mm("10 mm", 3.5) > 0.0);
    }

    #[test]
    fn units_are_written_in_lower_case() {
        // "mm" and "cm" stand at the x-height (4 of 6), not as capitals or small capitals.
        for unit in ["mm", "cm", "ocr", "x"] {
            let (lo, hi) = vertical_extent(unit);
            assert!(lo.abs() < 1e-9 && (hi - 4.0).abs() < 1e-9, "{unit}: {lo}..{hi}");
        }
        // Each lower case letter is its own glyph, not a smaller capital.
        for (lower, upper) in ('a'..='z').zip('A'..='Z') {
            assert_ne!(glyph(lower), glyph(upper), "{lower}");
        }
        // Ascenders reach the capitals, descenders go below the baseline.
        let close = |a: f64, b: f64| (a - b).abs() < 1e-9;
        let (lo, hi) = vertical_extent("d");
        assert!(close(lo, 0.0) && close(hi, 6.0), "d: {lo}..{hi}");
        assert!(close(vertical_extent("p").0, -2.0));
        // "1:2", "12%", "±0.5 mm" keep every character: none falls back to a blank.
        for label in ["1:2", "12% of rim", "±0.5 mm", "Ø 283 mm (274-291)"] {
            for c in label.chars().filter(|c| *c != ' ') {
                assert!(!glyph(c).is_empty(), "{c} of {label}");
            }
        }
        // Proportional letters: "mm" is wider than "ii", digits are tabular.
        assert!(text_width_mm("mm", 3.5) > 1.5 * text_width_mm("ii", 3.5));
        assert!((text_width_mm("11", 3.5) - text_width_mm("88", 3.5)).abs() < 1e-12);
    }
}
