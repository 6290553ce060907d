//! Random vessel profiles: the mid-wall curve of a vessel in the rz-plane (r the distance
//! to the rotation axis, z the height above the standing plane, both in millimetres),
//! running from the centre of the base outwards and up to the rim, with a wall thickness.
//!
//! The curve is a uniform cubic B-spline through a control polygon drawn per vessel
//! family. A B-spline keeps the curvature bounded, so the two skins offset by half the
//! wall thickness on either side never fold; profiles whose tightest bend is sharper than
//! the wall allows are rejected and redrawn. The base is exactly flat (four collinear
//! control points give straight spans) and meets the axis at a right angle (the control
//! polygon is mirrored across the axis), as on a real thrown vessel.

use rand::Rng;
use serde::{Deserialize, Serialize};


/// The vessel families the generator draws from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum VesselShape {
    /// Open hemispherical to conical bowl (rim radius 60-200 mm).
    Bowl,
    /// Bowl with a sharp change of wall direction (carination) halfway up.
    CarinatedBowl,
    /// Closed jar: a body wider than the rim, a neck and a flaring rim.
    Jar,
    /// Low, wide plate or dish.
    Plate,
    /// Tall, slightly flaring beaker.
    Beaker,
    /// A jar whose body is a spherical zone: pieces from it determine no axis.
    Globular,
}

impl VesselShape {
    /// Every family, in a fixed order.
    pub const ALL: [VesselShape; 6] = [
        VesselShape::Bowl,
        VesselShape::CarinatedBowl,
        VesselShape::Jar,
        VesselShape::Plate,
        VesselShape::Beaker,
        VesselShape::Globular,
    ];

    /// The ordinary families (all but [`VesselShape::Globular`], whose body pieces are
    /// a hard case on purpose).
    pub const ORDINARY: [VesselShape; 5] = [
        VesselShape::Bowl,
        VesselShape::CarinatedBowl,
        VesselShape::Jar,
        VesselShape::Plate,
        VesselShape::Beaker,
    ];

    /// The lower-case name used on the command line and in JSON.
    pub fn name(self) -> &'static str {
        match self {
            VesselShape::Bowl => "bowl",
            VesselShape::CarinatedBowl => "carinated_bowl",
            VesselShape::Jar => "jar",
            VesselShape::Plate => "plate",
            VesselShape::Beaker => "beaker",
            VesselShape::Globular => "globular",
        }
    }

    /// A random ordinary family.
    pub fn random(rng: &mut impl Rng) -> Self {
        Self::ORDINARY[rng.random_range(0..Self::ORDINARY.len())]
    }
}

impl std::str::FromStr for VesselShape {
    type Err = crate::Error;

    fn from_str(text: &str) -> crate::Result<Self> {
        super::parse_name(text, &VesselShape::ALL, VesselShape::name, "vessel shape")
    }
}

/// How the wall ends at the rim.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RimForm {
    /// Cut square across the wall.
    Flat,
    /// Rounded: the skins close along a quarter-circle-like cap of radius half the wall
    /// thickness (up to 70 degrees, leaving a narrow flat top).
    Rounded,
    /// Rounded, with a bead outside: the outer skin swells just below the cap, so that the
    /// lip's outer edge, where a radius chart reads it, lies below its top.
    Thickened,
}

impl RimForm {
    /// Every lip form.
    pub const ALL: [RimForm; 3] = [RimForm::Flat, RimForm::Rounded, RimForm::Thickened];

    /// The lower-case name used on the command line and in JSON.
    pub fn name(self) -> &'static str {
        match self {
            RimForm::Flat => "flat",
            RimForm::Rounded => "rounded",
            RimForm::Thickened => "thickened",
        }
    }
}

impl std::str::FromStr for RimForm {
    type Err = crate::Error;

    fn from_str(text: &str) -> crate::Result<Self> {
        super::parse_name(text, &RimForm::ALL, RimForm::name, "lip form")
    }
}

/// How the base meets the ground.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BaseForm {
    /// The underside stands on the ground over its whole width.
    Flat,
    /// A ring foot: a ridge under the floor, inside the base's edge, on which the vessel
    /// stands; the floor's centre is raised off the ground by the ridge's height.
    RingFoot,
}

impl BaseForm {
    /// Every base form.
    pub const ALL: [BaseForm; 2] = [BaseForm::Flat, BaseForm::RingFoot];

    /// The lower-case name used on the command line and in JSON.
    pub fn name(self) -> &'static str {
        match self {
            BaseForm::Flat => "flat",
            BaseForm::RingFoot => "ring_foot",
        }
    }
}

impl std::str::FromStr for BaseForm {
    type Err = crate::Error;

