# expect: 3:8 (hex is not decimal)
camera eye 0 0 5 look 0 0 0 up 0 1 0
sphere 0x10 0 0 1
