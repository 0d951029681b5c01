# expect: 3:1 (principal point 1e9 pixels off a 640x480 image: past limits::MAX_PRINCIPAL_OFFSET)
sphere 0 0 0 1
camera eye 0 0 5 look 0 0 0 up 0 1 0 K 500 500 1e9 240
