# expect: 2:1 (up parallel to look - eye)
camera eye 0 0 5 look 0 0 0 up 0 0 2
sphere 0 0 0 1
