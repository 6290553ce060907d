//! Refinement of a pre-oriented axis (Wilczek et al. 2018, section 2.3): one file per
//! criterion (circles, pareto, profile, tangent) behind a common objective.
