//! Horizontal circle adjustment by the multi-criteria approach (Wilczek et al. 2018,
//! section 2.3.2): for each horizontal section a circle is fitted (Chernov), and two
//! costs of the two tilts are traded off on a Pareto front:
//!
//! * Eq. 3, the dispersion of the circle centres projected on the xy-plane,
//!   `sum w_i |C_i - C|^2 / sum w_i`;
//! * Eq. 4, the circle residuals, `sum (w_i / k_i) sum_j (|X_ij - C_i| - R_i)^2 / sum w_i`;
//!
//! with `w_i` the sector angle of section `i` (radians). Sections with too few points or
//! too small an arc are dropped. The shifts are not searched: the axis passes through the
//! weighted mean centre.
//!
//! The search samples the whole cone of tilts within the bound around the start axis (the
//! original's NSGA-II with 20 individuals over 20 generations explores it poorly), then
//! repeatedly samples finer grids around the current non-dominated set, never leaving the
//! cone. The chosen solution is the knee of the front by default.

use serde::{Deserialize, Serialize};

use super::circle_fit::{fit_circle, CircleFitMethod};
use super::sections::{axis_through, sector_angle_rad, AxisParameters, CandidateFrame, PreparedSurface};

/// Settings of the multi-criteria search.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ParetoOptions {
    /// Sections with fewer points are dropped.
    pub min_section_points: usize,
    /// Sections whose arc is smaller are dropped, degrees.
    pub min_sector_angle_deg: f64,
    /// Circle fit per section.
    pub circle_fit: CircleFitMethod,
    /// Samples per side of the first grid over the tilt box.
    pub grid_samples_per_side: usize,
    /// Rounds of finer local sampling around the front.
    pub refinement_rounds: usize,
    /// At most this many front points are refined per round (spread along the front).
    pub refined_points_per_round: usize,
    /// Which front solution becomes the axis.
    pub choice: ParetoChoice,
}

impl Default for ParetoOptions {
    fn default() -> Self {
        ParetoOptions {
            min_section_points: 10,
            min_sector_angle_deg: 3.0,
            circle_fit: CircleFitMethod::Taubin,
            grid_samples_per_side: 15,
            refinement_rounds: 8,
            refined_points_per_round: 8,
            choice: ParetoChoice::Knee,
        }
    }
}

impl ParetoOptions {
    /// These options if a search can use them: at least 3 points per section (a circle
    /// needs three), an arc limit of 0 to 360 degrees, the mean of at least one solution;
    /// else why not.
    pub fn validated(self) -> crate::Result<Self> {
        let problem = if self.min_section_points < 3 {
            format!("the Pareto criterion's min_points must be at least 3 (a circle needs three), got {}", self.min_section_points)
        } else if !(0.0..=360.0).contains(&self.min_sector_angle_deg) {
            format!("the Pareto criterion's min_sector_deg must be in [0, 360], got {}", self.min_sector_angle_deg)
        } else if self.choice == ParetoChoice::MeanOfBest(0) {
            "the Pareto criterion's mean of the best needs a count of at least 1".to_string()
        } else {
            return Ok(self);
        };
        Err(crate::Error::InvalidArgument(problem))
    }
}

/// How the solution is picked from the front.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum ParetoChoice {
    /// The knee: the front point with the smallest product of the two costs, i.e. the
    /// smallest sum of their logarithms. Both are mean squares, so the trade-off is made
    /// in ratios: a move along the front is worth it when it divides one cost by more
    /// than it multiplies the other. Scaling by ranges instead lets the noise of a cost
    /// that barely changes (circle residuals on a smooth wall) decide the choice.
    Knee,
    /// The best centre dispersion (Eq. 3 alone).
    Centres,
    /// The best circle residual (Eq. 4 alone).
    Residuals,
    /// The mean of the tilts of the `n` points with the smallest sum of scaled costs
    /// (the original takes n = 2).
    MeanOfBest(usize),
}

