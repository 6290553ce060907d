//! Mesh repair before processing (Wilczek et al. 2018, section 2.1).
