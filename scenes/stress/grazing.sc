# Triangles and quads nearly parallel to the rays: a corridor 1.7e-3 wide and 2.2e-3 high
# running from 5 to 2e4 units ahead, seen through a 0.0115 degree field of view, so the
# rays meet floor, ceiling and walls at 1e-7 to 1e-4 rad (1e-5 rad about 100 units
# ahead), plus a sliver triangle 2000 units long rising at 1e-5 rad.
# Probes: depth is ill-conditioned (relative error ~u / angle: ~6e-3 at 1e-5 rad in f32)
# and edges seen edge-on; corners where walls meet at grazing incidence.

camera eye 0 0 0 look 0 0 -1 up 0 1 0 fov 0.011459155864419278

quad -0.0009 -0.001 -5.0   0.0008 -0.001 -5.0   0.0008 -0.001 -20000.0   -0.0009 -0.001 -20000.0
quad -0.0009 0.0012 -20000.0   0.0008 0.0012 -20000.0   0.0008 0.0012 -5.0   -0.0009 0.0012 -5.0
quad 0.0008 -0.001 -5.0   0.0008 0.0012 -5.0   0.0008 0.0012 -20000.0   0.0008 -0.001 -20000.0
triangle -0.0009 -0.001 -5.0   -0.0009 -0.001 -20000.0   -0.0009 0.0012 -20000.0
triangle -0.0009 -0.001 -5.0   -0.0009 0.0012 -20000.0   -0.0009 0.0012 -5.0
triangle -0.0002 -0.0004 -30.0   0.0003 0.0196 -2030.0   0.0002 -0.0005 -30.0
