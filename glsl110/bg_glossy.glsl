#version 110
// requires: bg_basis.glsl
// Glossy reflection (docs/shading.md 9.1), the twin of src/betelgeuse/cpu/glossy.c: the reflected
// ray of a glossy material mirrored about a normal drawn from Schlick's zenith factor Z(t) / pi (the
// GGX distribution of alpha^2 = r), r the coat's roughness if the material has a coat, else the
// base's; uv is the lobe's unit-square point at this sample (bg_scramble.glsl).

// d mirrored about the drawn normal (not normalised); below the surface when dot(result, n) <= 0.
vec3 bg_glossy_reflect(vec3 d, vec3 n, float r, vec2 uv)
{
    float q = 1.0 + (r - 1.0) * uv.x;
    float cos_h = sqrt((1.0 - uv.x) / q), sin_h = sqrt(r * uv.x / q);
    float phi = 6.283185307 * uv.y;
    vec3 a, b;
    bg_basis_across(n, a, b);
    vec3 h = cos_h * n + sin_h * (cos(phi) * a + sin(phi) * b);
    return d - 2.0 * dot(d, h) * h;
}

// The reflected child of bg_spawn (dir, w) of a hit with normal and base roughness nrm and coat
// (coat.w < 0: none) turned into the glossy one; roughness 0 keeps the mirror, a direction below the
// surface kills the child.
void bg_glossy_child(vec3 d, vec4 nrm, vec4 coat, vec2 uv, inout vec4 dir, inout vec4 w)
{
    float r = coat.w >= 0.0 ? coat.w : nrm.w;
    if (!(r > 0.0) || !(w.a > 0.0))
        return;
    vec3 g = bg_glossy_reflect(d, nrm.xyz, r, uv);
    float len = sqrt(dot(g, g));
    if (!(dot(g, nrm.xyz) > 0.0) || !(len > 0.0))
        w = vec4(0.0);
    else
        dir.xyz = g / len;
}
