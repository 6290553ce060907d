//! Edge and vertex adjacency, boundary and non-manifold edges, connected components.
