# expect: 3:16 (sphere with 5 numbers)
camera eye 0 0 5 look 0 0 0 up 0 1 0
sphere 0 0 0 1 2
