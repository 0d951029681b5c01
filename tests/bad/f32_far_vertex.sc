# expect: 3:1 (vertex 2e18 from the eye)
camera eye 0 0 5 look 0 0 0 up 0 1 0
triangle 0 0 0  2e18 0 0  0 1 0
