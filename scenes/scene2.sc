# Scene 2: 64 spheres of radius 0.5 in a 4x4x4 block, centre-to-centre spacing 1.5,
# centred at the origin (coordinates -2.25, -0.75, 0.75, 2.25 on each axis).
#
# Framing: looking at the block's (+x,+y,+z) corner from a diagonal about 28 degrees above
#   it, with a narrower fov of 30 degrees from farther away to keep perspective mild, so
#   it reads as a 3D block (hexagonal outline, three faces of spheres).

camera eye 11.63 10.51 16.75 look 0.01 -0.26 0.16 up 0 1 0 fov 30

# ids = 16*ix + 4*iy + iz (x slowest, z fastest)
sphere -2.25 -2.25 -2.25 0.5
sphere -2.25 -2.25 -0.75 0.5
sphere -2.25 -2.25 0.75 0.5
sphere -2.25 -2.25 2.25 0.5
sphere -2.25 -0.75 -2.25 0.5
sphere -2.25 -0.75 -0.75 0.5
sphere -2.25 -0.75 0.75 0.5
sphere -2.25 -0.75 2.25 0.5
sphere -2.25 0.75 -2.25 0.5
sphere -2.25 0.75 -0.75 0.5
sphere -2.25 0.75 0.75 0.5
sphere -2.25 0.75 2.25 0.5
sphere -2.25 2.25 -2.25 0.5
sphere -2.25 2.25 -0.75 0.5
sphere -2.25 2.25 0.75 0.5
sphere -2.25 2.25 2.25 0.5
sphere -0.75 -2.25 -2.25 0.5
sphere -0.75 -2.25 -0.75 0.5
sphere -0.75 -2.25 0.75 0.5
sphere -0.75 -2.25 2.25 0.5
sphere -0.75 -0.75 -2.25 0.5
sphere -0.75 -0.75 -0.75 0.5
sphere -0.75 -0.75 0.75 0.5
sphere -0.75 -0.75 2.25 0.5
sphere -0.75 0.75 -2.25 0.5
sphere -0.75 0.75 -0.75 0.5
sphere -0.75 0.75 0.75 0.5
sphere -0.75 0.75 2.25 0.5
sphere -0.75 2.25 -2.25 0.5
sphere -0.75 2.25 -0.75 0.5
sphere -0.75 2.25 0.75 0.5
sphere -0.75 2.25 2.25 0.5
sphere 0.75 -2.25 -2.25 0.5
sphere 0.75 -2.25 -0.75 0.5
sphere 0.75 -2.25 0.75 0.5
sphere 0.75 -2.25 2.25 0.5
sphere 0.75 -0.75 -2.25 0.5
sphere 0.75 -0.75 -0.75 0.5
sphere 0.75 -0.75 0.75 0.5
sphere 0.75 -0.75 2.25 0.5
sphere 0.75 0.75 -2.25 0.5
sphere 0.75 0.75 -0.75 0.5
sphere 0.75 0.75 0.75 0.5
sphere 0.75 0.75 2.25 0.5
sphere 0.75 2.25 -2.25 0.5
sphere 0.75 2.25 -0.75 0.5
sphere 0.75 2.25 0.75 0.5
sphere 0.75 2.25 2.25 0.5
sphere 2.25 -2.25 -2.25 0.5
sphere 2.25 -2.25 -0.75 0.5
sphere 2.25 -2.25 0.75 0.5
sphere 2.25 -2.25 2.25 0.5
sphere 2.25 -0.75 -2.25 0.5
sphere 2.25 -0.75 -0.75 0.5
sphere 2.25 -0.75 0.75 0.5
sphere 2.25 -0.75 2.25 0.5
sphere 2.25 0.75 -2.25 0.5
sphere 2.25 0.75 -0.75 0.5
sphere 2.25 0.75 0.75 0.5
sphere 2.25 0.75 2.25 0.5
sphere 2.25 2.25 -2.25 0.5
sphere 2.25 2.25 -0.75 0.5
sphere 2.25 2.25 0.75 0.5
sphere 2.25 2.25 2.25 0.5
