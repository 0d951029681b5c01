# Coplanar overlapping primitives in the tilted plane z = -5 + 0.3x - 0.2y: two overlapping
# triangles, a coplanar quad, an exact duplicate of triangle 0 and a copy with its
# vertices rotated; two identical spheres.
# Probes: genuine ties (equal f64 distances, within compare::TIE_REL = 1e-5): any id among
# the tied ones is right, and the lab excuses them; exact ties go to the lower id.

camera eye 0 0 0 look 0 0 -1 up 0 1 0 fov 60

triangle -2.0 -1.5 -5.3   1.0 -1.5 -4.4   -0.5 1.5 -5.45
triangle -1.0 -1.0 -5.1   2.0 -0.5 -4.300000000000001   0.5 1.8 -5.21
quad -1.5 -0.5 -5.3500000000000005   0.5 -0.5 -4.75   0.5 0.8 -5.01   -1.5 0.8 -5.61
triangle -2.0 -1.5 -5.3   1.0 -1.5 -4.4   -0.5 1.5 -5.45
triangle 1.0 -1.5 -4.4   -0.5 1.5 -5.45   -2.0 -1.5 -5.3
sphere 1.2 1.2 -6.0 0.8
sphere 1.2 1.2 -6.0 0.8
