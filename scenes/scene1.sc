# Scene 1: a square pyramid (base side 5, height 5, base centred at the origin on y = 0:
# 4 triangle sides and a quad base) with a sphere of radius 1 balanced exactly on the
# apex (centre (0,6,0), touching the apex at (0,5,0)), and at each base corner a sphere
# of radius 0.5 resting on y = 0 (centre y = 0.5), 3 units outward along the diagonal
# (x, z = +-(2.5 + 3/sqrt(2)) = +-4.621320344).
#
# Framing: seen from the front right, about 24 degrees above the ground (azimuth 22
#   degrees from +z), so two pyramid sides, the apex sphere and all four corner spheres
#   (the back one peeking out left of the apex) are visible; the whole group fills ~88% of
#   the frame height.

camera eye 4.36 7.77 13.37 look -0.69 1.77 0.87 up 0 1 0

# pyramid sides (ids 0-3): apex, then two adjacent base corners
triangle 0 5 0   -2.5 0 -2.5   2.5 0 -2.5
triangle 0 5 0   2.5 0 -2.5   2.5 0 2.5
triangle 0 5 0   2.5 0 2.5   -2.5 0 2.5
triangle 0 5 0   -2.5 0 2.5   -2.5 0 -2.5
# pyramid base (id 4), perimeter order
quad -2.5 0 -2.5   2.5 0 -2.5   2.5 0 2.5   -2.5 0 2.5
# sphere balanced on the apex (id 5)
sphere 0 6 0 1
# corner spheres (ids 6-9): corner + 3*(+-1, 0, +-1)/sqrt(2), centre y = 0.5
sphere -4.621320344 0.5 -4.621320344 0.5
sphere 4.621320344 0.5 -4.621320344 0.5
sphere 4.621320344 0.5 4.621320344 0.5
sphere -4.621320344 0.5 4.621320344 0.5
