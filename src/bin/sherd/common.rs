//! Arguments shared by the analysis sub-commands (`orient`, `draw`, `export`, `batch`) and
//! their translation into the library's options.

use std::path::Path;

use clap::{Args, ValueEnum};

use crate::choices::{Choices, cli_name};
use sherd::draw::{Annotations, DrawOptions, Placement, RegularityKind, SectionFill, Style};
use sherd::mesh::fingerprint::ScanFingerprint;
use sherd::mesh::Point;
use sherd::orient::{Axis, AxisRecord};
use sherd::pipeline::{PipelineOptions, RecordStatus};
use sherd::refine::circle_fit::CircleFitMethod;
use sherd::refine::pareto::{ParetoChoice, ParetoChoiceKind, ParetoOptions};
use sherd::refine::superposition::{ProfileMethod, ProfileMethodKind};
use sherd::refine::{Criterion, EdgeChoice, RefineOptions, Surface};
use sherd::vocabulary::{Vocabulary, or_list};

/// Units of a scan file whose format does not say.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum Units {
    Mm,
    Cm,
    M,
}

impl Units {
    fn millimetres(self) -> f64 {
        match self {
            Units::Mm => 1.0,
            Units::Cm => 10.0,
            Units::M => 1000.0,
        }
    }
}

/// The refinement criterion, or none (`--refine none` keeps the pre-orientation).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RefineChoice(pub Option<Criterion>);

impl RefineChoice {
    /// `--refine`'s values: the library's criteria, then `none`.
    fn choices() -> Choices<RefineChoice> {
        Choices::of(criterion_help, |criterion| RefineChoice(Some(criterion))).and(
            RefineChoice(None),
            "none",
            "Keep the pre-orientation",
        )
    }
}

/// The help line of a criterion in `--help`.
fn criterion_help(criterion: Criterion) -> Option<&'static str> {
    match criterion {
        Criterion::Auto => Some(
            "Tangent plane where a level rim or base is kept; otherwise circles, averaged with the profile criterion where the two agree",
        ),
        _ => None,
    }
}

/// The help line of a circle fit in `--help`.
fn circle_fit_help(fit: CircleFitMethod) -> Option<&'static str> {
    match fit {
        CircleFitMethod::Taubin => Some("Nearly unbiased on short arcs"),
        CircleFitMethod::Geometric => Some("Orthogonal distances, started from Taubin's"),
        _ => None,
    }
}

/// The help line of an edge in `--help`.
fn edge_help(edge: EdgeChoice) -> Option<&'static str> {
    (edge == EdgeChoice::Detect).then_some("The one whose extremes are level")
}

/// No help line: the name says it.
fn no_help<T>(_: T) -> Option<&'static str> {
    None
}

/// The library's default Pareto choice as `--pareto-choice` writes it.
fn pareto_choice_text(choice: ParetoChoice) -> String {
    match choice {
        ParetoChoice::Knee => cli_name(ParetoChoiceKind::Knee),
        ParetoChoice::Centres => cli_name(ParetoChoiceKind::Centres),
        ParetoChoice::Residuals => cli_name(ParetoChoiceKind::Residuals),
        ParetoChoice::MeanOfBest(count) => format!("{}:{count}", cli_name(ParetoChoiceKind::MeanOfBest)),
    }
}

/// "knee", "centres", "residuals" or "mean-of-best:N" as the Pareto criterion's choice.
fn parse_pareto_choice(text: &str) -> Result<ParetoChoice, String> {
    let (name, count) = text.split_once(':').unwrap_or((text, ""));
    let kind = ParetoChoiceKind::ALL.iter().copied().find(|kind| cli_name(*kind) == name);
    match (kind, count.parse::<usize>()) {
        (Some(ParetoChoiceKind::MeanOfBest), Ok(count)) => ParetoOptions { choice: ParetoChoice::MeanOfBest(count), ..Default::default() }
            .validated()
            .map(|options| options.choice)
            .map_err(|e| format!("{text:?}: {e}")),
        (Some(kind), _) if kind != ParetoChoiceKind::MeanOfBest && !text.contains(':') => Ok(kind.with_count(0)),
        _ => {
            let plain: Vec<String> =
                ParetoChoiceKind::ALL.iter().filter(|kind| **kind != ParetoChoiceKind::MeanOfBest).map(|kind| cli_name(*kind)).collect();
            Err(format!("{text:?} is not {} or {}:N (N at least 1)", plain.join(", "), cli_name(ParetoChoiceKind::MeanOfBest)))
        }
    }
}

