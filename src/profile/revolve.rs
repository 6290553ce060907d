//! 3D reconstruction by revolution of the profile.
