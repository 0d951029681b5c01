# expect: 3:1 (unknown keyword)
camera eye 0 0 5 look 0 0 0 up 0 1 0
cube 0 0 0 1
