//! The archaeological illustration (Wilczek et al. 2018, section 2.4): a small drawing
//! model built from an oriented sherd, its styles, and the SVG, EPS, PDF and PNG writers.
//!
//! ```no_run
//! # fn main() -> sherd::Result<()> {
//! use sherd::draw::{DrawOptions, Drawing, Style};
//! # let mesh = sherd::mesh::Mesh::default();
//! # let axis = sherd::orient::Axis::z();
//! let options = DrawOptions { style: Style::parse("light,occlusion")?, ..Default::default() };
//! Drawing::build(&mesh, &axis, &options)?.write(std::path::Path::new("sherd.pdf"))?;
//! # Ok(()) }
//! ```

pub(crate) mod font;
mod layout;
pub(crate) mod model;
pub mod occlusion;
pub mod png;
pub(crate) mod postscript;
pub(crate) mod raster;
pub(crate) mod stipple;
pub(crate) mod svg;
mod view;

use std::path::Path;

pub use model::{bounds_overlap, Anchor, Bounds, Dots, Drawing, Element, Group, Image, Segment, Stroke, Text};

use occlusion::OcclusionOptions;
use crate::mesh::Mesh;
use crate::orient::Axis;
use crate::profile::measure::Measurements;
use crate::vocabulary::{or_list, Vocabulary};
use crate::{Error, Result};

crate::vocabulary! {
    /// Output formats, named by their file extensions.
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    pub enum Format: "format", "formats" {
        /// SVG with one layer per part of the drawing.
        Svg = "svg" => "SVG, one layer per part of the drawing",
        /// Encapsulated PostScript, level 3.
        Eps = "eps" | "ps" => "Encapsulated PostScript, level 3",
        /// PDF 1.4.
        Pdf = "pdf" => "PDF 1.4",
        /// PNG at the drawing's resolution.
        Png = "png" => "PNG at the drawing's resolution",
    }
}

impl Format {
    /// The format a file name's extension asks for.
    pub fn from_path(path: &Path) -> Result<Format> {
        let extension = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
        extension.as_deref().and_then(Format::find).ok_or_else(|| {
            let extensions: Vec<String> = Format::ALL.iter().map(|format| format!(".{format}")).collect();
            Error::InvalidArgument(format!("{}: unknown drawing format; use {}", path.display(), or_list(&extensions)))
        })
    }
}

crate::vocabulary! {
    /// One rendering style: a member of a [`Style`].
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    pub enum StyleKind: "style", "styles" {
        /// [`Style::linear`].
        Linear = "linear" => "Outline and profile lines only",
        /// [`Style::colour`].
        Colour = "colour" | "color" => "The scan's colours",
        /// [`Style::light`].
        Light = "light" => "Shading by a light from the upper left",
        /// [`Style::occlusion`].
        Occlusion = "occlusion" => "Ambient occlusion shading",
        /// [`Style::stipple`].
        Stipple = "stipple" => "Stippled shading",
        /// [`Style::regularity`].
        Regularity = "regularity" => "Deviation from a regular vessel as colour",
    }
}

/// Rendering styles; any combination (section 2.4.3 and 2.4.4).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Style {
    /// Outlines and crease lines (rim, fracture edges) only.
    pub linear: bool,
    /// Vertex colours or the texture, projected orthographically.
    pub colour: bool,
    /// Directional light (from the upper left, the archaeological convention).
    pub light: bool,
    /// Ambient occlusion.
    pub occlusion: bool,
    /// Dots, denser in darker areas.
    pub stipple: bool,
    /// Vessel regularity as a colour map with its legend.
    pub regularity: bool,
}

impl Style {
    /// The default styles everywhere (`DrawOptions::default()`, `sherd draw`, the C ABI,
    /// Python, Blender and MeshLab): directional light and ambient occlusion.
    pub const DEFAULT: Style =
        Style { linear: false, colour: false, light: true, occlusion: true, stipple: false, regularity: false };

    /// The flag of one style.
    pub fn flag_mut(&mut self, kind: StyleKind) -> &mut bool {
        match kind {
            StyleKind::Linear => &mut self.linear,
            StyleKind::Colour => &mut self.colour,
            StyleKind::Light => &mut self.light,
            StyleKind::Occlusion => &mut self.occlusion,
            StyleKind::Stipple => &mut self.stipple,
            StyleKind::Regularity => &mut self.regularity,
        }
    }

    /// Whether the style includes `kind`.
    pub fn has(mut self, kind: StyleKind) -> bool {
        *self.flag_mut(kind)
    }

    /// The style made of `kinds`.
    pub fn of(kinds: impl IntoIterator<Item = StyleKind>) -> Style {
        let mut style = Style::default();
        kinds.into_iter().for_each(|kind| *style.flag_mut(kind) = true);
        style
    }

