# expect: 3:1 (keywords are lower case)
camera eye 0 0 5 look 0 0 0 up 0 1 0
Sphere 0 0 0 1
