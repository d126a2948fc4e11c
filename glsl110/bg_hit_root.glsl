#version 110
// requires: bg_common.glsl
// One shape's root for a ray (docs/shading.md section 2.7). The shape's span comes from the
// bg_shape_*.glsl file linked before it; a pass over several shapes includes this file once per
// shape with bg_shape_span and bg_hit_root renamed by #define (gpu_hit_pass.c).

int bg_shape_span(vec3 o, vec3 d, out vec2 t, out vec3 n0, out vec3 n1);

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
