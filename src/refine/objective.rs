//! The common shape of the refinement criteria: a scalar cost of the four axis
//! parameters ([`AxisParameters`]), minimised by Nelder-Mead (argmin) as in the
//! original tool (Wilczek et al. 2018, section 2.3), but restarted from its own result
//! with a fresh simplex until a restart no longer improves: a single Nelder-Mead run
//! often stalls on a collapsed simplex (a weakness of the original tool).

use argmin::core::{CostFunction, Executor, State};
use argmin::solver::neldermead::NelderMead;

use super::sections::AxisParameters;
use crate::{Error, Result};

/// A refinement criterion: lower is better.
pub trait Objective: Sync {
    /// The cost of the candidate axis `parameters` (start frame, see [`AxisParameters`]).
    fn value(&self, parameters: &AxisParameters) -> f64;
}

/// Which of the four parameters the search may change.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum FreeParameters {
    /// Two tilts and two shifts.
    All,
    /// Only the two shifts, keeping the direction: after a manual three-point
    /// pre-orientation the three points must stay on one horizontal plane.
    ShiftsOnly,
    /// Only the two tilts (the criterion fixes the shifts itself).
    TiltsOnly,
}

impl FreeParameters {
    /// The indices of the free parameters in [`AxisParameters`] order.
    pub(crate) fn indices(self) -> &'static [usize] {
        match self {
            FreeParameters::All => &[0, 1, 2, 3],
            FreeParameters::ShiftsOnly => &[2, 3],
            FreeParameters::TiltsOnly => &[0, 1],
        }
    }
}

/// Where a minimisation ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Minimum {
    /// The best parameters found.
    pub parameters: AxisParameters,
    /// The cost there.
    pub value: f64,
    /// Nelder-Mead iterations over all restarts.
    pub iterations: u64,
}

/// Settings of [`minimize`].
#[derive(Clone, Copy, Debug)]
pub struct SearchSettings {
    /// Which parameters move.
    pub free: FreeParameters,
    /// Initial simplex step for the tilts, radians.
    pub tilt_step_rad: f64,
    /// Initial simplex step for the shifts, millimetres.
    pub shift_step_mm: f64,
    /// Largest tilt from the start axis, radians: costs outside are infinite.
    pub tilt_bound_rad: f64,
    /// Iterations per Nelder-Mead run.
    pub max_iterations: u64,
    /// Most restarts from the best point.
    pub max_restarts: usize,
    /// A run stops when its simplex's costs spread less than this fraction of the best
    /// cost ([`RELATIVE_COST_TOLERANCE`] by default).
    pub relative_cost_tolerance: f64,
    /// A restart follows only a run that lowered the cost by more than this fraction
    /// ([`MIN_RESTART_IMPROVEMENT`] by default).
    pub min_restart_improvement: f64,
}

impl Default for SearchSettings {
    fn default() -> Self {
        SearchSettings {
            free: FreeParameters::All,
            tilt_step_rad: 1.5f64.to_radians(),
            shift_step_mm: 1.5,
            tilt_bound_rad: 10f64.to_radians(),
            max_iterations: 250,
            max_restarts: 4,
            relative_cost_tolerance: RELATIVE_COST_TOLERANCE,
            min_restart_improvement: MIN_RESTART_IMPROVEMENT,
        }
    }
}

struct Problem<'a, O: Objective + ?Sized> {
    objective: &'a O,
    base: AxisParameters,
    free: &'static [usize],
    tilt_bound_rad: f64,
}

impl<O: Objective + ?Sized> Problem<'_, O> {
    fn full(&self, free_values: &[f64]) -> AxisParameters {
        let mut parameters = self.base;
        for (&i, &v) in self.free.iter().zip(free_values) {
            parameters[i] = v;
        }
        parameters
    }
}

impl<O: Objective + ?Sized> CostFunction for Problem<'_, O> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, free_values: &Self::Param) -> std::result::Result<f64, argmin::core::Error> {
        let parameters = self.full(free_values);
        if parameters[0].hypot(parameters[1]) > self.tilt_bound_rad {
            return Ok(f64::INFINITY);
        }
        let value = self.objective.value(&parameters);
        Ok(if value.is_finite() { value } else { f64::INFINITY })
    }
}

/// A Nelder-Mead run stops when its simplex's costs spread less than this fraction of
/// the best cost so far. The criteria cut the skins anew at every candidate, and moving
/// the axis by a hundredth of a degree changes which triangles a plane cuts: their value
/// jitters by a part in a thousand or more, so closer agreement only shrinks the simplex
/// onto that jitter (`docs/calibration.md`).
pub const RELATIVE_COST_TOLERANCE: f64 = 1e-6;