    /// Parses a comma-separated list of names ("color" is accepted for "colour").
    pub fn parse(list: &str) -> Result<Style> {
        let kinds: Vec<StyleKind> =
            list.split(',').map(str::trim).filter(|n| !n.is_empty()).map(StyleKind::parse_name).collect::<Result<_>>()?;
        if kinds.is_empty() {
            return Err(Error::InvalidArgument(format!("no style given; choose among {}", StyleKind::names().join(", "))));
        }
        Ok(Style::of(kinds))
    }
}

/// The style's names, comma-separated, as [`Style::parse`] reads them ("light,occlusion").
impl std::fmt::Display for Style {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let names: Vec<&str> = StyleKind::ALL.iter().filter(|kind| self.has(**kind)).map(|kind| kind.name()).collect();
        f.write_str(&names.join(","))
    }
}

crate::vocabulary! {
    /// How the section is filled.
    #[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
    pub enum SectionFill: "section fill", "section fills" {
        /// Solid black (the usual convention for pottery).
        Black = "black" => "Solid black, the usual convention for pottery",
        /// 45-degree hatching.
        Hatched = "hatched" => "45-degree hatching",
    }
}

crate::vocabulary! {
    /// Where the views stand relative to the axis (section 2.4.1).
    #[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
    pub enum Placement: "placement", "placements" {
        /// Front view beside the axis, regardless of the true position (Fig. 4:a).
        Beside = "beside" => "The views beside the axis, whatever the true radius",
        /// Turned about the axis so that the fragment is at its true distance (Fig. 4:b).
        TrueDistance = "true_distance" => "The fragment at its true distance from the axis",
    }
}

crate::vocabulary! {
    /// Which regularity map the regularity style shows (section 2.4.4).
    #[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
    pub enum RegularityKind: "regularity map", "regularity maps" {
        /// Distance of each point to the axis (Fig. 7:a).
        AxisDistance = "axis_distance" => "Distance of each vertex to the axis: blue near, red far",
        /// Distance to the ideal vessel revolved from the section (Fig. 7:b).
        IdealVessel = "ideal_vessel" => "Signed distance to the vessel revolved from the profile: blue inside the ideal wall, white on it, red outside",
    }
}

crate::vocabulary! {
    /// One measurement written under the drawing: a member of [`Annotations`].
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    pub enum AnnotationKind: "annotation", "annotations" {
        /// [`Annotations::height`].
        Height = "height" => "The preserved height along the axis",
        /// [`Annotations::wall_thickness`].
        WallThickness = "wall_thickness" => "The median wall thickness",
        /// [`Annotations::capacity`].
        Capacity = "capacity" => "The capacity, where the profile runs from base to rim",
    }
}

/// The measurements written under the drawing besides the diameters and the preserved
/// share, which are always given. Each is left out where it was not measured (no
/// capacity without a profile from base to rim).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Annotations {
    /// The preserved height along the axis.
    pub height: bool,
    /// The median wall thickness.
    pub wall_thickness: bool,
    /// The capacity, litres.
    pub capacity: bool,
}

impl Annotations {
    /// Every annotation.
    pub const ALL: Annotations = Annotations { height: true, wall_thickness: true, capacity: true };

    /// The flag of one annotation.
    pub fn flag_mut(&mut self, kind: AnnotationKind) -> &mut bool {
        match kind {
            AnnotationKind::Height => &mut self.height,
            AnnotationKind::WallThickness => &mut self.wall_thickness,
            AnnotationKind::Capacity => &mut self.capacity,
        }
    }

    /// Whether the annotations include `kind`.
    pub fn has(mut self, kind: AnnotationKind) -> bool {
        *self.flag_mut(kind)
    }

    /// Parses a comma-separated list of names, or `all`, or `none` (no annotation, the
    /// default). An empty list is refused: `none` says it.
    pub fn parse(list: &str) -> Result<Annotations> {
        let names: Vec<String> = list
            .split(',')
            .map(|n| n.trim().to_ascii_lowercase().replace('-', "_"))
            .filter(|n| !n.is_empty())
            .collect();
        let choices = || format!("{}, or all, or none", AnnotationKind::names().join(", "));
        match names.iter().map(String::as_str).collect::<Vec<_>>()[..] {
            [] => return Err(Error::InvalidArgument(format!("no annotation given; choose among {}", choices()))),
            ["all"] => return Ok(Annotations::ALL),
            ["none"] => return Ok(Annotations::default()),
            _ => {}
        }
        let mut annotations = Annotations::default();
        for name in &names {
            if let Some(kind) = AnnotationKind::find(name) {
                *annotations.flag_mut(kind) = true;
                continue;
            }
            match name.as_str() {
                "all" | "none" => {
                    return Err(Error::InvalidArgument(format!(
                        "{name:?} cannot be combined with other annotations; give {}",
                        choices()
                    )))
                }
                _ => return Err(Error::InvalidArgument(format!("unknown annotation {name:?}; the annotations are {}", choices()))),
            }
        }
        Ok(annotations)
    }
}

