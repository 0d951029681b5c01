//! Regressions found by fuzzing (fuzz/, CONTRIBUTING.md).

use crate::numbers::{rejected_with, render_both};

/// fuzz `render` crash-89bb9530: a 12-unit triangle seen from 5e17 away. Subtracting the eye
/// in f64 (spacing 64 there) merged two vertices, one edge plane normal became zero, and the
/// triangle turned into an endless wedge: the packet kernel drew it across the image where the
/// oracle did not. Now rejected: its edges subtend less than `limits::MIN_EDGE_ANGLE`.
#[test]
fn fuzz_far_tiny_triangle_collapses_eye_relative() {
    rejected_with(
        "# Sc 4: along theg bes show f-1\n\
         triangle -6 2 -1   6 2 1   6 2 -1.\n\
         \n\
         camera eye -5e17 5.19 8.68 look -5.02 0.38 -0.25 up 0 07 1\n",
        2,
        &["triangle edge", "subtends", "rad"],
    );
    // The same triangle from an ordinary distance renders, both kernels agreeing.
    let ids = render_both(
        "triangle -6 2 -1   6 2 1   6 2 -1.\n\
         camera eye -5 5.19 8.68 look -5.02 0.38 -0.25 up 0 07 1\n",
    );
    assert!(ids[0].contains(&0));
}