crate::vocabulary! {
    /// The kinds of [`ParetoChoice`], by name (`MeanOfBest` without its count).
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    pub enum ParetoChoiceKind: "Pareto choice", "Pareto choices" {
        /// [`ParetoChoice::Knee`].
        Knee = "knee" => "The front's solution with the smallest product of the two costs",
        /// [`ParetoChoice::Centres`].
        Centres = "centres" => "The best centre dispersion (Eq. 3 alone)",
        /// [`ParetoChoice::Residuals`].
        Residuals = "residuals" => "The best circle residual (Eq. 4 alone)",
        /// [`ParetoChoice::MeanOfBest`].
        MeanOfBest = "mean_of_best" => "The mean of the best solutions (the original tool takes 2)",
    }
}

impl ParetoChoiceKind {
    /// The choice of this kind; `count` is the number of best solutions `MeanOfBest`
    /// averages (the others ignore it).
    pub fn with_count(self, count: usize) -> ParetoChoice {
        match self {
            ParetoChoiceKind::Knee => ParetoChoice::Knee,
            ParetoChoiceKind::Centres => ParetoChoice::Centres,
            ParetoChoiceKind::Residuals => ParetoChoice::Residuals,
            ParetoChoiceKind::MeanOfBest => ParetoChoice::MeanOfBest(count),
        }
    }
}

/// One evaluated tilt: both costs and the axis it gives.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ParetoPoint {
    /// Turn about the start frame's x axis, degrees.
    pub tilt_x_deg: f64,
    /// Turn about the start frame's y axis, degrees.
    pub tilt_y_deg: f64,
    /// Eq. 3: sector-weighted dispersion of the circle centres, mm^2.
    pub centre_dispersion_mm2: f64,
    /// Eq. 4: sector-weighted mean squared circle residual, mm^2.
    pub circle_residual_mm2: f64,
    /// The four axis parameters (start frame) of this solution, shifts from the mean centre.
    #[serde(skip)]
    pub parameters: AxisParameters,
}

/// Both costs of Eq. 3 and 4 at one pair of tilts, and the shifts the mean centre gives.
pub fn evaluate(surface: &PreparedSurface, tilt_x_rad: f64, tilt_y_rad: f64, options: &ParetoOptions) -> Option<ParetoPoint> {
    let frame = CandidateFrame::new(&[tilt_x_rad, tilt_y_rad, 0.0, 0.0]);
    let sections = surface.horizontal_sections(&frame);
    let mut fits = Vec::new();
    for section in &sections {
        if section.points.len() < options.min_section_points {
            continue;
        }
        let Some(circle) = fit_circle(&section.points, options.circle_fit) else { continue };
        let sector = sector_angle_rad(
            section.points.iter().map(|p| (p[1] - circle.center[1]).atan2(p[0] - circle.center[0])).collect(),
        );
        if sector < options.min_sector_angle_deg.to_radians() {
            continue;
        }
        let mean_squared_residual = section.points.iter().map(|&p| circle.signed_distance(p).powi(2)).sum::<f64>()
            / section.points.len() as f64;
        fits.push((circle, sector, mean_squared_residual, section.height_mm));
    }
    if fits.len() < 2 {
        return None;
    }
    let weight_sum: f64 = fits.iter().map(|f| f.1).sum();
    let mean = [
        fits.iter().map(|f| f.1 * f.0.center[0]).sum::<f64>() / weight_sum,
        fits.iter().map(|f| f.1 * f.0.center[1]).sum::<f64>() / weight_sum,
    ];
    let mean_height = fits.iter().map(|f| f.1 * f.3).sum::<f64>() / weight_sum;
    let dispersion = fits
        .iter()
        .map(|f| f.1 * ((f.0.center[0] - mean[0]).powi(2) + (f.0.center[1] - mean[1]).powi(2)))
        .sum::<f64>()
        / weight_sum;
    let residual = fits.iter().map(|f| f.1 * f.2).sum::<f64>() / weight_sum;
    Some(ParetoPoint {
        tilt_x_deg: tilt_x_rad.to_degrees(),
        tilt_y_deg: tilt_y_rad.to_degrees(),
        centre_dispersion_mm2: dispersion,
        circle_residual_mm2: residual,
        parameters: axis_through([tilt_x_rad, tilt_y_rad], mean, mean_height),
    })
}

