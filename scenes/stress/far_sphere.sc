# Small spheres far away: radius 0.3 at 1e4, radius 1 at 5e4, radius 3 at 1e5 units, seen
# through a 0.0115 degree field of view (each about 50-60 pixels across).
# Probes: the textbook quadratic b^2 - 4ac cancels (b^2 ~ 4e8..4e10, disc ~ 4 r^2) and loses
# the spheres in f32; the stable form keeps them (error ~4u|oc| at the silhouette).

camera eye 0 0 0 look 0 0 -1 up 0 1 0 fov 0.011459155864419278

sphere -0.4 0.05 -10000.0 0.3
sphere 0.5 2.5 -50000.0 1.0
sphere 4.0 -0.5 -100000.0 3.0
