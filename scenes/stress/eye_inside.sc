# The eye inside a sphere of radius 10 that holds a closed cube (12 triangles), two
# spheres, a triangle and a floor quad running out through the sphere's wall; fov 100.
# Probes: the inside case of sphere tests (the hit is the far root: the stable form's
# t = q, the naive form's +sqrt branch), and occlusion by the enclosing sphere.
# lab: closed 1-12

camera eye 0 0 0 look 0 -0.2 -1 up 0 1 0 fov 100

sphere 0.5 0.2 -0.3 10.0
triangle 0.5 -0.7 -6.0   2.5 -0.7 -6.0   2.5 1.3 -6.0
triangle 0.5 -0.7 -6.0   2.5 1.3 -6.0   0.5 1.3 -6.0
triangle 2.5 -0.7 -8.0   0.5 -0.7 -8.0   0.5 1.3 -8.0
triangle 2.5 -0.7 -8.0   0.5 1.3 -8.0   2.5 1.3 -8.0
triangle 0.5 -0.7 -8.0   0.5 -0.7 -6.0   0.5 1.3 -6.0
triangle 0.5 -0.7 -8.0   0.5 1.3 -6.0   0.5 1.3 -8.0
triangle 2.5 -0.7 -6.0   2.5 -0.7 -8.0   2.5 1.3 -8.0
triangle 2.5 -0.7 -6.0   2.5 1.3 -8.0   2.5 1.3 -6.0
triangle 0.5 1.3 -6.0   2.5 1.3 -6.0   2.5 1.3 -8.0
triangle 0.5 1.3 -6.0   2.5 1.3 -8.0   0.5 1.3 -8.0
triangle 0.5 -0.7 -8.0   2.5 -0.7 -8.0   2.5 -0.7 -6.0
triangle 0.5 -0.7 -8.0   2.5 -0.7 -6.0   0.5 -0.7 -6.0
sphere -2.0 1.0 -6.0 1.0
triangle -4.0 -1.0 -4.0   -1.0 -1.5 -5.0   -3.0 2.0 -7.0
quad -8.0 -2.0 -8.0   8.0 -2.0 -8.0   8.0 -2.0 4.0   -8.0 -2.0 4.0
sphere 0.2 -0.5 3.0 0.7