/// The non-dominated points of `points` (both costs minimised), sorted by centre dispersion.
pub fn non_dominated(points: &[ParetoPoint]) -> Vec<ParetoPoint> {
    let mut sorted: Vec<ParetoPoint> = points.to_vec();
    sorted.sort_by(|a, b| {
        a.centre_dispersion_mm2.total_cmp(&b.centre_dispersion_mm2).then(a.circle_residual_mm2.total_cmp(&b.circle_residual_mm2))
    });
    let mut front: Vec<ParetoPoint> = Vec::new();
    for p in sorted {
        if front.last().is_none_or(|last| p.circle_residual_mm2 < last.circle_residual_mm2) {
            front.push(p);
        }
    }
    front
}

/// Scales both costs of the front by their ranges over all `samples` (the whole box):
/// a cost that hardly changes along the front compared with how it changes across
/// the box carries no information there, and scaling by the front's own range would
/// blow its noise up to the size of the other cost's signal.
fn scaled(front: &[ParetoPoint], samples: &[ParetoPoint]) -> Vec<[f64; 2]> {
    let range = |f: fn(&ParetoPoint) -> f64| {
        let low = samples.iter().chain(front).map(f).fold(f64::INFINITY, f64::min);
        let high = samples.iter().chain(front).map(f).fold(f64::NEG_INFINITY, f64::max);
        (low, (high - low).max(1e-300))
    };
    let (c_low, c_span) = range(|p| p.centre_dispersion_mm2);
    let (r_low, r_span) = range(|p| p.circle_residual_mm2);
    front
        .iter()
        .map(|p| [(p.centre_dispersion_mm2 - c_low) / c_span, (p.circle_residual_mm2 - r_low) / r_span])
        .collect()
}

/// The parameters chosen from a non-empty front (sorted as [`non_dominated`] gives it),
/// costs scaled by their ranges over all evaluated `samples`.
pub fn choose(front: &[ParetoPoint], samples: &[ParetoPoint], choice: ParetoChoice) -> AxisParameters {
    let scaled_costs = scaled(front, samples);
    match choice {
        ParetoChoice::Centres => front[0].parameters,
        ParetoChoice::Residuals => front[front.len() - 1].parameters,
        ParetoChoice::Knee => {
            let best = (0..front.len())
                .min_by(|&a, &b| {
                    let product = |p: &ParetoPoint| p.centre_dispersion_mm2.max(0.0) * p.circle_residual_mm2.max(0.0);
                    product(&front[a]).total_cmp(&product(&front[b]))
                })
                .unwrap_or(0);
            front[best].parameters
        }
        ParetoChoice::MeanOfBest(n) => {
            let mut order: Vec<usize> = (0..front.len()).collect();
            order.sort_by(|&a, &b| {
                (scaled_costs[a][0] + scaled_costs[a][1]).total_cmp(&(scaled_costs[b][0] + scaled_costs[b][1]))
            });
            let chosen = &order[..n.clamp(1, front.len())];
            let mut mean = [0.0; 4];
            for &i in chosen {
                for (sum, value) in mean.iter_mut().zip(&front[i].parameters) {
                    *sum += value / chosen.len() as f64;
                }
            }
            mean
        }
    }
}

/// The result of the search: every front point and the chosen parameters.
#[derive(Clone, Debug)]
pub struct ParetoSearch {
    /// The final non-dominated set.
    pub front: Vec<ParetoPoint>,
    /// The parameters picked by the choice rule.
    pub chosen: AxisParameters,
    /// Cost evaluations made.
    pub evaluations: usize,
}

/// Whether the tilts `(tilt_x_rad, tilt_y_rad)` lie within the cone of half-angle
/// `bound_rad` about `centre`. The norm of the two tilts is what the other criteria's
/// search bounds too (`objective::minimize`), and it is never smaller than the angle
/// between the axes, so a point inside is never more than `bound_rad` off the start.
pub fn within_bound(centre: [f64; 2], tilt_x_rad: f64, tilt_y_rad: f64, bound_rad: f64) -> bool {
    (tilt_x_rad - centre[0]).hypot(tilt_y_rad - centre[1]) <= bound_rad + 1e-12
}