    fn from_str(text: &str) -> crate::Result<Self> {
        super::parse_name(text, &BaseForm::ALL, BaseForm::name, "base form")
    }
}

/// The lip and base forms a random profile is drawn from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ProfileForms {
    /// Lip forms, drawn with equal chances (flat and rounded alone keep their 30/70 share).
    pub lips: Vec<RimForm>,
    /// Base forms, drawn with equal chances.
    pub bases: Vec<BaseForm>,
}

impl Default for ProfileForms {
    /// Flat and rounded lips on flat bases.
    fn default() -> Self {
        ProfileForms { lips: vec![RimForm::Flat, RimForm::Rounded], bases: vec![BaseForm::Flat] }
    }
}

impl ProfileForms {
    /// A lip form. The draw for the default pair is the one the generator has always
    /// made, so that the corpora of a seed stay the same files.
    fn draw_lip(&self, rng: &mut impl Rng) -> RimForm {
        match distinct(&self.lips, |form| form as u8).as_slice() {
            [] => RimForm::Rounded,
            [RimForm::Flat, RimForm::Rounded] => {
                if rng.random_bool(0.7) {
                    RimForm::Rounded
                } else {
                    RimForm::Flat
                }
            }
            several => draw_one(several, rng),
        }
    }

    /// A base form; no draw at all where only one is allowed.
    fn draw_base(&self, rng: &mut impl Rng) -> BaseForm {
        match distinct(&self.bases, |form| form as u8).as_slice() {
            [] => BaseForm::Flat,
            several => draw_one(several, rng),
        }
    }
}

/// The distinct forms of `forms` in their declared order, so that a draw does not hang on
/// how they were listed.
fn distinct<T: Copy>(forms: &[T], rank: fn(T) -> u8) -> Vec<T> {
    let mut forms = forms.to_vec();
    forms.sort_by_key(|&form| rank(form));
    forms.dedup_by_key(|form| rank(*form));
    forms
}

/// One of `forms` (not empty) with equal chances; the only one without a draw.
fn draw_one<T: Copy>(forms: &[T], rng: &mut impl Rng) -> T {
    match forms {
        [only] => *only,
        several => several[rng.random_range(0..several.len())],
    }
}

/// A swelling of the outer skin along the mid-wall curve (a lip's bead, a ring foot): a
/// plateau of `height_mm` over `plateau_half_mm` either side of `centre_s_mm`, falling to
/// nothing over `flank_mm` along a squared cosine, so that the skin stays smooth.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Swelling {
    centre_s_mm: f64,
    plateau_half_mm: f64,
    flank_mm: f64,
    height_mm: f64,
}

impl Swelling {
    fn at(&self, s_mm: f64) -> f64 {
        let beyond = (s_mm - self.centre_s_mm).abs() - self.plateau_half_mm;
        if beyond <= 0.0 {
            self.height_mm
        } else if beyond < self.flank_mm {
            self.height_mm * (0.5 * std::f64::consts::PI * beyond / self.flank_mm).cos().powi(2)
        } else {
            0.0
        }
    }

    fn support_s_mm(&self) -> [f64; 2] {
        let half = self.plateau_half_mm + self.flank_mm;
        [self.centre_s_mm - half, self.centre_s_mm + half]
    }
}

/// The angle up to which a rounded rim's cap turns before its narrow flat top, radians.
const ROUNDED_RIM_CAP_ANGLE_RAD: f64 = 70.0 * std::f64::consts::PI / 180.0;

/// A point of the mid-wall curve with its unit outward normal (both in the rz-plane).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProfileSample {
    /// Distance to the axis, mm.
    pub r_mm: f64,
    /// Height above the standing plane, mm.
    pub z_mm: f64,
    /// Radial component of the outward unit normal.
    pub normal_r: f64,
    /// Axial component of the outward unit normal.
    pub normal_z: f64,
}

/// A vessel's profile: the mid-wall curve sampled uniformly in arc length `s` (mm from
/// the centre of the base), and the wall thickness. The outer skin is the curve moved by
/// half the thickness along the outward normal, the inner skin by half against it.
#[derive(Clone, Debug)]
pub struct VesselProfile {
    /// The family it was drawn from.
    pub shape: VesselShape,
    /// Wall thickness, mm.
    pub wall_thickness_mm: f64,
    /// How the wall ends at the rim.
    pub rim_form: RimForm,
    /// How the base meets the ground.
    pub base_form: BaseForm,
    /// A thickened lip's bead: a swelling of the outer skin below the rounding.
    bead: Option<Swelling>,
    /// A ring foot's swelling of the outer skin under the floor.
    foot: Option<Swelling>,
    /// Height added to the whole curve so that a ring foot stands on the plane where the
    /// flat underside would, mm.
    lift_mm: f64,
    /// Arc length where the outer skin leaves the standing plane: the base's edge, or a
    /// ring foot's outer flank.
    standing_edge_s_mm: f64,
    step_mm: f64,
    points: Vec<[f64; 2]>,
    normals: Vec<[f64; 2]>,
    base_edge_s_mm: f64,
    spherical_band_s_mm: Option<[f64; 2]>,
}

