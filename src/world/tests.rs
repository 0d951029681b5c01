//! The world engine held to the f64 oracle.
