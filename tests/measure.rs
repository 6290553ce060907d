//! Measurements of synthetic sherds at their true axes, against the generator's truth.

use sherd::mesh::{Mesh, Point};
use sherd::orient::Axis;
use sherd::profile::measure::{measure, MeasureOptions, MAX_UNFLAGGED_AXIS_INTERVAL_DEG};
use sherd::refine::uncertainty::BootstrapOptions;
use sherd::synth::{synthetic_sherd, BaseForm, ProfileForms, RimForm, SherdOptions, SherdPart, SynthSherd};

fn options(part: SherdPart) -> SherdOptions {
    SherdOptions { target_faces: 8000, ..SherdOptions::for_part(part).ideal() }
}

/// Measurement settings without the bootstrap (no intervals): fast.
fn without_intervals() -> MeasureOptions {
    MeasureOptions { bootstrap: BootstrapOptions { samples: 0, ..Default::default() }, ..Default::default() }
}

/// Volume inside the revolved inner profile (base centre to rim), litres, by frustums.
fn true_capacity_litres(inner_profile: &[[f64; 2]]) -> f64 {
    inner_profile
        .windows(2)
        .map(|w| {
            let ([r0, z0], [r1, z1]) = (w[0], w[1]);
            std::f64::consts::PI * (z1 - z0) * (r0 * r0 + r0 * r1 + r1 * r1) / 3.0
        })
        .sum::<f64>()
        * 1e-6
}

#[test]
fn rim_sherd_measured_at_its_true_axis() {
    let mut checked = 0;
    for seed in 0..6 {
        let sherd = synthetic_sherd(seed, &options(SherdPart::Rim));
        if sherd.truth.part != SherdPart::Rim {
            continue;
        }
        checked += 1;
        let truth = &sherd.truth;
        let m = measure(&sherd.mesh, &truth.axis, &MeasureOptions::default());
        let rim_truth = truth.rim_radius_mm.expect("a rim sherd has a rim radius");
        let rim = m.rim_radius_mm.unwrap_or_else(|| panic!("seed {seed}: rim not found: {:?}", m.notes));
        assert!((rim - rim_truth).abs() < 0.01 * rim_truth, "seed {seed}: rim radius {rim} vs {rim_truth}");
        assert_eq!(m.rim_diameter_mm, Some(2.0 * rim));
        let [low, high] = m.rim_diameter_interval_mm.expect("an interval");
        // The interval's half-width is at least 3% of the diameter (the floor for what no
        // resample shows: the corpus's deformation and noise); the bound of 2.5% this
        // once had was tighter than the floor. At most 5% now: the floor and a little.
        assert!(low < 2.0 * rim && 2.0 * rim < high && high - low < 0.2 * rim, "seed {seed}: interval [{low}, {high}] for {rim}, axis interval {:?}", m.axis_angle_interval_deg);
        assert!((m.sector_angle_deg - truth.sector_angle_deg).abs() < 1.0, "sector {} vs {}", m.sector_angle_deg, truth.sector_angle_deg);
        assert!((m.sector_percent - m.sector_angle_deg / 3.6).abs() < 1e-9);
        // The rim's own arc, not the sherd's: what "N% of rim" states.
        let rim_arc = m.rim_sector_deg.expect("a rim arc");
        let rim_arc_truth = truth.rim_sector_angle_deg.expect("the truth knows the rim arc");
        assert!((rim_arc - rim_arc_truth).abs() < 1.8, "seed {seed}: rim arc {rim_arc} vs {rim_arc_truth} degrees");
        assert!(m.base_sector_deg.is_none(), "a rim sherd has no base arc");
        assert!((m.height_mm - truth.height_mm).abs() < 0.5, "height {} vs {}", m.height_mm, truth.height_mm);
        let wall = m.wall_thickness_mm.expect("a wall thickness");
        let wall_truth = truth.vessel.wall_thickness_mm;
        assert!((wall - wall_truth).abs() < 0.2 * wall_truth, "seed {seed}: wall {wall} vs {wall_truth}");
        assert!(m.capacity_litres.is_none(), "a rim sherd has no capacity");
        let [zero, angle] = m.axis_angle_interval_deg.expect("an axis interval");
        assert!(zero == 0.0 && (0.0..5.0).contains(&angle), "axis interval {angle}");
        assert_eq!(m.axis_uncertain, angle > MAX_UNFLAGGED_AXIS_INTERVAL_DEG, "axis interval {angle}");
    }
    assert!(checked >= 3, "only {checked} rim sherds generated");
}

