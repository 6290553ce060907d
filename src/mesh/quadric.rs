//! Error quadrics (Garland and Heckbert 1997).
