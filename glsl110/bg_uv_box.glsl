#version 110
// requires:
// Box UV mapping (docs/shading.md 4), ported from box() in uv_map.c: the face of the dominant
// axis shows the whole texture, upright seen from outside. Ties go to x, then y, so that an edge
// point gets the same face in both renderers.

vec2 bg_uv_map(vec3 p, out vec3 dpdu)
{
    vec3 a = abs(p);
    vec2 uv;
    if (a.x >= a.y && a.x >= a.z) {
        if (p.x >= 0.0) {
            uv.x = 0.5 * (1.0 - p.z);
            dpdu = vec3(0.0, 0.0, -1.0);
        } else {
            uv.x = 0.5 * (1.0 + p.z);
            dpdu = vec3(0.0, 0.0, 1.0);
        }
        uv.y = 0.5 * (1.0 + p.y);
    } else if (a.y >= a.z) {
        uv.x = 0.5 * (1.0 + p.x);
        uv.y = p.y >= 0.0 ? 0.5 * (1.0 - p.z) : 0.5 * (1.0 + p.z);
        dpdu = vec3(1.0, 0.0, 0.0);
    } else {
        if (p.z >= 0.0) {
            uv.x = 0.5 * (1.0 + p.x);
            dpdu = vec3(1.0, 0.0, 0.0);
        } else {
            uv.x = 0.5 * (1.0 - p.x);
            dpdu = vec3(-1.0, 0.0, 0.0);
        }
        uv.y = 0.5 * (1.0 + p.y);
    }
    return uv;
}
