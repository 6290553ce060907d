//! Synthetic sherds with known axes: a random vessel profile revolved with wall
//! thickness, deformed, made noisy, broken along a Voronoi diagram and moved by random
//! rigid motions. The test bed of every later layer (design: "Tests that count").
