# The Utah teapot (scenes/meshes/teapot.obj: 992 faces, fan-triangulated), from above and to
# the side, standing on a floor quad.
camera eye 24 18 32 look 0 -1 0 up 0 1 0 fov 50
mesh meshes/teapot.obj
quad -30 -7.875 -30  30 -7.875 -30  30 -7.875 30  -30 -7.875 30
