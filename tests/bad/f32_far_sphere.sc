# expect: 3:1 (sphere 3e38 from the eye: beyond limits::MAX_EYE_DISTANCE)
camera eye 0 0 5 look 0 0 0 up 0 1 0
sphere 3e38 0 0 1
