/* curvature.glsl - earth curvature as every method draws it (src/terrain/terrain.h):
 * a point at horizontal distance r from the eye is lowered by k r^2,
 * k = 1 / (2 R) on a sphere, 0 on a flat earth. Positions are relative to
 * the eye, so r^2 = dot(xy, xy). */
uniform highp float u_earth_drop_per_m2;

vec3 ft_earth_curve(vec3 rel_eye_m)
{
    return vec3(rel_eye_m.xy, rel_eye_m.z - u_earth_drop_per_m2 * dot(rel_eye_m.xy, rel_eye_m.xy));
}
