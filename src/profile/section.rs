//! The profile section: the cut of the oriented mesh by a half-plane through the axis.
