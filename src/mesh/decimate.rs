//! Quadric edge-collapse decimation.
