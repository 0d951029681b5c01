# expect: 3:1 (sphere with 3 numbers)
camera eye 0 0 5 look 0 0 0 up 0 1 0
sphere 0 0 0
