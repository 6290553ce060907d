//! The crests of the sections' lips: the top of a parabola fitted through each section's
//! points near its extreme, steadier on a rounded rim than the one noisy extreme vertex.

use super::TangentObjective;
use crate::mesh::{planar_length, Point};
use crate::refine::sections::CandidateFrame;

impl TangentObjective {
    /// The crest of each vertical section's lip under a candidate frame, in the candidate
    /// frame: the top of the parabola in the distance to the axis fitted through the
    /// section's points within 0.5 mm of its extreme (weighted, fading to nothing at
    /// 0.5 mm), its curvature shared by all sections, placed at their centroid. `None`
    /// for a section with too few points; every section's extreme where the lips are not
    /// rounded or too few sections fit (see `lip_crests`).
    pub fn crest_points(&self, frame: &CandidateFrame) -> Vec<Option<Point>> {
        let bands = self.sections.iter().map(|section| section.lip_band(frame, self.edge, CREST_BAND_MM).expect("sections are not empty")).collect();
        lip_crests(bands, self.edge.outward())
    }
}

/// One section's lip band in the coordinates of its crest parabola.
struct LipBand {
    /// `[u, h, weight]` per point: `u` the distance to the axis less the extreme's, `h`
    /// the height signed outward (up for a rim, down for a base).
    coordinates: Vec<[f64; 3]>,
    /// The weighted centroid, where the crest is placed: in a frame not yet level the
    /// band reaches further along the arc on the section's higher side, and its fitted
    /// height is that of its centroid, not of its extreme.
    centroid: Point,
    /// The extreme's height, signed outward.
    extreme_height: f64,
}

impl LipBand {
    /// Each point weighs `(1 - (depth / band_mm)^2)^2` by its depth below the extreme: the
    /// weights fade to nothing at the band's floor, so that the fit, unlike a band that
    /// takes points in or drops them whole, changes smoothly as the frame turns (the
    /// extreme's height does; its `u` may jump to another vertex, which moves the origin
    /// of `u` and not the parabola's top).
    fn new(extreme: &Point, band: &[Point], outward: f64, band_mm: f64) -> Self {
        let radius_at_extreme = planar_length(extreme.x, extreme.y);
        let coordinates: Vec<[f64; 3]> = band
            .iter()
            .map(|p| {
                let depth = (outward * (extreme.z - p.z)).max(0.0) / band_mm;
                [planar_length(p.x, p.y) - radius_at_extreme, outward * p.z, (1.0 - depth * depth).max(0.0).powi(2)]
            })
            .collect();
        let weight: f64 = coordinates.iter().map(|c| c[2]).sum();
        let centroid = Point::from(band.iter().zip(&coordinates).map(|(p, c)| p.coords * c[2]).sum::<crate::mesh::Vector>() / weight.max(1e-300));
        LipBand { coordinates, centroid, extreme_height: outward * extreme.z }
    }

    /// The weighted least-squares line `value = a + b u` over the band as `[a, b]`, `None`
    /// with fewer than [`CREST_MIN_POINTS`] points of weight or no spread in `u`.
    fn line_fit(&self, value: impl Fn(&[f64; 3]) -> f64) -> Option<[f64; 2]> {
        if self.coordinates.iter().filter(|c| c[2] > 0.0).count() < CREST_MIN_POINTS {
            return None;
        }
        let weight: f64 = self.coordinates.iter().map(|c| c[2]).sum();
        let mean_u = self.coordinates.iter().map(|c| c[2] * c[0]).sum::<f64>() / weight;
        let mean_value = self.coordinates.iter().map(|c| c[2] * value(c)).sum::<f64>() / weight;
        let spread: f64 = self.coordinates.iter().map(|c| c[2] * (c[0] - mean_u).powi(2)).sum();
        if !(spread > 1e-12) {
            return None;
        }
        let slope = self.coordinates.iter().map(|c| c[2] * (c[0] - mean_u) * (value(c) - mean_value)).sum::<f64>() / spread;
        Some([mean_value - slope * mean_u, slope])
    }
}