/// Settings of [`Drawing::build`].
#[derive(Clone, Debug, PartialEq)]
pub struct DrawOptions {
    /// Rendering styles.
    pub style: Style,
    /// Publication scale 1:n (1 = natural size).
    pub scale_denominator: u32,
    /// Resolution of raster content and of PNG output, dots per inch.
    pub dpi: f64,
    /// Angle of the section about the axis (0 = through the centroid); `None` picks the
    /// most informative profile.
    pub section_angle_rad: Option<f64>,
    /// Section fill.
    pub section_fill: SectionFill,
    /// View placement. Either way a view that does not fit its half of the drawing is
    /// cut at the axis.
    pub placement: Placement,
    /// Draw the interior view between the section and the axis.
    pub interior_view: bool,
    /// Draw the vessel's outline right of the axis (the outer profile mirrored at its
    /// true radius, dashed where the exterior view does not show it) and carry the rim,
    /// carination and base lines to it.
    pub prolongation: bool,
    /// Measurements written under the drawing.
    pub annotations: Annotations,
    /// The map the regularity style shows.
    pub regularity: RegularityKind,
    /// Ambient occlusion quality.
    pub occlusion: OcclusionOptions,
    /// Direction towards the light in the view frame: x right, -y towards the viewer, z up.
    pub light_direction: [f64; 3],
    /// Stipple: dot spacing in fully black areas, paper mm.
    pub stipple_spacing_mm: f64,
    /// Stipple: dot radius, paper mm.
    pub stipple_dot_radius_mm: f64,
    /// An optional title (inventory number...).
    pub title: Option<String>,
    /// The fragment's measurements (`profile::measure`) for the diameter and sector
    /// labels and the rim and base lines; `None` measures it here (without bootstrap).
    pub measurements: Option<Measurements>,
}

impl Default for DrawOptions {
    fn default() -> Self {
        DrawOptions {
            style: Style::DEFAULT,
            scale_denominator: 1,
            dpi: 300.0,
            section_angle_rad: None,
            section_fill: SectionFill::Black,
            placement: Placement::Beside,
            interior_view: true,
            prolongation: true,
            annotations: Annotations::default(),
            regularity: RegularityKind::IdealVessel,
            occlusion: OcclusionOptions { directions: 32, resolution: 512 },
            light_direction: [-0.5, -0.6, 0.62],
            stipple_spacing_mm: 0.35,
            stipple_dot_radius_mm: 0.09,
            title: None,
            measurements: None,
        }
    }
}

impl DrawOptions {
    /// Rejects values no drawing can be made with, naming them.
    pub fn check(&self) -> Result<()> {
        if self.scale_denominator == 0 || self.scale_denominator > 100 {
            return Err(Error::InvalidArgument(format!("scale 1:{} is out of range 1:1 to 1:100", self.scale_denominator)));
        }
        if !(self.dpi.is_finite() && (10.0..=4800.0).contains(&self.dpi)) {
            return Err(Error::InvalidArgument(format!("resolution {} dpi is out of range 10 to 4800", self.dpi)));
        }
        if let Some(a) = self.section_angle_rad {
            crate::profile::section::check_angle(a)?;
        }
        let l = self.light_direction;
        if !(l.iter().all(|c| c.is_finite()) && l.iter().any(|&c| c != 0.0)) {
            return Err(Error::InvalidArgument(format!("light direction {l:?} must be a non-zero finite vector")));
        }
        if !(self.stipple_spacing_mm > 0.0 && self.stipple_dot_radius_mm > 0.0) {
            return Err(Error::InvalidArgument("stipple spacing and dot radius must be positive".into()));
        }
        Ok(())
    }
}

impl Drawing {
    /// The illustration of `mesh` (scan frame) oriented by `axis` (base to rim).
    pub fn build(mesh: &Mesh, axis: &Axis, options: &DrawOptions) -> Result<Drawing> {
        layout::build(mesh, axis, options)
    }

    /// The drawing encoded in `format` (PNG at the drawing's dpi).
    pub fn to_bytes(&self, format: Format) -> Result<Vec<u8>> {
        match format {
            Format::Svg => svg::to_svg(self),
            Format::Eps => postscript::to_eps(self),
            Format::Pdf => postscript::to_pdf(self),
            Format::Png => png::to_png(self, self.dpi),
        }
    }

    /// Writes the drawing to `path` atomically, in the format its extension names.
    pub fn write(&self, path: &Path) -> Result<()> {
        let bytes = self.to_bytes(Format::from_path(path)?)?;
        crate::mesh::atomic::write_bytes_atomically(path, &bytes)
    }
}
