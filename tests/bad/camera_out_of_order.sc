# expect: 2:8 (look before eye)
camera look 0 0 0 eye 0 0 5 up 0 1 0
sphere 0 0 0 1
