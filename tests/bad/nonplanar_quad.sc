# expect: 3:1 (vertex D off the plane)
camera eye 0 0 5 look 0 0 0 up 0 1 0
quad 0 0 0  1 0 0  1 1 0  0 1 0.1
