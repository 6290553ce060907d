//! Laplacian and HC smoothing.