#[test]
fn complete_profile_gives_capacity() {
    let mut checked = 0;
    for seed in 0..12 {
        let sherd = synthetic_sherd(seed, &options(SherdPart::RimToBase));
        if sherd.truth.part != SherdPart::RimToBase {
            continue;
        }
        let m = measure(&sherd.mesh, &sherd.truth.axis, &without_intervals());
        // A round-bottomed vessel has no level base to recognise: no capacity then.
        let Some(capacity) = m.capacity_litres else {
            println!("seed {seed}: no capacity: {:?}", m.notes);
            continue;
        };
        checked += 1;
        let truth = true_capacity_litres(&sherd.truth.inner_profile);
        assert!((capacity - truth).abs() < 0.05 * truth, "seed {seed}: capacity {capacity} l vs {truth} l");
        let base_truth = sherd.truth.base_radius_mm.expect("a base radius");
        let base = m.base_radius_mm.expect("a base radius");
        // Known weakness: where the skin test drops the foot corner the widest point of the
        // 1 mm band is taken, up to 4% wide of the truth on rounded feet.
        assert!((base - base_truth).abs() < 0.05 * base_truth, "base radius {base} vs {base_truth}");
    }
    assert!(checked >= 2, "only {checked} complete profiles generated");
}

#[test]
fn body_sherd_has_no_rim_base_or_capacity() {
    let sherd = synthetic_sherd(3, &options(SherdPart::Body));
    let m = measure(&sherd.mesh, &sherd.truth.axis, &MeasureOptions::default());
    assert!(m.rim_radius_mm.is_none() && m.base_radius_mm.is_none() && m.capacity_litres.is_none(), "{m:?}");
    assert!(m.notes.iter().any(|n| n.contains("no level rim")));
    let json = serde_json::to_string(&m).unwrap();
    assert!(json.contains("\"sector_angle_deg\""));
}

/// A piece of the flat floor stands level like a base, but its outer break is no base
/// edge: the widest point there once passed for the base radius, 15-40% short of it.
#[test]
fn floor_pieces_give_no_base_diameter() {
    let floor_options = SherdOptions { target_faces: 8000, ..SherdOptions::for_part(SherdPart::Flat) };
    let floors: Vec<(u64, SynthSherd)> =
        (0..6).map(|seed| (seed, synthetic_sherd(seed, &floor_options))).filter(|(_, s)| s.truth.part == SherdPart::Flat).collect();
    assert!(floors.len() >= 3, "only {} floor pieces generated", floors.len());
    for (seed, sherd) in &floors {
        let m = measure(&sherd.mesh, &sherd.truth.axis, &without_intervals());
        assert!(m.base_radius_mm.is_none() && m.base_diameter_interval_mm.is_none(), "seed {seed}: {m:?}");
        assert!(m.notes.iter().any(|n| n.contains("no base diameter")), "seed {seed}: {:?}", m.notes);
    }
}

/// Base sherds (floor and some wall) keep their base diameter.
#[test]
fn base_sherds_give_a_base_diameter() {
    let mut measured = 0;
    for seed in 0..8 {
        let sherd = synthetic_sherd(seed, &options(SherdPart::Base));
        let Some(truth) = sherd.truth.base_radius_mm else { continue };
        let m = measure(&sherd.mesh, &sherd.truth.axis, &without_intervals());
        if let Some(base) = m.base_radius_mm {
            measured += 1;
            assert!((base - truth).abs() < 0.05 * truth, "seed {seed}: base radius {base} vs {truth}");
            // The base's edge spans no more than the sherd, and something of it.
            let base_arc = m.base_sector_deg.expect("a base arc where there is a base radius");
            assert!(base_arc > 1.0 && base_arc <= m.sector_angle_deg + 1e-9, "seed {seed}: base arc {base_arc}, sherd {}", m.sector_angle_deg);
        }
    }
    assert!(measured >= 4, "only {measured} base sherds gave a base radius");
}

