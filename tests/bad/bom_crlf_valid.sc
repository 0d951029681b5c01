# A valid scene with a UTF-8 BOM and CRLF line ends: must render.
camera eye 0 0 5 look 0 0 0 up 0 1 0 fov 50

sphere 0 0 0 1
triangle -2 -1 -1  2 -1 -1  0 2 -1