/// The crests of the sections' lips from their bands (`(extreme, band)` as
/// [`SectionCandidates::lip_band`] gives them): at each band's centroid, the top over the
/// band's `u` of `h = a_j + b_j u + c u^2` (see [`LipBand`]), whose curvature `c` all
/// sections share and whose `a_j`, `b_j` are each section's own. `None` for a section
/// with too few points to fit. Where the lips are not rounded (`c` not below
/// `-CREST_MIN_CURVATURE_PER_MM`), or where fewer than three sections or than half of
/// them fit, every section's crest is its extreme.
///
/// A rounded lip is the same cap along the whole rim, so its shape is learnt from all
/// sections at once, while each section keeps its own crest height and radius (the
/// vessel's ovality and wobble move the crest in and out by tenths of a millimetre).
///
/// [`SectionCandidates::lip_band`]: super::candidates::SectionCandidates::lip_band
fn lip_crests(bands: Vec<(Point, Vec<Point>)>, outward: f64) -> Vec<Option<Point>> {
    let lips: Vec<LipBand> = bands.iter().map(|(extreme, band)| LipBand::new(extreme, band, outward, CREST_BAND_MM)).collect();
    fitted_crests(&lips, outward).unwrap_or_else(|| bands.into_iter().map(|(extreme, _)| Some(extreme)).collect())
}

/// [`lip_crests`] where the lips give crests: `None` where every section keeps its extreme.
fn fitted_crests(lips: &[LipBand], outward: f64) -> Option<Vec<Option<Point>>> {
    // The curvature alone, each section's own line in u taken out of u^2 and of h
    // (Frisch-Waugh), summed over sections.
    let (mut cross, mut square) = (0.0, 0.0);
    for lip in lips {
        let (Some(q), Some(h)) = (lip.line_fit(|c| c[0] * c[0]), lip.line_fit(|c| c[1])) else { continue };
        for c in &lip.coordinates {
            let residual_q = c[0] * c[0] - (q[0] + q[1] * c[0]);
            let residual_h = c[1] - (h[0] + h[1] * c[0]);
            cross += c[2] * residual_q * residual_h;
            square += c[2] * residual_q * residual_q;
        }
    }
    let curvature = cross / square;
    if !(square > 0.0 && curvature < -CREST_MIN_CURVATURE_PER_MM) {
        return None;
    }
    let crests: Vec<Option<Point>> = lips
        .iter()
        .map(|lip| {
            let [a, b] = lip.line_fit(|c| c[1] - curvature * c[0] * c[0])?;
            let (low, high) = lip.coordinates.iter().filter(|c| c[2] > 0.0).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), c| (l.min(c[0]), h.max(c[0])));
            let top_u = (-b / (2.0 * curvature)).clamp(low, high);
            let top = a + b * top_u + curvature * top_u * top_u;
            (top <= lip.extreme_height + CREST_MAX_RISE_MM).then(|| Point::new(lip.centroid.x, lip.centroid.y, outward * top))
        })
        .collect();
    // A coarse mesh leaves most lips a vertex or two in the band: the extremes then, for
    // every section, since a crest and an extreme stand at different heights (the top of
    // the parabola against the highest vertex near it) and a plane through both would tip.
    let fitted = crests.iter().flatten().count();
    (fitted >= 3 && 2 * fitted >= crests.len()).then_some(crests)
}

/// Highest a crest may stand above its section's extreme vertex, mm: the vertex nearest
/// a crest falls short of it by `(spacing / 2)^2 / (2 radius)`, 0.03 mm for a lip of
/// radius 2 mm sampled every millimetre. A parabola topping out higher has been fitted
/// to something else than a lip, such as the break face at the end of a rim, whose band
/// ran 0.7 mm above its highest point on a 200k-face synthetic rim.
const CREST_MAX_RISE_MM: f64 = 0.05;

/// Fewest points of a section's lip band for its crest.
const CREST_MIN_POINTS: usize = 3;

/// Least (negative) curvature of the lips' parabola for [`lip_crests`], per mm: a
/// cap of radius 50 mm. Flatter, the lip is a flat face and its crest the extreme.
const CREST_MIN_CURVATURE_PER_MM: f64 = 0.01;

/// Depth of the band below a section's extreme through which its crest parabola is
/// fitted, mm.
const CREST_BAND_MM: f64 = 0.5;
