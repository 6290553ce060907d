//! The archaeological illustration (Wilczek et al. 2018, section 2.4): a small drawing
//! model built from an oriented sherd, its styles, and the SVG, EPS, PDF and PNG writers.