/// Sampling step of the arc-length table, mm: fine enough that the chord error of the
/// linear interpolation (step^2 / 8 / bend radius) stays below a micrometre.
const TABLE_STEP_MM: f64 = 0.1;
/// Height above the standing plane at which the outer skin counts as having left the
/// base: the base radius is measured there.
const BASE_EDGE_RISE_MM: f64 = 1.0;
/// The tightest bend allowed, as a multiple of the wall thickness (an offset by half the
/// thickness folds at 0.5; the margin keeps the skins' triangles well shaped).
const MIN_BEND_RADIUS_PER_THICKNESS: f64 = 0.7;

impl VesselProfile {
    /// A random profile of `shape`, with realistic proportions (rim radius 60-200 mm,
    /// wall 4-10 mm), its lip and base drawn from `forms`.
    pub fn random(shape: VesselShape, forms: &ProfileForms, rng: &mut impl Rng) -> Self {
        loop {
            let (control, thickness) = control_polygon(shape, rng);
            let Some(profile) = Self::from_control_polygon(shape, &control, thickness) else {
                continue;
            };
            let profile = match forms.draw_lip(rng) {
                RimForm::Thickened => {
                    let (height, width) = (thickness * uniform(rng, 0.4, 0.7), thickness * uniform(rng, 1.2, 2.0));
                    profile.with_thickened_lip(height, width)
                }
                form => profile.with_rim_form(form),
            };
            let profile = match forms.draw_base(rng) {
                BaseForm::RingFoot => {
                    let fraction = uniform(rng, 0.55, 1.0);
                    let (height, width) = (uniform(rng, 3.0, 7.0), thickness * uniform(rng, 1.5, 2.5));
                    match profile.with_ring_foot(fraction, height, width) {
                        Some(footed) => footed,
                        None => continue,
                    }
                }
                BaseForm::Flat => profile,
            };
            return profile;
        }
    }

