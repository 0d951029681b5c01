# expect: 4:1 (second camera)
camera eye 0 0 5 look 0 0 0 up 0 1 0
sphere 0 0 0 1
camera eye 0 0 6 look 0 0 0 up 0 1 0