/// Samples the cone of tilts of half-angle `bound_rad` about `centre` (tilts) on a
/// grid, then refines the front on finer grids; every sample lies in the cone.
pub fn search(surface: &PreparedSurface, centre: [f64; 2], bound_rad: f64, options: &ParetoOptions) -> Option<ParetoSearch> {
    let n = options.grid_samples_per_side.max(3);
    let step = 2.0 * bound_rad / (n - 1) as f64;
    let mut samples = Vec::new();
    let mut evaluations = 0;
    let mut sample = |tx: f64, ty: f64, samples: &mut Vec<ParetoPoint>| {
        if !within_bound(centre, tx, ty, bound_rad) {
            return;
        }
        evaluations += 1;
        if let Some(p) = evaluate(surface, tx, ty, options) {
            samples.push(p);
        }
    };
    for i in 0..n {
        for j in 0..n {
            sample(centre[0] - bound_rad + step * i as f64, centre[1] - bound_rad + step * j as f64, &mut samples);
        }
    }
    let mut front = non_dominated(&samples);
    let mut local_step = step / 2.0;
    for _ in 0..options.refinement_rounds {
        if front.is_empty() {
            break;
        }
        let picks = spread(&front, &samples, options.refined_points_per_round.max(1));
        for p in picks {
            let (tx, ty) = (p.tilt_x_deg.to_radians(), p.tilt_y_deg.to_radians());
            for di in -1i32..=1 {
                for dj in -1i32..=1 {
                    if di != 0 || dj != 0 {
                        sample(tx + local_step * di as f64, ty + local_step * dj as f64, &mut samples);
                    }
                }
            }
        }
        front = non_dominated(&samples);
        local_step /= 2.0;
    }
    if front.is_empty() {
        return None;
    }
    let chosen = choose(&front, &samples, options.choice);
    Some(ParetoSearch { front, chosen, evaluations })
}

/// Up to `count` front points spread evenly along it (always both ends and the knee).
fn spread(front: &[ParetoPoint], samples: &[ParetoPoint], count: usize) -> Vec<ParetoPoint> {
    if front.len() <= count {
        return front.to_vec();
    }
    let mut picks: Vec<ParetoPoint> = (0..count).map(|k| front[k * (front.len() - 1) / (count - 1).max(1)]).collect();
    let knee = choose(front, samples, ParetoChoice::Knee);
    if let Some(p) = front.iter().find(|p| p.parameters == knee) {
        picks.push(*p);
    }
    picks
}

/// One axis of [`front_svg`]: logarithmic when the values are positive and span more than
/// a decade (a front often runs over several, and a linear axis then crushes all but one
/// point against the origin), else linear; `at` maps a value to `[0, 1]`.
struct PlotAxis {
    low: f64,
    high: f64,
    logarithmic: bool,
}

impl PlotAxis {
    fn over(values: impl Iterator<Item = f64> + Clone) -> PlotAxis {
        let low = values.clone().fold(f64::INFINITY, f64::min);
        let high = values.fold(f64::NEG_INFINITY, f64::max);
        if !(low.is_finite() && high.is_finite()) {
            return PlotAxis { low: 0.0, high: 1.0, logarithmic: false };
        }
        let logarithmic = low > 0.0 && high / low > 10.0;
        let high = if high > low { high } else { low + low.abs().max(1e-12) * 1e-6 };
        PlotAxis { low, high, logarithmic }
    }

    fn at(&self, value: f64) -> f64 {
        if self.logarithmic {
            (value / self.low).log10() / (self.high / self.low).log10()
        } else {
            (value - self.low) / (self.high - self.low)
        }
    }

    /// Values to label: the decades within the range on a logarithmic axis (at most
    /// seven, else every other), and the ends of a linear one and its middle.
    fn ticks(&self) -> Vec<f64> {
        if !self.logarithmic {
            return vec![self.low, (self.low + self.high) / 2.0, self.high];
        }
        let decades: Vec<f64> = (self.low.log10().ceil() as i32..=self.high.log10().floor() as i32).map(|e| 10f64.powi(e)).collect();
        match decades.len() {
            0 | 1 => vec![self.low, self.high],
            n if n > 7 => decades.into_iter().step_by(2).collect(),
            _ => decades,
        }
    }