/// "reference:N", "polynomial:D" or "spline:MM" as the profile criterion's form.
fn parse_profile_method(text: &str) -> Result<ProfileMethod, String> {
    let wrong = || {
        let forms: Vec<String> = ProfileMethodKind::ALL.iter().map(|kind| profile_method_form(*kind)).collect();
        format!("{text:?} is not {}", or_list(&forms))
    };
    let (name, parameter) = text.split_once(':').ok_or_else(wrong)?;
    let whole = || parameter.parse::<usize>().map_err(|_| format!("{text:?}: {parameter:?} is not a whole number"));
    let kind = ProfileMethodKind::ALL.iter().copied().find(|kind| cli_name(*kind) == name).ok_or_else(wrong)?;
    let method = match kind {
        ProfileMethodKind::Reference => ProfileMethod::ReferenceProfile { vertical_sections: whole()? },
        ProfileMethodKind::Polynomial => ProfileMethod::Polynomial { degree: whole()? },
        ProfileMethodKind::Spline => ProfileMethod::Spline {
            knot_spacing_mm: parameter.parse().map_err(|_| format!("{text:?}: {parameter:?} is not a number of millimetres"))?,
        },
    };
    method.validated().map_err(|e| format!("{text:?}: {e}"))
}

/// How `--profile-method` writes a form and its parameter: "reference:N (vertical sections)".
fn profile_method_form(kind: ProfileMethodKind) -> String {
    let parameter = match kind {
        ProfileMethodKind::Reference => "N (vertical sections)",
        ProfileMethodKind::Polynomial => "D (degree)",
        ProfileMethodKind::Spline => "MM (knot spacing)",
    };
    format!("{}:{parameter}", cli_name(kind))
}

/// The library's default profile form as `--profile-method` writes it ("spline:1.5").
fn profile_method_text(method: ProfileMethod) -> String {
    match method {
        ProfileMethod::ReferenceProfile { vertical_sections } => format!("{}:{vertical_sections}", cli_name(ProfileMethodKind::Reference)),
        ProfileMethod::Polynomial { degree } => format!("{}:{degree}", cli_name(ProfileMethodKind::Polynomial)),
        ProfileMethod::Spline { knot_spacing_mm } => format!("{}:{knot_spacing_mm}", cli_name(ProfileMethodKind::Spline)),
    }
}

/// "POINTS,DEG" as the Pareto criterion's section limits (fewest points, smallest arc).
fn parse_section_limits(text: &str) -> Result<(usize, f64), String> {
    let wrong = || format!("{text:?} is not POINTS,DEG (at least 3 points, an arc of 0 to 360 degrees)");
    let (points, degrees) = text.split_once(',').ok_or_else(wrong)?;
    let (Ok(points), Ok(degrees)) = (points.trim().parse::<usize>(), degrees.trim().parse::<f64>()) else {
        return Err(wrong());
    };
    let limits = ParetoOptions { min_section_points: points, min_sector_angle_deg: degrees, ..Default::default() };
    limits.validated().map(|_| (points, degrees)).map_err(|e| format!("{text:?}: {e}"))
}

/// A finite positive number of millimetres.
fn parse_positive_mm(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(value) if value.is_finite() && value > 0.0 => Ok(value),
        _ => Err(format!("{text:?} is not a positive number of millimetres")),
    }
}

