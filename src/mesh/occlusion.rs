//! Ambient occlusion per vertex.
