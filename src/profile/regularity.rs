//! Vessel regularity maps.