/// How a scan is oriented and measured.
#[derive(Args, Debug, Clone)]
pub struct AnalysisArgs {
    /// Manual pre-orientation from three points on one horizontal feature (rim, rill,
    /// decoration line), in the scan's units: "x,y,z;x,y,z;x,y,z".
    #[arg(long, value_name = "x,y,z;x,y,z;x,y,z")]
    pub manual: Option<String>,
    /// Refinement criterion after pre-orientation.
    #[arg(long, value_parser = RefineChoice::choices(), default_value = cli_name(Criterion::default()))]
    pub refine: RefineChoice,
    /// Skins the refinement uses.
    #[arg(long, value_parser = Choices::of(no_help, |surface: Surface| surface), default_value = cli_name(Surface::default()))]
    pub surface: Surface,
    /// Which solution of the Pareto front becomes the axis (--refine pareto): knee (the
    /// smallest product of the two costs), centres (Eq. 3 alone), residuals (Eq. 4 alone),
    /// or mean-of-best:N (the mean of the N best; the original tool takes 2).
    #[arg(long, value_name = "CHOICE", default_value = pareto_choice_text(ParetoOptions::default().choice), value_parser = parse_pareto_choice)]
    pub pareto_choice: ParetoChoice,
    /// The tangent plane's tolerance epsilon (Eq. 7), mm: a vertical section whose extreme
    /// lies farther below the rim's highest point (above the base's lowest) is taken for
    /// damaged and left out.
    #[arg(long, value_name = "MM", default_value = "3", value_parser = parse_positive_mm)]
    pub tangent_tolerance: f64,
    /// The edge the tangent plane rests on (--refine tangent or auto).
    #[arg(long, value_parser = Choices::of(edge_help, |edge: EdgeChoice| edge), default_value = cli_name(EdgeChoice::default()))]
    pub edge: EdgeChoice,
    /// The profile criterion's form (--refine profile): reference:N (Eq. 5, N vertical
    /// sections), polynomial:D (Eq. 6, degree D) or spline:MM (Eq. 6 as a cubic spline,
    /// knots MM apart).
    #[arg(long, value_name = "FORM", default_value = profile_method_text(ProfileMethod::default()), value_parser = parse_profile_method)]
    pub profile_method: ProfileMethod,
    /// The circle fit of each horizontal section in the Pareto criterion.
    #[arg(long, value_parser = Choices::of(circle_fit_help, |fit: CircleFitMethod| fit), default_value = cli_name(ParetoOptions::default().circle_fit))]
    pub circle_fit: CircleFitMethod,
    /// The Pareto criterion's limits per horizontal section: fewer points or a smaller arc
    /// (degrees) and the section is left out.
    #[arg(long, value_name = "POINTS,DEG", default_value = "10,3", value_parser = parse_section_limits)]
    pub pareto_section_limits: (usize, f64),
    /// Units of the scan. Without it, the unit a comment of the file declares ("comment
    /// units cm" in a PLY header, "# units cm" in an OBJ), else millimetres (what
    /// scanners mostly write). Given, it overrides the file.
    #[arg(long, value_enum)]
    pub units: Option<Units>,
}

impl AnalysisArgs {
    /// The library's options for these arguments.
    pub fn pipeline_options(&self) -> Result<PipelineOptions, String> {
        // 0: the file's declared unit, else millimetres (see `PipelineOptions`).
        let millimetres_per_unit = self.units.map_or(0.0, Units::millimetres);
        let mut options = PipelineOptions { millimetres_per_unit, ..Default::default() };
        if let Some(text) = &self.manual {
            options.manual_points = Some(parse_three_points(text)?);
        }
        options.refine = self.refine.0.map(|criterion| {
            let defaults = RefineOptions::default();
            RefineOptions {
                criterion,
                surface: self.surface,
                pareto: ParetoOptions {
                    choice: self.pareto_choice,
                    circle_fit: self.circle_fit,
                    min_section_points: self.pareto_section_limits.0,
                    min_sector_angle_deg: self.pareto_section_limits.1,
                    ..defaults.pareto
                },
                profile_method: self.profile_method,
                tangent_tolerance_mm: self.tangent_tolerance,
                edge: self.edge.edge(),
                ..defaults
            }
        });
        Ok(options)
    }
}

/// "x,y,z;x,y,z;x,y,z" as three points.
pub fn parse_three_points(text: &str) -> Result<[Point; 3], String> {
    let points: Vec<&str> = text.split(';').map(str::trim).filter(|p| !p.is_empty()).collect();
    if points.len() != 3 {
        return Err(format!("--manual needs three points \"x,y,z;x,y,z;x,y,z\", got {} in {text:?}", points.len()));
    }
    let mut parsed = [Point::origin(); 3];
    for (i, point) in points.iter().enumerate() {
        let coordinates: Result<Vec<f64>, _> = point.split(',').map(|c| c.trim().parse::<f64>()).collect();
        match coordinates {
            Ok(c) if c.len() == 3 && c.iter().all(|v| v.is_finite()) => parsed[i] = Point::new(c[0], c[1], c[2]),
            _ => return Err(format!("--manual: point {} ({point:?}) is not three finite numbers x,y,z", i + 1)),
        }
    }
    Ok(parsed)
}

