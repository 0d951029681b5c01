# Scene 4: along the x axis, alternating cube (side 2), sphere (radius 1), cube, sphere,
# cube, all resting on y = 0 with gaps of 0.5: centres x = -5, -2.5, 0, 2.5, 5, spanning
# x = -6..6. Cubes span y 0..2, z -1..1; spheres are centred at y = 1.
# Each cube is made of 12 triangles (2 per face).
# Same objects and camera as scene 3, with the cube faces split into triangles.
#
# Framing: from the front left (azimuth -30 degrees from +z), about 25 degrees above, so
#   the row recedes to the right and the cubes show front, side and top faces; the row
#   spans the frame width with ~30 px margins.

camera eye -6.17 5.19 8.68 look -1.02 0.38 -0.25 up 0 1 0

# cube centred at x = -5
triangle -6 0 -1   -4 0 -1   -4 0 1   # bottom y=0
triangle -6 0 -1   -4 0 1   -6 0 1
triangle -6 2 -1   -6 2 1   -4 2 1   # top y=2
triangle -6 2 -1   -4 2 1   -4 2 -1
triangle -6 0 -1   -6 2 -1   -4 2 -1   # back z=-1
triangle -6 0 -1   -4 2 -1   -4 0 -1
triangle -6 0 1   -4 0 1   -4 2 1   # front z=1
triangle -6 0 1   -4 2 1   -6 2 1
triangle -6 0 -1   -6 0 1   -6 2 1   # left x=-6
triangle -6 0 -1   -6 2 1   -6 2 -1
triangle -4 0 -1   -4 2 -1   -4 2 1   # right x=-4
triangle -4 0 -1   -4 2 1   -4 0 1
# sphere centred at x = -2.5
sphere -2.5 1 0 1
# cube centred at x = 0
triangle -1 0 -1   1 0 -1   1 0 1   # bottom y=0
triangle -1 0 -1   1 0 1   -1 0 1
triangle -1 2 -1   -1 2 1   1 2 1   # top y=2
triangle -1 2 -1   1 2 1   1 2 -1
triangle -1 0 -1   -1 2 -1   1 2 -1   # back z=-1
triangle -1 0 -1   1 2 -1   1 0 -1
triangle -1 0 1   1 0 1   1 2 1   # front z=1
triangle -1 0 1   1 2 1   -1 2 1
triangle -1 0 -1   -1 0 1   -1 2 1   # left x=-1
triangle -1 0 -1   -1 2 1   -1 2 -1
triangle 1 0 -1   1 2 -1   1 2 1   # right x=1
triangle 1 0 -1   1 2 1   1 0 1
# sphere centred at x = 2.5
sphere 2.5 1 0 1
# cube centred at x = 5
triangle 4 0 -1   6 0 -1   6 0 1   # bottom y=0
triangle 4 0 -1   6 0 1   4 0 1
triangle 4 2 -1   4 2 1   6 2 1   # top y=2
triangle 4 2 -1   6 2 1   6 2 -1
triangle 4 0 -1   4 2 -1   6 2 -1   # back z=-1
triangle 4 0 -1   6 2 -1   6 0 -1
triangle 4 0 1   6 0 1   6 2 1   # front z=1
triangle 4 0 1   6 2 1   4 2 1
triangle 4 0 -1   4 0 1   4 2 1   # left x=4
triangle 4 0 -1   4 2 1   4 2 -1
triangle 6 0 -1   6 2 -1   6 2 1   # right x=6
triangle 6 0 -1   6 2 1   6 0 1
