//! Spatial indices: a k-d tree for nearest points and a BVH for ray casts.
