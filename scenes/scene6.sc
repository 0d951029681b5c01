# Scene 6: a 10-pointed star of 20 triangles in the plane z = 0, centred at the origin:
# a fan of 10 triangles from the centre forms the decagon core (circumradius 1), and
# 10 spike triangles stand on the decagon's edges with their tips at radius 2.5.
# One tip points straight up (+y).
#
# Framing: camera on the +z axis at distance 7 looking straight at the origin (fov 60), so
#   the star (tips at radius 2.5) is seen face-on, centred, ~40 px from the top and
#   bottom.

camera eye 0 0 7 look 0 0 0 up 0 1 0

# core fan (ids 0-9): centre, decagon vertex k, decagon vertex k+1
triangle 0 0 0   0.309017 0.951057 0   -0.309017 0.951057 0
triangle 0 0 0   -0.309017 0.951057 0   -0.809017 0.587785 0
triangle 0 0 0   -0.809017 0.587785 0   -1 0 0
triangle 0 0 0   -1 0 0   -0.809017 -0.587785 0
triangle 0 0 0   -0.809017 -0.587785 0   -0.309017 -0.951057 0
triangle 0 0 0   -0.309017 -0.951057 0   0.309017 -0.951057 0
triangle 0 0 0   0.309017 -0.951057 0   0.809017 -0.587785 0
triangle 0 0 0   0.809017 -0.587785 0   1 0 0
triangle 0 0 0   1 0 0   0.809017 0.587785 0
triangle 0 0 0   0.809017 0.587785 0   0.309017 0.951057 0
# spikes (ids 10-19): decagon vertex k, tip k, decagon vertex k+1
triangle 0.309017 0.951057 0   0 2.5 0   -0.309017 0.951057 0
triangle -0.309017 0.951057 0   -1.469463 2.022542 0   -0.809017 0.587785 0
triangle -0.809017 0.587785 0   -2.377641 0.772542 0   -1 0 0
triangle -1 0 0   -2.377641 -0.772542 0   -0.809017 -0.587785 0
triangle -0.809017 -0.587785 0   -1.469463 -2.022542 0   -0.309017 -0.951057 0
triangle -0.309017 -0.951057 0   0 -2.5 0   0.309017 -0.951057 0
triangle 0.309017 -0.951057 0   1.469463 -2.022542 0   0.809017 -0.587785 0
triangle 0.809017 -0.587785 0   2.377641 -0.772542 0   1 0 0
triangle 1 0 0   2.377641 0.772542 0   0.809017 0.587785 0
triangle 0.809017 0.587785 0   1.469463 2.022542 0   0.309017 0.951057 0
