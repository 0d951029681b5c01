# Scene 5: 11 spheres of radius 0.5 along the x axis with gaps of 0.5, centred at the
# origin: centres x = -5, -4, ..., 5 (y = 0, z = 0), spanning x = -5.5..5.5.
#
# Framing: from the front left, about 25 degrees above (azimuth -40 degrees from +z), so
#   the row recedes diagonally across the frame from the large near sphere at x = -5 to
#   the small far one at x = 5; ~30 px side margins.

camera eye -6.26 2.99 5.11 look -1.33 -0.58 -0.76 up 0 1 0

sphere -5 0 0 0.5
sphere -4 0 0 0.5
sphere -3 0 0 0.5
sphere -2 0 0 0.5
sphere -1 0 0 0.5
sphere 0 0 0 0.5
sphere 1 0 0 0.5
sphere 2 0 0 0.5
sphere 3 0 0 0.5
sphere 4 0 0 0.5
sphere 5 0 0 0.5
