# expect: 3:10 (inf is not a number)
camera eye 0 0 5 look 0 0 0 up 0 1 0
sphere 0 inf 0 1
