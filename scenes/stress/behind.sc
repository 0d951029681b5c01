# Primitives behind the eye (a sphere, a triangle), straddling the eye's plane (a floor
# triangle, a wall quad, a sphere beside the eye, a ceiling sliver), a quad 1e-3 in front
# of the eye and a reference sphere; fov 120.
# Probes: false hits (t <= 0, behind the eye) and the sign handling of each method.

camera eye 0 0 0 look 0 0 -1 up 0 1 0 fov 120

sphere 0.0 0.0 5.0 1.0
triangle -1.0 -1.0 3.0   1.0 -1.0 3.0   0.0 1.0 3.0
triangle -2.0 -1.0 -3.0   2.0 -1.0 -3.0   0.0 -1.0 3.0
quad 1.5 -1.0 4.0   1.5 1.0 4.0   1.5 1.0 -6.0   1.5 -1.0 -6.0
sphere -3.0 0.0 0.5 2.0
sphere 0.0 0.3 -6.0 1.0
triangle -0.5 1.5 2.0   0.5 1.5 2.0   0.0 1.5 -2.0
quad 0.0005 -0.0005 -0.001   0.0015 -0.0005 -0.001   0.0015 0.0005 -0.001   0.0005 0.0005 -0.001
