# expect: 3:8 (1e400 overflows f64)
camera eye 0 0 5 look 0 0 0 up 0 1 0
sphere 1e400 0 0 1
