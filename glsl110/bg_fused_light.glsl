#version 110
// requires: bg_common.glsl bg_light.glsl bg_brdf.glsl
// One light's term at a hit of the fused plan (docs/shading.md 2.8, 7 and 8), its shadow test
// included: the multipass does the same work in a shadow pass (bg_stage_shadow.glsl) and a light
// pass (bg_stage_light.glsl). The surface arrives packed as the multipass G-buffer packs it:
//   nrm      unit normal facing the ray, base roughness
//   base     base reflectance, base isotropy
//   coat     coat reflectance, coat roughness (< 0: the material has no coat)
//   tangent  unit tangent, coat isotropy
// The light is packed as bg_light.glsl says.

// Generated per scene (gpu/fused_source.c): whether a shadow caster other than object `self` meets
// the open segment from p along l of length dist (dist < 0: unbounded).
bool bg_fused_blocked(vec3 p, vec3 l, float dist, float self);

// pi f E v' of a light that reaches p unblocked, else 0. The light is not tested for a shadow when
// the surface faces away from it (v' <= 0): it brings nothing there anyway (section 7).
vec3 bg_fused_light(vec3 p, vec4 nrm, vec4 base, vec4 coat, vec4 tangent, vec3 view, float self, vec4 pos_type,
                    vec3 radiance, vec3 attenuation, vec4 spot, float spot_exponent)
{
    vec3 l, e;
    float dist;
    if (!bg_light_at(p, pos_type, radiance, attenuation, spot, spot_exponent, l, dist, e))
        return vec3(0.0);
    float vl = dot(nrm.xyz, l);
    if (!(vl > 0.0))
        return vec3(0.0);
    if (bg_fused_blocked(p, l, dist, self))
        return vec3(0.0);
    vec3 f = bg_brdf(nrm.xyz, tangent.xyz, view, l, base.rgb, nrm.w, base.a, coat.w >= 0.0, coat.rgb, coat.w,
                     tangent.w);
    return 3.14159265 * f * e * vl;
}