    /// The profile of the uniform cubic B-spline of `control` (mid-wall points from the
    /// centre of the base, `control[0]` on the axis, to the rim), or `None` when the curve
    /// bends tighter than the wall thickness allows or the inner skin crosses the axis.
    pub fn from_control_polygon(shape: VesselShape, control: &[[f64; 2]], wall_thickness_mm: f64) -> Option<Self> {
        if control.len() < 3 || control[0][0] != 0.0 {
            return None;
        }
        let n = control.len();
        let mut extended = Vec::with_capacity(n + 2);
        // Mirroring the second point across the axis makes the curve start on the axis,
        // perpendicular to it; reflecting the last-but-one through the last makes it end
        // exactly at the rim point.
        extended.push([-control[1][0], control[1][1]]);
        extended.extend_from_slice(control);
        extended.push([2.0 * control[n - 1][0] - control[n - 2][0], 2.0 * control[n - 1][1] - control[n - 2][1]]);

        let max_curvature = 1.0 / (MIN_BEND_RADIUS_PER_THICKNESS * wall_thickness_mm);
        let samples_per_span = 256;
        let mut dense_points: Vec<[f64; 2]> = Vec::new();
        let mut dense_tangents: Vec<[f64; 2]> = Vec::new();
        for span in extended.windows(4) {
            let first = if dense_points.is_empty() { 0 } else { 1 };
            for k in first..=samples_per_span {
                let t = k as f64 / samples_per_span as f64;
                let (point, first_derivative, second_derivative) = bspline_span(span, t);
                let speed = first_derivative[0].hypot(first_derivative[1]);
                if speed < 1e-9 {
                    return None;
                }
                let curvature = (first_derivative[0] * second_derivative[1] - first_derivative[1] * second_derivative[0])
                    / speed.powi(3);
                if curvature.abs() > max_curvature {
                    return None;
                }
                dense_points.push(point);
                dense_tangents.push([first_derivative[0] / speed, first_derivative[1] / speed]);
            }
        }

        let mut arc_length = vec![0.0; dense_points.len()];
        for i in 1..dense_points.len() {
            let (a, b) = (dense_points[i - 1], dense_points[i]);
            arc_length[i] = arc_length[i - 1] + (b[0] - a[0]).hypot(b[1] - a[1]);
        }
        let total = *arc_length.last()?;
        let count = (total / TABLE_STEP_MM).ceil() as usize + 1;
        let step_mm = total / (count - 1) as f64;
        let mut points = Vec::with_capacity(count);
        let mut normals = Vec::with_capacity(count);
        let mut segment = 0;
        for k in 0..count {
            let s = (k as f64 * step_mm).min(total);
            while segment + 2 < dense_points.len() && arc_length[segment + 1] < s {
                segment += 1;
            }
            let length = arc_length[segment + 1] - arc_length[segment];
            let w = if length > 0.0 { ((s - arc_length[segment]) / length).clamp(0.0, 1.0) } else { 0.0 };
            let lerp = |a: [f64; 2], b: [f64; 2]| [a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1])];
            let point = lerp(dense_points[segment], dense_points[segment + 1]);
            let tangent = lerp(dense_tangents[segment], dense_tangents[segment + 1]);
            let norm = tangent[0].hypot(tangent[1]);
            // Outward normal: the tangent turned clockwise (down on the base, out on the wall).
            normals.push([tangent[1] / norm, -tangent[0] / norm]);
            points.push(point);
        }
        points[0][0] = 0.0;

        let mut profile = VesselProfile {
            shape,
            wall_thickness_mm,
            rim_form: RimForm::Flat,
            base_form: BaseForm::Flat,
            bead: None,
            foot: None,
            lift_mm: 0.0,
            standing_edge_s_mm: 0.0,
            step_mm,
            points,
            normals,
            base_edge_s_mm: 0.0,
            spherical_band_s_mm: None,
        };
        let half = 0.5 * wall_thickness_mm;
        let base_z = profile.outer_at(0.0)[1];
        let base_edge_index = (0..count).find(|&k| {
            let s = k as f64 * step_mm;
            profile.outer_at(s)[1] > base_z + BASE_EDGE_RISE_MM
        })?;
        profile.base_edge_s_mm = base_edge_index as f64 * step_mm;
        profile.standing_edge_s_mm = profile.base_edge_s_mm;
        // The inner skin must stay off the axis except at the base centre.
        let inner_crosses_axis = (0..count).any(|k| {
            let s = k as f64 * step_mm;
            s > half && profile.inner_at(s)[0] <= 0.0
        });
        if inner_crosses_axis || profile.base_edge_s_mm < 2.0 * wall_thickness_mm {
            return None;
        }
        profile.spherical_band_s_mm = find_spherical_band(&profile, 0.05);
        Some(profile)
    }

    /// Arc length of the mid-wall curve from the base centre to the rim, mm.
    pub fn length_mm(&self) -> f64 {
        (self.points.len() - 1) as f64 * self.step_mm
    }

    /// The mid-wall point and outward normal at arc length `s_mm` (clamped to the curve).
    pub fn sample(&self, s_mm: f64) -> ProfileSample {
        let position = (s_mm / self.step_mm).clamp(0.0, (self.points.len() - 1) as f64);
        let index = (position.floor() as usize).min(self.points.len() - 2);
        let w = position - index as f64;
        let (a, b) = (self.points[index], self.points[index + 1]);
        let (na, nb) = (self.normals[index], self.normals[index + 1]);
        let normal = [na[0] + w * (nb[0] - na[0]), na[1] + w * (nb[1] - na[1])];
        let norm = normal[0].hypot(normal[1]);
        ProfileSample {
            r_mm: (a[0] + w * (b[0] - a[0])).max(0.0),
            z_mm: a[1] + w * (b[1] - a[1]) + self.lift_mm,
            normal_r: normal[0] / norm,
            normal_z: normal[1] / norm,
        }
    }

    /// The same profile ending in a rim of `form` (a thickened lip's bead 0.55 wall
    /// thicknesses out and 1.6 tall).
    pub fn with_rim_form(self, form: RimForm) -> Self {
        match form {
            RimForm::Thickened => {
                let thickness = self.wall_thickness_mm;
                self.with_thickened_lip(0.55 * thickness, 1.6 * thickness)
            }
            _ => VesselProfile { rim_form: form, ..self },
        }
    }

    /// The same profile ending in a rounded lip with a bead outside, `height_mm` out from
    /// the skin and `width_mm` tall along the wall (its widest part half of that), centred a
    /// quarter of its width below the rounding. Where the wall bends too tightly under the bead for the
    /// outer skin to stay unfolded, the lip is left rounded.
    pub fn with_thickened_lip(self, height_mm: f64, width_mm: f64) -> Self {
        let mut profile = VesselProfile { rim_form: RimForm::Thickened, ..self };
        let flank = 0.5 * width_mm;
        let bead = Swelling { centre_s_mm: profile.rim_cap_start_s_mm() - 0.25 * width_mm, plateau_half_mm: 0.5 * flank, flank_mm: 0.5 * flank, height_mm };
        let reach = 0.5 * profile.wall_thickness_mm + height_mm;
        if profile.tightest_bend_radius_mm(bead.support_s_mm()) < reach * MIN_BEND_RADIUS_PER_THICKNESS / 0.5 {
            profile.rim_form = RimForm::Rounded;
            return profile;
        }
        profile.bead = Some(bead);
        profile
    }

    /// The same profile standing on a ring foot under the floor: a ridge `height_mm` high
    /// and `width_mm` wide at its foot (its flat bottom half of that), whose centre
    /// lies at `radius_fraction` of the base's radius, or, where the ridge would reach past
    /// the flat floor, as far out as the floor allows (a foot under the wall). `None` where
    /// the floor is too small to hold it.
    pub fn with_ring_foot(self, radius_fraction: f64, height_mm: f64, width_mm: f64) -> Option<Self> {
        let ring_radius = radius_fraction * self.base_radius_mm();
        let on_floor = |s: f64| self.sample(s).normal_z < -0.999;
        let arc_lengths = || (0..self.points.len()).map(|k| k as f64 * self.step_mm);
        let floor_end = arc_lengths().take_while(|&s| on_floor(s)).last()?;
        let wanted_centre = arc_lengths().find(|&s| self.sample(s).r_mm >= ring_radius)?;
        // A foot that would reach past the flat floor stands under the wall instead, its
        // outer flank running into the wall's foot.
        let half_support = 0.5 * width_mm;
        let centre = wanted_centre.min(floor_end - half_support);
        let foot = Swelling { centre_s_mm: centre, plateau_half_mm: width_mm / 4.0, flank_mm: width_mm / 4.0, height_mm };
        if foot.support_s_mm()[0] <= 0.0 {
            return None;
        }
        let mut profile = VesselProfile { base_form: BaseForm::RingFoot, lift_mm: self.lift_mm + height_mm, ..self };
        profile.foot = Some(foot);
        // The vessel stands on the ridge: its base radius is where the outer skin, beyond
        // the ridge's lowest point, has risen above the ground.
        let standing = profile.outer_at(centre)[1];
        let risen = |s: f64| profile.outer_at(s)[1] > standing + BASE_EDGE_RISE_MM;
        let leaves = (0..profile.points.len()).map(|k| k as f64 * profile.step_mm).find(|&s| s > centre && risen(s))?;
        // The flank rises steeply over a table step: bisect to the rise itself.
        let (mut below, mut above) = (leaves - profile.step_mm, leaves);
        for _ in 0..30 {
            let middle = 0.5 * (below + above);
            if risen(middle) {
                above = middle;
            } else {
                below = middle;
            }
        }
        profile.standing_edge_s_mm = above;
        Some(profile)
    }

    /// The tightest bend radius of the mid-wall curve over `range` of arc length, mm.
    fn tightest_bend_radius_mm(&self, [from, to]: [f64; 2]) -> f64 {
        let first = ((from / self.step_mm).floor().max(0.0) as usize).min(self.normals.len() - 1);
        let last = ((to / self.step_mm).ceil().max(0.0) as usize).min(self.normals.len() - 1);
        (first..last)
            .map(|k| {
                let (a, b) = (self.normals[k], self.normals[k + 1]);
                let turn = (a[0] * b[1] - a[1] * b[0]).abs().max(1e-12);
                self.step_mm / turn
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// Arc length (mid-wall) where the rim's rounding starts; the rim's end for a flat rim.
    pub fn rim_cap_start_s_mm(&self) -> f64 {
        match self.rim_form {
            RimForm::Flat => self.length_mm(),
            RimForm::Rounded | RimForm::Thickened => self.length_mm() - 0.5 * self.wall_thickness_mm * ROUNDED_RIM_CAP_ANGLE_RAD.sin(),
        }
    }

    /// Half the wall thickness at arc length `s_mm`: constant, except over a rounded
    /// rim's cap, where the skins follow a circle of radius half the thickness.
    pub fn half_thickness_mm(&self, s_mm: f64) -> f64 {
        let half = 0.5 * self.wall_thickness_mm;
        let into_cap = s_mm - self.rim_cap_start_s_mm();
        if into_cap <= 0.0 {
            return half;
        }
        let sine = (into_cap / half).min(ROUNDED_RIM_CAP_ANGLE_RAD.sin());
        half * (1.0 - sine * sine).sqrt()
    }

    /// The point of the skin on side `side` (+1 outer, -1 inner) at arc length `s_mm`.
    pub fn skin_at(&self, s_mm: f64, side: f64) -> [f64; 2] {
        let sample = self.sample(s_mm);
        let swelling = if side > 0.0 { [self.bead, self.foot].iter().flatten().map(|w| w.at(s_mm)).sum() } else { 0.0 };
        let offset = side * self.half_thickness_mm(s_mm) + swelling;
        [(sample.r_mm + offset * sample.normal_r).max(0.0), sample.z_mm + offset * sample.normal_z]
    }

    /// The outer skin's `(r, z)` at arc length `s_mm` of the mid-wall curve.
    pub fn outer_at(&self, s_mm: f64) -> [f64; 2] {
        self.skin_at(s_mm, 1.0)
    }

    /// The inner skin's `(r, z)` at arc length `s_mm` of the mid-wall curve.
    pub fn inner_at(&self, s_mm: f64) -> [f64; 2] {
        self.skin_at(s_mm, -1.0)
    }

    /// The skin `side` (+1 outer, -1 inner) as a polyline from the base centre to the rim,
    /// points at most `step_mm` apart along the mid-wall curve and close enough on bends
    /// that the polyline stays within a micrometre of the skin.
    pub fn skin_polyline(&self, side: f64, step_mm: f64) -> Vec<[f64; 2]> {
        // Dense samples (finer over a rounded rim's cap, which bends far more tightly than
        // the wall), then a greedy simplification keeping the chord error under 1 um.
        let cap_start = self.rim_cap_start_s_mm();
        let mut dense: Vec<([f64; 2], f64)> = Vec::new();
        let mut push_range = |from: f64, to: f64, step: f64| {
            let count = ((to - from) / step).ceil().max(1.0) as usize;
            let first = if dense.is_empty() { 0 } else { 1 };
            for k in first..=count {
                let s = from + (to - from) * k as f64 / count as f64;
                dense.push((self.skin_at(s, side), s));
            }
        };
        push_range(0.0, cap_start, 0.05);
        if self.length_mm() > cap_start {
            push_range(cap_start, self.length_mm(), 0.005);
        }
        const TOLERANCE_MM: f64 = 1e-3;
        let mut polyline = vec![dense[0].0];
        let mut start = 0;
        while start + 1 < dense.len() {
            let mut end = start + 1;
            while end + 1 < dense.len() && dense[end + 1].1 - dense[start].1 <= step_mm {
                let candidate = end + 1;
                let chord = [dense[start].0, dense[candidate].0];
                let fits = (start + 1..candidate).all(|k| distance_to_polyline(dense[k].0, &chord) <= TOLERANCE_MM);
                if !fits {
                    break;
                }
                end = candidate;
            }
            polyline.push(dense[end].0);
            start = end;
        }
        polyline
    }

    /// Arc length (mid-wall) where the underside turns into the wall: where the outer skin
    /// of the floor rises 1 mm (`BASE_EDGE_RISE_MM`) above its flat part. The end of the
    /// base; on a ring-footed vessel, beyond the foot.
    pub fn base_edge_s_mm(&self) -> f64 {
        self.base_edge_s_mm
    }

    /// Radius of the base as a radius chart reads it: the outer skin's radius where it
    /// leaves the standing plane (rises 1 mm above it), at the base's edge or a ring foot's
    /// outer flank, mm.
    pub fn base_radius_mm(&self) -> f64 {
        self.outer_at(self.standing_edge_s_mm)[0]
    }

    /// Radius of the rim: the outer skin's radius at the lip's outer edge, where a radius
    /// chart reads it (where a rounded rim's rounding starts; a thickened lip's widest
    /// point), mm.
    pub fn rim_radius_mm(&self) -> f64 {
        let at_cap = self.outer_at(self.rim_cap_start_s_mm())[0];
        let Some(bead) = self.bead else {
            return at_cap;
        };
        let from = bead.support_s_mm()[0].min(self.length_mm());
        let count = ((self.length_mm() - from) / (0.1 * self.step_mm)).ceil() as usize;
        (0..=count).map(|k| self.outer_at(from + (self.length_mm() - from) * k as f64 / count.max(1) as f64)[0]).fold(at_cap, f64::max)
    }

    /// Height of the vessel: the highest point of either skin above the standing plane, mm.
    pub fn height_mm(&self) -> f64 {
        [1.0, -1.0]
            .iter()
            .flat_map(|&side| self.skin_polyline(side, 1.0))
            .map(|p| p[1])
            .fold(f64::MIN, f64::max)
    }

    /// Largest radius of the outer skin, mm.
    pub fn max_radius_mm(&self) -> f64 {
        (0..self.points.len()).map(|k| self.outer_at(k as f64 * self.step_mm)[0]).fold(0.0, f64::max)
    }

    /// For a [`VesselShape::Globular`] vessel, the arc-length interval (mid-wall, mm) over
    /// which the wall is a spherical zone.
    pub fn spherical_band_s_mm(&self) -> Option<[f64; 2]> {
        self.spherical_band_s_mm
    }

    /// The mid-wall radius at arc length `s_mm`.
    pub fn mid_radius_mm(&self, s_mm: f64) -> f64 {
        self.sample(s_mm).r_mm
    }
}

/// Point, first and second derivative of a uniform cubic B-spline span at `t` in [0, 1].
fn bspline_span(p: &[[f64; 2]], t: f64) -> ([f64; 2], [f64; 2], [f64; 2]) {
    let u = 1.0 - t;
    let position_weights = [u * u * u / 6.0, (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0, (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0, t * t * t / 6.0];
    let first_weights = [-0.5 * u * u, 0.5 * (3.0 * t * t - 4.0 * t), 0.5 * (-3.0 * t * t + 2.0 * t + 1.0), 0.5 * t * t];
    let second_weights = [u, 3.0 * t - 2.0, 1.0 - 3.0 * t, t];
    let combine = |w: [f64; 4]| {
        [
            w[0] * p[0][0] + w[1] * p[1][0] + w[2] * p[2][0] + w[3] * p[3][0],
            w[0] * p[0][1] + w[1] * p[1][1] + w[2] * p[2][1] + w[3] * p[3][1],
        ]
    };
    (combine(position_weights), combine(first_weights), combine(second_weights))
}

fn uniform(rng: &mut impl Rng, low: f64, high: f64) -> f64 {
    rng.random_range(low..high)
}

/// A random control polygon of the mid-wall curve for `shape`, and the wall thickness.
fn control_polygon(shape: VesselShape, rng: &mut impl Rng) -> (Vec<[f64; 2]>, f64) {
    let wall: Vec<[f64; 2]>;
    let base_radius: f64;
    let thickness: f64;
    match shape {
        VesselShape::Bowl => {
            let rim = uniform(rng, 60.0, 200.0);
            let height = rim * uniform(rng, 0.35, 0.75);
            base_radius = rim * uniform(rng, 0.3, 0.5);
            thickness = (rim * uniform(rng, 0.03, 0.055)).clamp(4.0, 10.0);
            let bulge = uniform(rng, 0.5, 0.7);
            wall = vec![
                [base_radius + bulge * (rim - base_radius), height * uniform(rng, 0.12, 0.22)],
                [rim * uniform(rng, 0.92, 0.98), height * uniform(rng, 0.5, 0.62)],
                [rim, height],
            ];
        }
        VesselShape::CarinatedBowl => {
            let rim = uniform(rng, 60.0, 180.0);
            let height = rim * uniform(rng, 0.45, 0.8);
            base_radius = rim * uniform(rng, 0.3, 0.45);
            thickness = (rim * uniform(rng, 0.03, 0.05)).clamp(4.0, 10.0);
            let carination = [rim * uniform(rng, 1.04, 1.15), height * uniform(rng, 0.4, 0.6)];
            wall = vec![
                [base_radius + 0.55 * (carination[0] - base_radius), carination[1] * 0.35],
                carination,
                carination,
                [rim * uniform(rng, 0.97, 1.01), height * uniform(rng, 0.8, 0.88)],
                [rim, height],
            ];
        }
        VesselShape::Jar => {
            let rim = uniform(rng, 60.0, 120.0);
            let belly = rim * uniform(rng, 1.3, 1.7);
            let height = belly * uniform(rng, 1.3, 2.0);
            base_radius = belly * uniform(rng, 0.45, 0.65);
            thickness = (rim * uniform(rng, 0.05, 0.08)).clamp(4.0, 10.0);
            let neck = rim * uniform(rng, 0.85, 0.93);
            wall = vec![
                [belly * 0.9, height * 0.18],
                [belly, height * uniform(rng, 0.4, 0.5)],
                [belly * 0.9, height * 0.68],
                [neck, height * 0.84],
                [neck, height * 0.92],
                [rim, height],
            ];
        }
        VesselShape::Plate => {
            let rim = uniform(rng, 100.0, 200.0);
            let height = (rim * uniform(rng, 0.12, 0.2)).max(25.0);
            base_radius = rim * uniform(rng, 0.5, 0.7);
            thickness = (rim * uniform(rng, 0.03, 0.045)).clamp(4.0, 10.0);
            wall = vec![[base_radius + 0.75 * (rim - base_radius), height * 0.45], [rim, height]];
        }
        VesselShape::Beaker => {
            let rim = uniform(rng, 60.0, 100.0);
            let height = rim * uniform(rng, 1.6, 2.6);
            base_radius = rim * uniform(rng, 0.55, 0.8);
            thickness = (rim * uniform(rng, 0.05, 0.08)).clamp(4.0, 10.0);
            wall = vec![
                [base_radius * 1.08, height * 0.2],
                [rim * uniform(rng, 0.86, 0.94), height * 0.6],
                [rim, height],
            ];
        }
        VesselShape::Globular => {
            let sphere_radius = uniform(rng, 100.0, 190.0);
            base_radius = sphere_radius * uniform(rng, 0.3, 0.42);
            thickness = (sphere_radius * uniform(rng, 0.03, 0.05)).clamp(4.0, 10.0);
            let neck = (sphere_radius * uniform(rng, 0.5, 0.65)).max(60.0);
            let rim = neck * 1.08;
            let z0 = 0.5 * thickness;
            let start_angle = (base_radius / sphere_radius).asin();
            let centre_z = z0 + sphere_radius * start_angle.cos();
            let end_angle = std::f64::consts::PI - (neck / sphere_radius).asin();
            let steps = ((end_angle - start_angle) * sphere_radius / 5.0).ceil() as usize;
            let mut points: Vec<[f64; 2]> = (1..=steps)
                .map(|k| {
                    let angle = start_angle + (end_angle - start_angle) * k as f64 / steps as f64;
                    [sphere_radius * angle.sin(), centre_z - sphere_radius * angle.cos()]
                })
                .collect();
            let top = points.last().expect("at least one arc point")[1];
            let neck_height = uniform(rng, 15.0, 30.0);
            points.push([neck, top + 0.5 * neck_height]);
            points.push([rim, top + neck_height]);
            wall = points;
        }
    }
    let z0 = 0.5 * thickness;
    // Straight, flat base: four collinear control points end the flat part `step` before
    // the base radius, where the B-spline starts to turn into the wall.
    let step = (base_radius / 4.0).min(6.0);
    let mut control = vec![[0.0, z0], [base_radius - 2.0 * step, z0], [base_radius - step, z0], [base_radius, z0]];
    control.extend(wall.iter().map(|p| [p[0], p[1].max(z0 + 1.0)]));
    (control, thickness)
}

/// The spherical zone of a globular profile: the longest run of arc length over which the
/// mid-wall curve lies within `tolerance_mm` of a sphere centred on the axis, found by
/// fitting the circle through three points of the run.
pub(crate) fn find_spherical_band(profile: &VesselProfile, tolerance_mm: f64) -> Option<[f64; 2]> {
    if profile.shape != VesselShape::Globular {
        return None;
    }
    // The circle is centred on the axis: r^2 + (z - c)^2 = R^2. Estimate c and R from two
    // mid-height samples of the body (whose wall is the arc by construction).
    let length = profile.length_mm();
    let a = profile.sample(0.45 * length);
    let b = profile.sample(0.6 * length);
    // r_a^2 + z_a^2 - 2 c z_a = r_b^2 + z_b^2 - 2 c z_b
    let denominator = 2.0 * (a.z_mm - b.z_mm);
    if denominator.abs() < 1e-9 {
        return None;
    }
    let centre = (a.r_mm.powi(2) + a.z_mm.powi(2) - b.r_mm.powi(2) - b.z_mm.powi(2)) / denominator;
    let radius = a.r_mm.hypot(a.z_mm - centre);
    let on_sphere = |s: f64| {
        let p = profile.sample(s);
        (p.r_mm.hypot(p.z_mm - centre) - radius).abs() <= tolerance_mm
    };
    let step = 0.5;
    let count = (length / step) as usize;
    let (mut best, mut run_start): (Option<[f64; 2]>, Option<f64>) = (None, None);
    for k in 0..=count {
        let s = k as f64 * step;
        if on_sphere(s) {
            run_start.get_or_insert(s);
        }
        if !on_sphere(s) || k == count {
            if let Some(start) = run_start.take() {
                let end = if on_sphere(s) { s } else { s - step };
                if best.is_none_or(|b| end - start > b[1] - b[0]) {
                    best = Some([start, end]);
                }
            }
        }
    }
    best
}

/// Distance (mm) from `point` (`[r, z]`) to a polyline in the rz-plane.
pub fn distance_to_polyline(point: [f64; 2], polyline: &[[f64; 2]]) -> f64 {
    polyline.windows(2).map(|w| crate::mesh::segment_distance(point, w[0], w[1])).fold(f64::INFINITY, f64::min)
}
