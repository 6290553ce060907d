//! The section's outer and inner outline as functions of height, which the views are
//! placed against and the horizontal lines and the vessel's outline follow.

use crate::profile::section::ProfileSection;

/// The outer (largest radius) and inner outline of the section as functions of height.
pub(super) struct OuterProfile {
    /// `(z, r_outer, r_inner)` from bottom to top.
    samples: Vec<(f64, f64, f64)>,
    pub(super) outer_radius_max: f64,
    inner_radius_min: f64,
    pub(super) z_bottom: f64,
    pub(super) z_top: f64,
}

impl OuterProfile {
    pub(super) fn of(section: &ProfileSection) -> Self {
        let outlines = section.closed_outlines();
        let (r0, r1, z0, z1) = section.bounds().unwrap_or((0.0, 0.0, 0.0, 0.0));
        let steps = 400;
        let mut samples = Vec::with_capacity(steps + 1);
        for i in 0..=steps {
            let z = z0 + (z1 - z0) * (i as f64 + 0.5) / (steps as f64 + 1.0);
            let (mut outer, mut inner) = (f64::NEG_INFINITY, f64::INFINITY);
            for o in &outlines {
                for k in 0..o.len() {
                    let (a, b) = (o[k], o[(k + 1) % o.len()]);
                    if (a[1] <= z) != (b[1] <= z) {
                        let r = a[0] + (z - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
                        outer = outer.max(r);
                        inner = inner.min(r);
                    }
                }
            }
            if outer.is_finite() {
                samples.push((z, outer, inner));
            }
        }
        OuterProfile { samples, outer_radius_max: r1, inner_radius_min: r0, z_bottom: z0, z_top: z1 }
    }

    /// The outer and inner radius at height `z`, interpolated between the samples and
    /// held at the end samples beyond them.
    fn radii_at(&self, z: f64) -> (f64, f64) {
        let samples = &self.samples;
        let Some(first) = samples.first() else { return (self.outer_radius_max, self.inner_radius_min) };
        let i = samples.partition_point(|s| s.0 < z);
        if i == 0 {
            return (first.1, first.2);
        }
        if i == samples.len() {
            let last = samples[i - 1];
            return (last.1, last.2);
        }
        let (a, b) = (samples[i - 1], samples[i]);
        let t = (z - a.0) / (b.0 - a.0).max(1e-12);
        (a.1 + t * (b.1 - a.1), a.2 + t * (b.2 - a.2))
    }

    pub(super) fn outer_at(&self, z: f64) -> f64 {
        self.radii_at(z).0
    }

    pub(super) fn inner_at(&self, z: f64) -> f64 {
        self.radii_at(z).1
    }

    /// The samples on the outer skin: without the ends where the outermost crossing runs
    /// along a slanted break face (the wall narrows there to nothing), unless that end is
    /// the base (`keep_bottom`) or the rim (`keep_top`), whose rounding is the vessel's own.
    pub(super) fn outer_skin(&self, keep_bottom: bool, keep_top: bool) -> &[(f64, f64, f64)] {
        let mut widths: Vec<f64> = self.samples.iter().map(|s| s.1 - s.2).collect();
        if widths.is_empty() {
            return &self.samples;
        }
        let wall = crate::statistics::quantile(&mut widths, 0.5);
        let on_wall = |s: &(f64, f64, f64)| s.1 - s.2 >= 0.6 * wall;
        let start = if keep_bottom { 0 } else { self.samples.iter().position(on_wall).unwrap_or(0) };
        let end = if keep_top { self.samples.len() } else { self.samples.iter().rposition(on_wall).map_or(self.samples.len(), |i| i + 1) };
        &self.samples[start..end.max(start)]
    }

    /// The outer radius at the top (the rim radius, for a rim sherd).
    pub(super) fn top_radius(&self) -> f64 {
        self.samples.last().map(|s| s.1).unwrap_or(self.outer_radius_max)
    }

    pub(super) fn bottom_radius(&self) -> f64 {
        self.samples.first().map(|s| s.1).unwrap_or(self.outer_radius_max)
    }

    /// Heights where the outer profile turns sharply (carinations): the direction over
    /// 3 mm before and after differs by more than 25 degrees, at the local maximum.
    pub(super) fn carinations(&self) -> Vec<(f64, f64)> {
        let n = self.samples.len();
        if n < 5 {
            return Vec::new();
        }
        let dz = (self.z_top - self.z_bottom) / n as f64;
        let window = ((3.0 / dz.max(1e-9)).round() as usize).clamp(1, n / 4 + 1);
        let turn: Vec<f64> = (0..n)
            .map(|i| {
                if i < window || i + window >= n {
                    return 0.0;
                }
                let (a, b, c) = (self.samples[i - window], self.samples[i], self.samples[i + window]);
                let before = (b.1 - a.1).atan2(b.0 - a.0);
                let after = (c.1 - b.1).atan2(c.0 - b.0);
                (after - before).abs().to_degrees()
            })
            .collect();
        // Only the strongest turn within the window counts, and not the rounding of the
        // rim's lip or the base's edge.
        let margin = 4.0;
        (1..n - 1)
            .filter(|&i| {
                let neighbourhood = &turn[i.saturating_sub(window)..(i + window + 1).min(n)];
                turn[i] > 25.0 && neighbourhood.iter().all(|&t| t <= turn[i]) && turn[i] > turn[i - 1]
            })
            .map(|i| (self.samples[i].0, self.samples[i].1))
            .filter(|&(z, _)| z > self.z_bottom + margin && z < self.z_top - margin)
            .collect()
    }
}
