//! lanecast in the browser (work in progress).