/// An axis read from a file, with the scan it was found on when the file records it.
pub struct AxisFile {
    /// The axis, in millimetres.
    pub axis: Axis,
    /// The fingerprint of the scan the axis was found on (`"scan"` of `sherd orient
    /// --json`), when the file has one.
    pub scan: Option<ScanFingerprint>,
}

/// Reads an axis written by `sherd orient --json` (or any JSON object with `axis` or
/// `point` + `direction`), in the scan's units, and brings it to millimetres.
pub fn read_axis(path: &Path, millimetres_per_unit: f64) -> Result<AxisFile, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let value: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| format!("{}: not JSON: {e}", path.display()))?;
    let axis_value = value.get("axis").cloned().unwrap_or_else(|| value.clone());
    if axis_value.is_null() {
        let hint = if value.get("best_guess").is_some_and(|guess| !guess.is_null()) {
            "; to use its best guess (not trusted), save the \"best_guess\" object alone and give that"
        } else {
            ""
        };
        return Err(format!("{}: the axis is null (was the sherd oriented?){hint}", path.display()));
    }
    let record: AxisRecord = serde_json::from_value(axis_value)
        .map_err(|e| format!("{}: no axis {{\"point\": [x,y,z], \"direction\": [dx,dy,dz]}}: {e}", path.display()))?;
    let axis = Axis::from_record(&record)
        .ok_or_else(|| format!("{}: the axis direction is zero or not finite", path.display()))?;
    let scan = match value.get("scan") {
        None | Some(serde_json::Value::Null) => None,
        Some(scan) => Some(
            serde_json::from_value(scan.clone())
                .map_err(|e| format!("{}: \"scan\" is not {{\"vertices\", \"faces\", \"checksum\"}}: {e}", path.display()))?,
        ),
    };
    Ok(AxisFile { axis: Axis { point: Point::from(axis.point.coords * millimetres_per_unit), direction: axis.direction }, scan })
}

/// Farthest an axis may pass from the nearest point of its sherd, mm: the radius of the
/// largest vessels (storage jars reach 1.5 m across) with a wide margin.
const MAX_AXIS_DISTANCE_MM: f64 = 1500.0;

/// Refuses an axis found on another scan: its recorded fingerprint differs from `scan`'s,
/// or (with no fingerprint) it passes farther from every point than any vessel's radius.
fn check_axis_fits(axis_file: &Path, scan_file: &Path, read: &AxisFile, mesh: &sherd::mesh::Mesh, millimetres_per_unit: f64) -> Result<(), String> {
    if let Some(recorded) = &read.scan {
        if let Some(difference) = recorded.difference(&ScanFingerprint::of(mesh)) {
            return Err(format!(
                "{}: the axis was found on another scan than {} ({difference}); orient this scan, or give its own axis file",
                axis_file.display(),
                scan_file.display()
            ));
        }
    }
    let axis = &read.axis;
    let nearest = mesh
        .positions
        .iter()
        .map(|p| axis.distance_to(&Point::from(p.coords * millimetres_per_unit)))
        .fold(f64::INFINITY, f64::min);
    if nearest > MAX_AXIS_DISTANCE_MM {
        return Err(format!(
            "{}: the axis passes {:.0} mm from the nearest point of {}, farther than any vessel's radius ({MAX_AXIS_DISTANCE_MM:.0} mm): is it the axis of another scan, or in other units?",
            axis_file.display(),
            nearest,
            scan_file.display()
        ));
    }
    Ok(())
}

/// The help line of a placement in `--help`.
fn placement_help(placement: Placement) -> Option<&'static str> {
    Some(match placement {
        Placement::Beside => "Beside the axis, whatever the true radius (the paper's Fig. 4:a)",
        Placement::TrueDistance => "At the fragment's true distance from the axis (Fig. 4:b)",
    })
}

/// The help line of a section fill in `--help`.
fn section_fill_help(fill: SectionFill) -> Option<&'static str> {
    Some(match fill {
        SectionFill::Black => "Solid black, the usual convention for pottery",
        SectionFill::Hatched => "45-degree hatching",
    })
}