    fn title(&self, name: &str) -> String {
        if self.logarithmic { format!("{name} (mm², log scale)") } else { format!("{name} (mm²)") }
    }
}

/// The front as an SVG scatter plot: centre dispersion (Eq. 3) across, circle residual
/// (Eq. 4) up, each on a logarithmic axis where the front spans more than a decade, the
/// chosen solution circled in red; each point's tooltip gives its tilts.
pub fn front_svg(front: &[ParetoPoint], chosen: Option<&ParetoPoint>) -> String {
    let (width, height) = (520.0, 380.0);
    let (left, right, top, bottom) = (78.0, 20.0, 20.0, 58.0);
    let all: Vec<&ParetoPoint> = front.iter().chain(chosen).collect();
    let across = PlotAxis::over(all.iter().map(|p| p.centre_dispersion_mm2));
    let up = PlotAxis::over(all.iter().map(|p| p.circle_residual_mm2));
    // A margin inside the axes, so that points at the ends are not cut by them.
    let inset = 0.04;
    let to_x = |v: f64| left + (inset + (1.0 - 2.0 * inset) * across.at(v)) * (width - left - right);
    let to_y = |v: f64| height - bottom - (inset + (1.0 - 2.0 * inset) * up.at(v)) * (height - top - bottom);
    let text = "font-family=\"sans-serif\" font-size=\"11\"";
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" viewBox=\"0 0 {width} {height}\">\n\
         <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n\
         <line x1=\"{left}\" y1=\"{0}\" x2=\"{1}\" y2=\"{0}\" stroke=\"black\"/>\n\
         <line x1=\"{left}\" y1=\"{0}\" x2=\"{left}\" y2=\"{top}\" stroke=\"black\"/>\n",
        height - bottom,
        width - right
    );
    for value in across.ticks() {
        let x = to_x(value);
        svg += &format!(
            "<line x1=\"{x:.2}\" y1=\"{0}\" x2=\"{x:.2}\" y2=\"{1}\" stroke=\"black\"/>\n<text x=\"{x:.2}\" y=\"{2}\" {text} text-anchor=\"middle\">{value:.2e}</text>\n",
            height - bottom,
            height - bottom + 4.0,
            height - bottom + 16.0
        );
    }
    for value in up.ticks() {
        let y = to_y(value);
        svg += &format!(
            "<line x1=\"{0}\" y1=\"{y:.2}\" x2=\"{left}\" y2=\"{y:.2}\" stroke=\"black\"/>\n<text x=\"{1}\" y=\"{2:.2}\" {text} text-anchor=\"end\">{value:.2e}</text>\n",
            left - 4.0,
            left - 6.0,
            y + 4.0
        );
    }
    svg += &format!(
        "<text x=\"{0}\" y=\"{1}\" {text} text-anchor=\"middle\">{2}</text>\n",
        left + (width - left - right) / 2.0,
        height - 12.0,
        across.title("centre dispersion, Eq. 3")
    );
    svg += &format!(
        "<text x=\"{0}\" y=\"{1}\" {text} text-anchor=\"middle\" transform=\"rotate(-90 {0} {1})\">{2}</text>\n",
        14.0,
        top + (height - top - bottom) / 2.0,
        up.title("circle residual, Eq. 4")
    );
    for p in front {
        svg += &format!(
            "<circle cx=\"{:.2}\" cy=\"{:.2}\" r=\"3\" fill=\"#3060c0\"><title>tilt {:.3}, {:.3} deg</title></circle>\n",
            to_x(p.centre_dispersion_mm2),
            to_y(p.circle_residual_mm2),
            p.tilt_x_deg,
            p.tilt_y_deg
        );
    }
    if let Some(p) = chosen {
        svg += &format!(
            "<circle cx=\"{:.2}\" cy=\"{:.2}\" r=\"6\" fill=\"none\" stroke=\"#d02020\" stroke-width=\"2\"><title>chosen: tilt {:.3}, {:.3} deg</title></circle>\n",
            to_x(p.centre_dispersion_mm2),
            to_y(p.circle_residual_mm2),
            p.tilt_x_deg,
            p.tilt_y_deg
        );
    }
    svg += "</svg>\n";
    svg
}