/// A thickened lip is measured at its bead's outer edge, below the top, where a radius
/// chart reads it; a radius taken at the top would be short by the bead.
#[test]
fn thickened_lips_are_measured_at_the_bead() {
    let forms = ProfileForms { lips: vec![RimForm::Thickened], bases: vec![BaseForm::Flat] };
    let mut beads = 0;
    for seed in 0..8 {
        let sherd = synthetic_sherd(seed, &SherdOptions { forms: forms.clone(), ..options(SherdPart::Rim) });
        let (Some(truth), RimForm::Thickened) = (sherd.truth.rim_radius_mm, sherd.truth.vessel.rim_form) else { continue };
        let m = measure(&sherd.mesh, &sherd.truth.axis, &without_intervals());
        let rim = m.rim_radius_mm.unwrap_or_else(|| panic!("seed {seed}: rim not found: {:?}", m.notes));
        assert!((rim - truth).abs() < 0.005 * truth, "seed {seed}: rim radius {rim} vs the bead's edge at {truth}");
        beads += 1;
    }
    assert!(beads >= 4, "only {beads} thickened lips made");
}

/// A ring foot's base radius is the foot's, where the vessel stands.
#[test]
fn ring_feet_give_the_foot_as_base_diameter() {
    let forms = ProfileForms { lips: vec![RimForm::Rounded], bases: vec![BaseForm::RingFoot] };
    let mut measured = 0;
    for seed in 0..8 {
        let sherd = synthetic_sherd(seed, &SherdOptions { forms: forms.clone(), ..options(SherdPart::Base) });
        assert_eq!(sherd.truth.vessel.base_form, BaseForm::RingFoot, "seed {seed}");
        let Some(truth) = sherd.truth.base_radius_mm else { continue };
        if let Some(base) = measure(&sherd.mesh, &sherd.truth.axis, &without_intervals()).base_radius_mm {
            assert!((base - truth).abs() < 0.03 * truth, "seed {seed}: base radius {base} vs the foot's {truth}");
            measured += 1;
        }
    }
    assert!(measured >= 3, "only {measured} ring-foot bases measured");
}

/// An axis interval wider than the threshold flags the axis as uncertain (here forced by
/// a floor beyond it), with a note saying so.
#[test]
fn a_wide_axis_interval_flags_the_axis() {
    let sherd = synthetic_sherd(0, &options(SherdPart::Rim));
    let floor_deg = MAX_UNFLAGGED_AXIS_INTERVAL_DEG + 1.0;
    let wide = MeasureOptions { bootstrap: BootstrapOptions { samples: 6, angle_floor_deg: floor_deg, ..Default::default() }, ..Default::default() };
    let m = measure(&sherd.mesh, &sherd.truth.axis, &wide);
    assert!(m.axis_angle_interval_deg.is_some_and(|i| i[1] >= floor_deg), "{:?}", m.axis_angle_interval_deg);
    assert!(m.axis_uncertain && m.notes.iter().any(|n| n.contains("uncertain")), "{:?}", m.notes);
}

#[test]
fn the_intervals_reach_a_competing_axis_the_orientation_could_not_rule_out() {
    let sherd = synthetic_sherd(0, &options(SherdPart::Rim));
    let bootstrap = BootstrapOptions { samples: 6, ..Default::default() };
    let alone = measure(&sherd.mesh, &sherd.truth.axis, &MeasureOptions { bootstrap, ..Default::default() });
    let reach = sherd::orient::CompetitorReach { angle_deg: 30.0, distance_mm: 60.0 };
    let with_competitor =
        measure(&sherd.mesh, &sherd.truth.axis, &MeasureOptions { bootstrap, axis_competitor_reach: Some(reach), ..Default::default() });
    let (angle, distance) = (alone.axis_angle_interval_deg.unwrap()[1], alone.axis_distance_interval_mm.unwrap()[1]);
    assert!(angle < 30.0 && distance < 60.0, "{angle} deg, {distance} mm");
    let (angle, distance) = (with_competitor.axis_angle_interval_deg.unwrap()[1], with_competitor.axis_distance_interval_mm.unwrap()[1]);
    assert!(angle >= 30.0 && distance >= 60.0, "{angle} deg, {distance} mm");
    assert!(with_competitor.axis_uncertain, "{:?}", with_competitor.axis_doubts);
}