/// The help line of a regularity map in `--help`.
fn regularity_help(kind: RegularityKind) -> Option<&'static str> {
    Some(match kind {
        RegularityKind::AxisDistance => "Distance of each point to the axis",
        RegularityKind::IdealVessel => "Distance to the ideal vessel revolved from the section",
    })
}

/// A section angle in degrees: a finite number.
fn parse_degrees(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(value) if value.is_finite() => Ok(value),
        _ => Err(format!("{text:?} is not a finite number of degrees")),
    }
}

/// How a sherd is drawn: every layout choice of the library's `DrawOptions`, under the
/// names of the C ABI and Python (`section_fill`, `placement`, `interior_view`,
/// `prolongation`, `annotations`, `title`, `section_angle`, `regularity`), hyphenated.
#[derive(Args, Debug, Clone)]
pub struct DrawingArgs {
    /// Rendering styles, combinable: linear, colour, light, occlusion, stipple, regularity.
    /// The default is the library's, the C ABI's, Python's and the add-ons'.
    #[arg(long, default_value = Style::DEFAULT.to_string())]
    pub style: String,
    /// Publication scale: 1 for 1:1, 2 for 1:2, 3 for 1:3... (1 to 100).
    #[arg(long, default_value_t = 1)]
    pub scale: u32,
    /// Resolution of PNG output (and of raster styles inside vector files), dots per inch.
    #[arg(long, default_value_t = 300.0)]
    pub dpi: f64,
    /// Where the views stand: beside the axis, or turned about it to the fragment's true
    /// distance.
    #[arg(long, value_parser = Choices::of(placement_help, |placement: Placement| placement), default_value = cli_name(DrawOptions::default().placement))]
    pub placement: Placement,
    /// How the section is filled.
    #[arg(long, value_parser = Choices::of(section_fill_help, |fill: SectionFill| fill), default_value = cli_name(DrawOptions::default().section_fill))]
    pub section_fill: SectionFill,
    /// Draw the interior view between the section and the axis (true or false).
    #[arg(long, value_name = "BOOL", default_value_t = true, action = clap::ArgAction::Set)]
    pub interior_view: bool,
    /// Prolong the outer profile, dashed, to the full diameter (true or false).
    #[arg(long, value_name = "BOOL", default_value_t = true, action = clap::ArgAction::Set)]
    pub prolongation: bool,
    /// Measurements written under the drawing besides the diameters and the preserved
    /// share: a comma list of height, wall_thickness, capacity (or wall-thickness), or
    /// all, or none. Each is left out where it was not measured.
    #[arg(long, value_name = "LIST", default_value = "none")]
    pub annotations: String,
    /// A title above the drawing (inventory number...).
    #[arg(long, value_name = "TEXT")]
    pub title: Option<String>,
    /// The angle of the section about the axis, degrees from the fragment's centroid.
    /// Without it, the most informative profile is cut.
    #[arg(long, value_name = "DEG", allow_negative_numbers = true, value_parser = parse_degrees)]
    pub section_angle: Option<f64>,
    /// The map the regularity style shows.
    #[arg(long, value_parser = Choices::of(regularity_help, |kind: RegularityKind| kind), default_value = cli_name(DrawOptions::default().regularity))]
    pub regularity: RegularityKind,
}

impl DrawingArgs {
    /// The library's drawing options, checked.
    pub fn draw_options(&self) -> Result<DrawOptions, String> {
        let style = Style::parse(&self.style).map_err(|e| format!("--style: {e}"))?;
        let annotations = Annotations::parse(&self.annotations).map_err(|e| format!("--annotations: {e}"))?;
        let options = DrawOptions {
            style,
            scale_denominator: self.scale,
            dpi: self.dpi,
            placement: self.placement,
            section_fill: self.section_fill,
            interior_view: self.interior_view,
            prolongation: self.prolongation,
            annotations,
            title: self.title.clone(),
            section_angle_rad: self.section_angle.map(f64::to_radians),
            regularity: self.regularity,
            ..Default::default()
        };
        options.check().map_err(|e| e.to_string())?;
        Ok(options)
    }
}

