# expect: 3:1 (two vertices the same)
camera eye 0 0 5 look 0 0 0 up 0 1 0
triangle 0 0 0  1 0 0  0 0 0
