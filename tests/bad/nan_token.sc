# expect: 3:8 (nan is not a number)
camera eye 0 0 5 look 0 0 0 up 0 1 0
sphere nan 0 0 1
