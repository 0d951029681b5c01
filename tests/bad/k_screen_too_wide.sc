# expect: 2:1 (K focal lengths give a screen 6e302 wide at 640x480: past limits::MAX_SCREEN)
camera eye 0 0 5 look 0 0 0 up 0 1 0 K 1e-300 1e-300 320 240
sphere 0 0 0 1
