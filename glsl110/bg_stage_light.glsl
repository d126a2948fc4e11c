#version 110
// requires: bg_common.glsl bg_light.glsl bg_brdf.glsl
// One light's term at a G-buffer pixel (docs/shading.md sections 7 and 8), before the path weight.
// rgb is pi f E v' x visibility; a is 1.0 when the light was evaluated, so that a pixel no light
// reaches can be discarded instead of blending a zero.

vec4 bg_light_term(vec3 p, vec3 n, vec3 view, vec3 tangent, vec3 base_c, float base_r, float base_p,
                   bool has_coat, vec3 coat_c, float coat_r, float coat_p, vec4 pos_type, vec3 radiance,
                   vec3 attenuation, vec4 spot, float spot_exponent, float visible, bool skip_facing)
{
    vec3 l, e;
    float dist;
    if (!bg_light_at(p, pos_type, radiance, attenuation, spot, spot_exponent, l, dist, e))
        return vec4(0.0);
    float vl = dot(n, l);
    if (skip_facing && !(vl > 0.0))
        return vec4(0.0);
    vec3 f = bg_brdf(n, tangent, view, l, base_c, base_r, base_p, has_coat, coat_c, coat_r, coat_p);
    // Without the facing skip the term is still computed but must vanish for v' <= 0.
    float facing = vl > 0.0 ? 1.0 : 0.0;
    return vec4(3.14159265 * f * e * (vl * facing * visible), 1.0);
}