/// Another restart follows only a run that lowered the cost by more than this fraction.
/// Smaller gains are the criteria's jitter (see [`RELATIVE_COST_TOLERANCE`]) or a polish
/// that no longer moves the axis (`docs/calibration.md`). With 1e-9 every search used all
/// its restarts.
pub const MIN_RESTART_IMPROVEMENT: f64 = 1e-2;

/// Minimises `objective` from `start` by restarted Nelder-Mead.
pub fn minimize<O: Objective + ?Sized>(objective: &O, start: AxisParameters, settings: &SearchSettings) -> Result<Minimum> {
    let free = settings.free.indices();
    let mut best = Minimum { parameters: start, value: objective.value(&start), iterations: 0 };
    let mut scale = 1.0;
    for _ in 0..=settings.max_restarts {
        let centre: Vec<f64> = free.iter().map(|&i| best.parameters[i]).collect();
        let mut simplex = vec![centre.clone()];
        for (k, &i) in free.iter().enumerate() {
            let mut vertex = centre.clone();
            vertex[k] += scale * if i < 2 { settings.tilt_step_rad } else { settings.shift_step_mm };
            simplex.push(vertex);
        }
        let solver = NelderMead::new(simplex)
            .with_sd_tolerance(settings.relative_cost_tolerance * best.value.abs())
            .map_err(|e| Error::NotConverged(format!("Nelder-Mead setup: {e}")))?;
        let problem = Problem { objective, base: best.parameters, free, tilt_bound_rad: settings.tilt_bound_rad };
        let result = Executor::new(problem, solver)
            .configure(|state| state.max_iters(settings.max_iterations))
            .run()
            .map_err(|e| Error::NotConverged(format!("Nelder-Mead: {e}")))?;
        let state = result.state();
        best.iterations += state.get_iter();
        let improved = match (state.get_best_param(), state.get_best_cost()) {
            (Some(p), cost) if cost < best.value => {
                let relative = (best.value - cost) / best.value.abs().max(1e-300);
                let mut parameters = best.parameters;
                for (&i, &v) in free.iter().zip(p) {
                    parameters[i] = v;
                }
                best.parameters = parameters;
                best.value = cost;
                relative > settings.min_restart_improvement
            }
            _ => false,
        };
        if !improved {
            break;
        }
        // Each restart searches a smaller neighbourhood of the improved point.
        scale *= 0.3;
    }
    if !best.value.is_finite() {
        return Err(Error::NotConverged("the criterion is undefined around the start axis".into()));
    }
    Ok(best)
}

/// What one criterion's search from the start gave.
#[derive(Clone, Copy, Debug)]
pub(crate) struct CriterionRun {
    /// The axis found, or the start where the search did not beat it.
    pub parameters: AxisParameters,
    /// The criterion's cost at the start.
    pub start_cost: f64,
    /// The criterion's cost at `parameters`.
    pub cost: f64,
    /// Optimiser iterations (cost evaluations for the Pareto search).
    pub iterations: u64,
    /// True when the search did not beat the start, which is kept.
    pub kept_start: bool,
}

/// Minimises `objective` from `start`, and keeps the start when the search does not beat
/// it: a refinement never returns an axis its own criterion rates worse.
pub(crate) fn run_guarded<O: Objective>(objective: &O, start: AxisParameters, settings: &SearchSettings) -> Result<CriterionRun> {
    let start_cost = objective.value(&start);
    let Minimum { parameters, value, iterations } = minimize(objective, start, settings)?;
    Ok(match value < start_cost {
        true => CriterionRun { parameters, start_cost, cost: value, iterations, kept_start: false },
        false => CriterionRun { parameters: start, start_cost, cost: start_cost, iterations, kept_start: true },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Bowl;
    impl Objective for Bowl {
        fn value(&self, p: &AxisParameters) -> f64 {
            (p[0] - 0.05).powi(2) + 2.0 * (p[1] + 0.03).powi(2) + 1e-4 * ((p[2] - 3.0).powi(2) + (p[3] + 1.0).powi(2))
        }
    }

    #[test]
    fn finds_the_minimum_of_a_badly_scaled_bowl() {
        let minimum = minimize(&Bowl, [0.0; 4], &SearchSettings::default()).unwrap();
        let p = minimum.parameters;
        assert!((p[0] - 0.05).abs() < 1e-5 && (p[1] + 0.03).abs() < 1e-5, "{p:?}");
        assert!((p[2] - 3.0).abs() < 1e-2 && (p[3] + 1.0).abs() < 1e-2, "{p:?}");
    }

    #[test]
    fn shifts_only_keeps_the_tilts() {
        let settings = SearchSettings { free: FreeParameters::ShiftsOnly, ..Default::default() };
        let minimum = minimize(&Bowl, [0.01, 0.02, 0.0, 0.0], &settings).unwrap();
        assert_eq!(&minimum.parameters[..2], &[0.01, 0.02]);
        assert!((minimum.parameters[2] - 3.0).abs() < 1e-2);
    }
}