#[test]
fn degenerate_mesh_is_reported_not_measured() {
    let mesh = Mesh::new(vec![Point::origin(); 4], vec![]);
    let m = measure(&mesh, &Axis::z(), &MeasureOptions::default());
    assert!(m.rim_radius_mm.is_none() && m.notes.iter().any(|n| n.contains("too few vertices")), "{m:?}");
}

/// Finely meshed rim sherds at their true axes (seeds the issue names, 200k faces): the
/// outer skin once vanished into one region with the inner one across the rounded lip
/// (seeds 2, 6, 12), and a rim kept over a third of the arc (seed 16) counted as not level.
#[test]
fn rims_of_finely_meshed_sherds_are_found() {
    for seed in [2, 6, 12, 16] {
        let sherd = synthetic_sherd(seed, &SherdOptions { target_faces: 200_000, ..SherdOptions::for_part(SherdPart::Rim) });
        let m = measure(&sherd.mesh, &sherd.truth.axis, &without_intervals());
        let truth = sherd.truth.rim_radius_mm.expect("a rim sherd has a rim radius");
        let rim = m.rim_radius_mm.unwrap_or_else(|| panic!("seed {seed}: rim not found: {:?}", m.notes));
        assert!((rim - truth).abs() < 0.02 * truth, "seed {seed}: rim radius {rim} vs {truth}");
    }
}

/// A base whose skins do not fix the axis's radial position (a short arc of a deformed
/// vessel): the tangent plane levels such an axis but leaves it where the pre-orientation
/// put it, here 8 mm too near the sherd. The diameter interval must then be as loose as
/// the position, not a narrow one about the wrong diameter (fragments 9 of vessel 1 and
/// 13 of vessel 0 of `examples/refine_accuracy.rs`, which the pipeline left 5 and 9 mm
/// off with intervals of +-5 and +-10 mm, 14 and 19 mm from the truth). Before resamples
/// went where Eq. 2 takes them, this test's intervals were [84, 93] mm about a true 108.5
/// and [189, 209] about 219.9.
#[test]
fn a_position_the_skins_do_not_fix_gets_a_loose_diameter_interval() {
    use sherd::synth::{generate_vessel, VesselOptions};
    for (vessel_seed, fragment) in [(1, 9), (0, 13)] {
        let vessel = generate_vessel(vessel_seed, &VesselOptions { fragment_count: 34, random_motion: true, ..Default::default() });
        let sherd = &vessel.fragments[fragment];
        let truth = &sherd.truth;
        let true_diameter = truth.base_radius_mm.expect("a base is preserved") * 2.0;
        // The true axis moved 8 mm towards the sherd, along the line from the axis to the
        // sherd's centroid: its direction exact, its position off.
        let centroid = sherd.mesh.positions.iter().fold(Point::origin(), |sum, p| sum + p.coords / sherd.mesh.positions.len() as f64);
        let towards = (centroid - truth.axis.closest_point(&centroid)).normalize();
        let off = Axis::new(truth.axis.point + towards * 8.0, truth.axis.direction.into_inner());
        let m = measure(&sherd.mesh, &off, &MeasureOptions::default());
        let measured = m.base_diameter_mm.expect("the base is measured");
        let [low, high] = m.base_diameter_interval_mm.expect("an interval");
        assert!((measured - true_diameter).abs() > 10.0, "vessel {vessel_seed} fragment {fragment}: the moved axis should misjudge the diameter, {measured:.1} vs {true_diameter:.1}");
        assert!(low <= true_diameter && true_diameter <= high, "vessel {vessel_seed} fragment {fragment}: true base diameter {true_diameter:.1} mm outside [{low:.1}, {high:.1}] (measured {measured:.1})");
    }
}