/// A record as the few lines an archaeologist reads.
pub fn describe(record: &sherd::pipeline::SherdRecord) -> String {
    use std::fmt::Write;
    let mut text = String::new();
    let _ = writeln!(text, "{}: {}", record.file, record.status);
    if let Some(reason) = &record.reason {
        let _ = writeln!(text, "  reason: {reason}");
    }
    if let Some(axis) = &record.axis {
        let [x, y, z] = axis.point;
        let [dx, dy, dz] = axis.direction;
        let _ = writeln!(text, "  axis: through ({x:.3}, {y:.3}, {z:.3}) along ({dx:.5}, {dy:.5}, {dz:.5}), base to rim");
    }
    if let Some(method) = &record.method {
        let _ = writeln!(text, "  method: {method}");
    }
    let interval = |i: Option<[f64; 2]>| i.map(|[lo, hi]| format!(" ({lo:.0}-{hi:.0})")).unwrap_or_default();
    if let Some(d) = record.rim_diameter_mm {
        let _ = writeln!(text, "  rim diameter: {d:.0} mm{}", interval(record.rim_diameter_interval_mm));
    }
    if let Some(d) = record.base_diameter_mm {
        let _ = writeln!(text, "  base diameter: {d:.0} mm{}", interval(record.base_diameter_interval_mm));
    }
    // The rim's own arc (what a rim chart reads) beside the sherd's.
    let rim_arc = record.rim_sector_deg.map(|arc| format!("; rim arc: {arc:.1} deg ({:.1}% of the rim)", arc / 3.6));
    if let (Some(angle), Some(percent)) = (record.sector_angle_deg, record.sector_percent) {
        let _ = writeln!(text, "  preserved sector: {angle:.1} deg ({percent:.1}% of the circumference){}", rim_arc.unwrap_or_default());
    } else if let Some(arc) = rim_arc {
        let _ = writeln!(text, "  {}", arc.trim_start_matches("; "));
    }
    if let Some(h) = record.height_mm {
        let _ = writeln!(text, "  preserved height: {h:.1} mm");
    }
    if let Some(t) = record.wall_thickness_mm {
        let _ = writeln!(text, "  wall thickness: {t:.1} mm");
    }
    if let Some(c) = record.capacity_litres {
        let _ = writeln!(text, "  capacity: {c:.2} l");
    }
    // What could not be measured and why: a plate without a level rim gets no rim diameter.
    for note in &record.notes {
        let _ = writeln!(text, "  note: {note}");
    }
    if let Some([_, hi]) = record.axis_angle_interval_deg {
        let _ = writeln!(text, "  axis angle uncertainty: {hi:.2} deg (95%)");
    }
    if let Some([_, hi]) = record.axis_distance_interval_mm {
        let _ = writeln!(text, "  axis position uncertainty: {hi:.2} mm of mean point distance (95%)");
    }
    if let Some(r) = record.residual_mm {
        let _ = writeln!(text, "  residual: {r:.3} mm");
    }
    if let Some(rills) = &record.rills {
        let _ = writeln!(
            text,
            "  wheel rills: {} traced (longest {:.0} mm), sloping {:.1} deg (+-{:.1}) under this axis",
            rills.count, rills.longest_arc_mm, rills.slope_deg, rills.slope_spread_deg
        );
    }
    if let Some(points) = &record.manual_points_on_rill {
        let picks: Vec<String> = points.iter().map(|[x, y, z]| format!("{x:.3},{y:.3},{z:.3}")).collect();
        let _ = writeln!(text, "  three points on its longest wheel rill, for --manual: \"{}\"", picks.join(";"));
    }
    if let Some(guess) = &record.best_guess {
        let [x, y, z] = guess.axis.point;
        let [dx, dy, dz] = guess.axis.direction;
        let sense = if guess.sense_known { "base to rim" } else { "which way is up a guess too" };
        // The reason printed above is what speaks against the guess: said once.
        let against = if record.reason.as_ref() == Some(&guess.against) { "the reason above" } else { &guess.against };
        let _ = writeln!(
            text,
            "  best guess (not trusted): axis through ({x:.3}, {y:.3}, {z:.3}) along ({dx:.5}, {dy:.5}, {dz:.5}), {sense}; against it: {against}"
        );
        let _ = writeln!(
            text,
            "  to orient it, give three points on one horizontal feature (rim, rill, base edge) with --manual; \
             to use the guess as it is (not refined), save the \"best_guess\" object of --json and give it to draw or export with --axis"
        );
    }
    if let Some(drawing) = &record.drawing {
        let _ = writeln!(text, "  drawing: {drawing}");
    }
    text
}

