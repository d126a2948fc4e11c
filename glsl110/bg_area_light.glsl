#version 110
// requires: bg_basis.glsl
// Area lights (docs/shading.md 7), the twin of src/betelgeuse/cpu/area_light.c. Beside bg_light.glsl's
// packing, an area light has
//   edge_u  xyz = a rectangle's first edge, w = the kind: 0.0 point or directional, 1.0 sphere,
//           2.0 rectangle
//   edge_v  xyz = a rectangle's second edge, w = a sphere's radius
// and uv, its unit-square point at this camera sample (bg_scramble.glsl).

// The point of the sphere (centre c, radius r) seen from p, uniform in solid angle; c from inside.
vec3 bg_sphere_light_point(vec3 c, float r, vec3 p, vec2 uv)
{
    vec3 to = c - p;
    float d2 = dot(to, to), r2 = r * r;
    if (!(d2 > r2))
        return c;
    float dist = sqrt(d2);
    vec3 w = to / dist;
    float x = r2 / d2;
    float one_minus_cos = uv.x * (x / (1.0 + sqrt(1.0 - x)));
    float cos_t = 1.0 - one_minus_cos;
    float sin2 = one_minus_cos * (2.0 - one_minus_cos);
    float sin_t = sqrt(max(sin2, 0.0));
    float phi = 6.283185307 * uv.y;
    vec3 a, b;
    bg_basis_across(w, a, b);
    vec3 dir = cos_t * w + sin_t * (cos(phi) * a + sin(phi) * b);
    float t = dist * cos_t - sqrt(max(r2 - d2 * sin2, 0.0));
    return p + t * dir;
}

// The light's point at this sample, packed as bg_light.glsl's pos_type: an area light's sample
// point as a point light; point and directional lights as they are.
vec4 bg_area_light_pos(vec3 p, vec4 pos_type, vec4 edge_u, vec4 edge_v, vec2 uv)
{
    if (edge_u.w < 0.5)
        return pos_type;
    if (edge_u.w < 1.5)
        return vec4(bg_sphere_light_point(pos_type.xyz, edge_v.w, p, uv), 0.0);
    return vec4(pos_type.xyz + uv.x * edge_u.xyz + uv.y * edge_v.xyz, 0.0);
}

// The radiance of the light's point q (bg_area_light_pos) towards p: a rectangle's times the cosine
// between its normal and the direction to p, 0 behind it (bg_light_at then skips the light).
vec3 bg_area_light_radiance(vec3 p, vec4 q, vec4 edge_u, vec4 edge_v, vec3 radiance)
{
    if (edge_u.w < 1.5)
        return radiance;
    vec3 n = normalize(cross(normalize(edge_u.xyz), normalize(edge_v.xyz)));
    vec3 to_p = p - q.xyz;
    float len = sqrt(dot(to_p, to_p));
    float cos_l = len > 0.0 ? dot(n, to_p) / len : 0.0;
    return cos_l > 0.0 ? radiance * cos_l : vec3(0.0);
}
