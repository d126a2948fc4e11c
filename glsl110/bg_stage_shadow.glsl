#version 110
// requires: bg_common.glsl bg_light.glsl
// Shadow segments against one object (docs/shading.md sections 2.8 and 7).

int bg_shape_span(vec3 o, vec3 d, out vec2 t, out vec3 n0, out vec3 n1);

// True when the open segment p + t l, 0 < t < dist (1 - BG_SHADOW_END_REL) (dist < 0: unbounded),
// meets the object.
bool bg_segment_blocked(vec3 p, vec3 l, float dist, mat4 to_object)
{
    vec3 o = (to_object * vec4(p, 1.0)).xyz;
    vec3 d = (to_object * vec4(l, 0.0)).xyz;
    vec2 t;
    vec3 n0, n1;
    int count = bg_shape_span(o, d, t, n0, n1);
    if (count == 0)
        return false;
    // The segment is open at the light's end by 2^-16 of its length (BG_SHADOW_END_REL in
    // cpu_internal.h, which says why this value): a light lying on a surface ends the segment on
    // it, and float cannot tell on which side of dist that root falls. A local constant, since
    // this file is inlined once per shape of a batch. GLSL 1.10 allows no exp2() here.
    const float BG_SHADOW_END_REL = 1.52587890625e-05;
    bool before_light = dist < 0.0 || t.x < dist * (1.0 - BG_SHADOW_END_REL);
    if (count == 1)
        return t.x > 0.0 && before_light;
    return t.y > 0.0 && before_light;
}

// 0.0 when the object blocks the light from p, else 1.0. A light that cannot contribute, or (with
// skip_facing) one the surface faces away from, is not tested: the light pass gives it nothing.
float bg_shadow_visibility(vec3 p, vec3 n, mat4 to_object, vec4 pos_type, vec3 radiance, vec3 attenuation,
                           vec4 spot, float spot_exponent, bool skip_facing)
{
    vec3 l, e;
    float dist;
    if (!bg_light_at(p, pos_type, radiance, attenuation, spot, spot_exponent, l, dist, e))
        return 1.0;
    if (skip_facing && dot(n, l) <= 0.0)
        return 1.0;
    return bg_segment_blocked(p, l, dist, to_object) ? 0.0 : 1.0;
}
