# Scene 7: one triangle with a vertex very close to the camera and two far away, to show
# the brightness falling off with hit distance (compare -cv linear and -cv log).
# Camera at the origin looking down -z. The near vertex is 0.503 from the eye, just
# below the view centre; the far vertices are 93.5 away, upper left and upper right.
#
# Framing: the triangle's image runs from the near vertex, 73% of the way down the centre
#   line, up to the far vertices near the top corners. With -cv linear the dimming shows
#   only as a band along the far edge: depth grows hyperbolically across the image, so
#   most pixels are near tmin. -cv log shows a gradual fade.

camera eye 0 0 0 look 0 0 -1 up 0 1 0

triangle 0 -0.15 -0.48   -42 24 -80   42 24 -80
