# The Stanford bunny (3,674 triangles, scenes/meshes/bunny.obj), seen from the front and a
# little above. Primitive ids 0..3673 are the mesh's triangles in file order.
camera eye 6 9 23 look 0 4.7 0 up 0 1 0 fov 42
mesh meshes/bunny.obj
