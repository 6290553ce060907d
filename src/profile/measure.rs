//! Measurements in the oriented frame.
