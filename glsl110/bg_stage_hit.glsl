#version 110
// requires: bg_common.glsl bg_hit_code.glsl
// One object against one ray map (docs/shading.md sections 2.7 and 3). The shape's span comes from
// the one bg_shape_*.glsl file linked into the program.

int bg_shape_span(vec3 o, vec3 d, out vec2 t, out vec3 n0, out vec3 n1);

// Depth of a hit at distance t > 0: t / (2 dmax) up to dmax, where the scene's bounded objects are
// and depth steps are finest, then 1 - dmax / (2 t) beyond, so that planes reach the horizon. The
// two halves meet at 1/2 and the whole is increasing, so the depth test LESS keeps the nearest hit.
// A distance so large that the depth rounds to 1.0 fails against the cleared 1.0: a miss.
float bg_depth(float t, float dmax)
{
    return t < dmax ? 0.5 * (t / dmax) : 1.0 - 0.5 * (dmax / t);
}

// The root this object gives the ray, or false. ray_o.w is the object the ray skips, ray_d.w the
// object it travels inside (far root only).
bool bg_hit_root(vec4 ray_o, vec4 ray_d, float index, mat4 to_object, out float t, out vec3 p_obj,
                 out vec3 n_obj, out bool first_root)
{
    t = 0.0;
    p_obj = vec3(0.0);
    n_obj = vec3(0.0, 1.0, 0.0);
    first_root = true;
    if (ray_o.w == index)
        return false;
    vec3 o = (to_object * vec4(ray_o.xyz, 1.0)).xyz;
    vec3 d = (to_object * vec4(ray_d.xyz, 0.0)).xyz;
    vec2 span;
    vec3 n0, n1;
    int count = bg_shape_span(o, d, span, n0, n1);
    if (count == 0)
        return false;
    bool far_only = ray_d.w == index;
    if (count == 1 || (!far_only && span.x > 0.0)) {
        if (!(span.x > 0.0))
            return false;
        t = span.x;
        n_obj = n0;
    } else {
        if (!(span.y > 0.0))
            return false;
        t = span.y;
        n_obj = n1;
        first_root = false;
    }
    p_obj = o + t * d;
    return true;
}

// The world normal facing the ray and whether the ray arrives from outside (section 3).
vec3 bg_hit_normal(mat3 normal_to_world, vec3 n_obj, vec3 d, bool thin, bool first_root, out bool entering)
{
    vec3 n = bg_normalize_or(normal_to_world * n_obj, -d);
    entering = thin ? dot(n, d) <= 0.0 : first_root;
    return entering ? n : -n;
}
