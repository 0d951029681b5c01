# expect: 2:1 (eye == look)
camera eye 1 2 3 look 1 2 3 up 0 1 0
sphere 0 0 0 1
