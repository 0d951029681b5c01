# expect: 3:1 (dart: corner B turns inwards)
camera eye 0 0 5 look 0 0 0 up 0 1 0
quad 0 0 0  1 0.3 0  2 0 0  1 2 0
