//! lanecast for Python (work in progress).
