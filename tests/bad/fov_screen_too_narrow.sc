# expect: 2:1 (fov 1e-300: a screen 1.7e-302 wide at 640x480, below limits::MIN_SCREEN, the rule K meets)
camera eye 0 0 5 look 0 0 0 up 0 1 0 fov 1e-300
sphere 0 0 0 1
