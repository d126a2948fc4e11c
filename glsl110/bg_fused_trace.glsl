#version 110
// requires: bg_common.glsl bg_hit_code.glsl
// One ray of the fused plan's Whitted tree (docs/shading.md 2.7, 3, 7 and 8): its nearest hit, the
// radiance the hit itself gives (emission, ambient, every light) or the background on a miss, and
// the surface its secondary rays start from, packed as bg_stage_spawn.glsl reads it. The scene's
// objects, materials and lights are unrolled into the three functions declared here, which
// gpu/fused_source.c generates per scene. A ray is (ro.xyz, skip) and (rd.xyz, inside), as in the
// multipass ray maps.

// The nearest root over every object, ties to the object added first: t, the object index win, the
// object-space point and prototype normal of the root, and whether it is the first root.
bool bg_fused_nearest(vec4 ro, vec4 rd, out float t, out float win, out vec3 p_obj, out vec3 n_obj,
                      out bool first_root);

// The hit attributes and material of object win: the hit code (bg_hit_code.glsl), nrm, base, coat
// and tangent as bg_fused_light.glsl packs them, once = emission + opaque x scene ambient x ambient,
// and xparent = (transparency, ior).
void bg_fused_surface(float win, vec3 p_obj, vec3 n_obj, bool first_root, vec3 d, out float code, out vec4 nrm,
                      out vec4 base, out vec4 coat, out vec4 tangent, out vec3 once, out vec2 xparent);

// Adds lw x the term of every light (bg_fused_light.glsl) to radiance, in the scene's light order.
void bg_fused_direct(vec3 p, vec4 nrm, vec4 base, vec4 coat, vec4 tangent, vec3 view, float self, vec3 lw,
                     inout vec3 radiance);

// Adds what the ray of path weight w gives by itself to radiance; false on a miss. On a hit, hit is
// (position, hit code) and nrm, base, coat, xparent describe the surface there.
bool bg_fused_ray(vec4 ro, vec4 rd, vec3 w, vec3 background, inout vec3 radiance, out vec4 hit, out vec4 nrm,
                  out vec4 base, out vec4 coat, out vec2 xparent)
{
    hit = vec4(0.0);
    nrm = vec4(0.0);
    base = vec4(0.0);
    coat = vec4(0.0, 0.0, 0.0, -1.0);
    xparent = vec2(0.0, 1.0);
    float t, win;
    vec3 p_obj, n_obj;
    bool first_root;
    if (!bg_fused_nearest(ro, rd, t, win, p_obj, n_obj, first_root)) {
        radiance += w * background;
        return false;
    }
    float code;
    vec4 tangent;
    vec3 once;
    bg_fused_surface(win, p_obj, n_obj, first_root, rd.xyz, code, nrm, base, coat, tangent, once, xparent);
    vec3 p = ro.xyz + t * rd.xyz;
    hit = vec4(p, code);
    radiance += w * once;
    // Light reaches thin shapes on either side and closed ones only from outside, never a fully
    // transparent surface, and only the side the viewer is on (section 7). A perfect mirror (every
    // layer of roughness 0) has no non-Dirac part: its light term is exactly 0 (bg_brdf.glsl,
    // a = b = 0), so its shadow rays are not traced.
    float opaque = 1.0 - xparent.x;
    vec3 view = -rd.xyz;
    bool diffuse = nrm.w > 0.0 || coat.w > 0.0;
    if (opaque > 0.0 && diffuse && bg_hit_outside(code) && dot(nrm.xyz, view) > 0.0)
        bg_fused_direct(p, nrm, base, coat, tangent, view, win, w * opaque, radiance);
    return true;
}
