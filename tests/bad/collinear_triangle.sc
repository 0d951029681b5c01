# expect: 3:1 (collinear vertices)
camera eye 0 0 5 look 0 0 0 up 0 1 0
triangle 0.1 0.2 0.3  0.2 0.4 0.6  0.3 0.6 0.9
