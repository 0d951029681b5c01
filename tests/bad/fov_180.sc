# expect: 2:42 (fov 180)
camera eye 0 0 5 look 0 0 0 up 0 1 0 fov 180
sphere 0 0 0 1
