# expect: 3:14 (radius 1e-30 below limits::MIN_RADIUS)
camera eye 0 0 5 look 0 0 0 up 0 1 0
sphere 0 0 0 1e-30
