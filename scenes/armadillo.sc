# The Stanford armadillo (52,000 triangles, scenes/meshes/armadillo.obj), seen from the front.
camera eye 60 60 -330 look 0 22 0 up 0 1 0 fov 40
mesh meshes/armadillo.obj
