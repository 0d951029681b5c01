# A sphere of radius 1e4 used as the ground, seen from 1.5 units above its top (horizon
# ~173 units away, 0.5 degrees below eye level), with small spheres, a quad and a triangle
# standing on it.
# Probes: f32 where it cannot represent the scene: r^2 - |l|^2 subtracts two ~1e8 values
# (ulp 8) so the discriminant, the depth near the horizon and the horizon line itself
# carry f32 error; the naive form also cancels in -b - sqrt(disc) (t ~ 1.5 from ~2e4).

camera eye 0 1.5 0 look 0 0 -20 up 0 1 0 fov 60

sphere 0.0 -10000.0 0.0 10000.0
sphere 0.0 0.5 -6.0 0.5
sphere 2.0 0.3 -10.0 0.3
sphere -3.0 1.0 -25.0 1.0
quad 3.0 0.0 -14.0   5.0 0.0 -15.0   5.0 2.0 -15.0   3.0 2.0 -14.0
triangle -20.0 0.0 -100.0   -10.0 0.0 -100.0   -15.0 8.0 -100.0
