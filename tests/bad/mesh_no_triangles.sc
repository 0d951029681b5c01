# expect: 3:6 (a mesh whose file holds no triangles: this scene itself)
camera eye 0 0 5 look 0 0 0 up 0 1 0
mesh mesh_no_triangles.sc
