#version 110
// requires: bg_common.glsl
// One light's direction, distance and arriving radiance at a point (docs/shading.md 7), ported from
// light_arrival() in src/betelgeuse/shade.c. The light is packed by the host:
//   pos_type    xyz = position (w = 0.0, point light) or the unit direction s it shines along
//               (w = 1.0, directional light)
//   radiance    color * intensity
//   attenuation (kc, kl, kq)
//   spot        xyz = unit spot axis, w = cos(cutoff), or -2.0 for no cone (cutoff 180)
//   spot_exponent  e >= 0; the spot factor is 1 when e == 0.0
// Returns false when the light brings nothing, so the caller can skip its shadow ray. Otherwise
// l = unit direction towards the light, dist = the shadow segment length (-1.0: infinite, for a
// directional light) and e = the radiance arriving at p.

bool bg_light_at(vec3 p, vec4 pos_type, vec3 radiance, vec3 attenuation, vec4 spot,
                 float spot_exponent, out vec3 l, out float dist, out vec3 e)
{
    l = vec3(0.0);
    dist = 0.0;
    e = vec3(0.0);
    if (pos_type.w > 0.5) {
        if (!(bg_maxabs3(pos_type.xyz) > 0.0))
            return false;
        l = bg_normalize_or(-pos_type.xyz, vec3(0.0));
        dist = -1.0;
        e = radiance;
        return bg_max3(e) > 0.0;
    }
    vec3 to_light = pos_type.xyz - p;
    float len = sqrt(dot(to_light, to_light));
    // A point exactly at the light has no direction towards it.
    if (!(len > 0.0))
        return false;
    l = to_light / len;
    float k = 1.0;
    // Cosines are never below -1, so the -2.0 sentinel can be told from every real cone.
    if (spot.w >= -1.0) {
        float cos_angle = -dot(l, spot.xyz);
        if (cos_angle < spot.w)
            return false;
        // pow(0, e) is undefined in GLSL only for e <= 0, but pow is commonly exp2(e log2 x),
        // which would pass through log2(0) = -Inf; the limit for e > 0 is 0.
        if (spot_exponent > 0.0)
            k = cos_angle > 0.0 ? pow(cos_angle, spot_exponent) : 0.0;
    }
    float att = attenuation.x + attenuation.y * len + attenuation.z * len * len;
    if (!(att > 0.0))
        return false;
    k = k / att;
    if (!(k > 0.0))
        return false;
    dist = len;
    e = radiance * k;
    return bg_max3(e) > 0.0;
}