/// A scan ready to draw or export: in millimetres, with its axis.
pub struct Oriented {
    pub mesh: sherd::mesh::Mesh,
    /// The axis, in millimetres.
    pub axis: Axis,
    /// What the pipeline found, when it oriented the scan (`None` with `--axis`).
    pub record: Option<sherd::pipeline::SherdRecord>,
    /// The pipeline's measurements (`None` with `--axis`): they label the drawing, which
    /// would otherwise measure the scan a second time.
    pub measurements: Option<sherd::profile::measure::Measurements>,
    /// Millimetres per unit of the scan file.
    pub millimetres_per_unit: f64,
}

impl Oriented {
    /// What `draw` and `export` print with `--json`: the pipeline's record (status, axis,
    /// measurements; or only the axis, in the scan's units, when it came from `axis_file`)
    /// and the files written.
    pub fn json(&self, scan: &Path, axis_file: Option<&Path>, written: &[&Path]) -> String {
        let mut value = match &self.record {
            Some(record) => serde_json::to_value(record).expect("a record always serialises"),
            None => {
                let in_scan_units = Axis { point: Point::from(self.axis.point.coords / self.millimetres_per_unit), ..self.axis };
                serde_json::json!({ "file": scan.display().to_string(), "status": RecordStatus::Ok, "axis": in_scan_units.record() })
            }
        };
        value["axis_file"] = serde_json::json!(axis_file.map(|path| path.display().to_string()));
        value["written"] = written.iter().map(|path| path.display().to_string()).collect();
        serde_json::to_string_pretty(&value).expect("plain data")
    }
}

/// The scan (in millimetres) and its axis: read from `axis_file` when given, else found by
/// the pipeline. A sherd the pipeline cannot orient is an error here: drawing or
/// exporting it along a wrong axis would mislead.
pub fn analyse_or_read_axis(scan: &Path, axis_file: Option<&Path>, analysis: &AnalysisArgs) -> Result<Oriented, String> {
    let (mesh, report) = sherd::mesh::io::read_mesh_with_report(scan).map_err(|e| e.to_string())?;
    let options = analysis.pipeline_options()?.with_declared_unit(report.declared_unit);
    let millimetres_per_unit = options.scale();
    match axis_file {
        Some(axis_file) => {
            let read = read_axis(axis_file, millimetres_per_unit)?;
            let mut mesh = mesh;
            mesh.validate().map_err(|e| format!("{}: {e}", scan.display()))?;
            check_axis_fits(axis_file, scan, &read, &mesh, millimetres_per_unit)?;
            let axis = read.axis;
            for p in &mut mesh.positions {
                p.coords *= millimetres_per_unit;
            }
            Ok(Oriented { mesh, axis, record: None, measurements: None, millimetres_per_unit })
        }
        None => {
            let result = sherd::pipeline::analyse(mesh, &options).map_err(|e| format!("{}: {e}", scan.display()))?;
            match &result.orientation.verdict {
                sherd::orient::Verdict::NeedsManualOrientation { reason } => {
                    return Err(format!(
                        "{}: needs manual orientation ({reason}); give three points with --manual or an axis with --axis",
                        scan.display()
                    ));
                }
                sherd::orient::Verdict::SenseUncertain { reason } => eprintln!(
                    "warning: {}: the sense of the axis is uncertain ({reason}); the result may be upside down: check it, or give an axis with --axis",
                    scan.display()
                ),
                sherd::orient::Verdict::Oriented => {}
            }
            let record = sherd::pipeline::SherdRecord::from_analysis(scan.display().to_string(), &result);
            if record.status == RecordStatus::AxisUncertain {
                eprintln!(
                    "warning: {}: the axis is not pinned down ({}); check it before using the figures, or give an axis with --axis",
                    scan.display(),
                    record.reason.as_deref().unwrap_or_default()
                );
            }
            let axis = *result.axis();
            Ok(Oriented { mesh: result.mesh, axis, record: Some(record), measurements: result.measurements, millimetres_per_unit })
        }
    }
}
