#version 110
// requires: bg_common.glsl bg_hit_code.glsl bg_brdf.glsl bg_fresnel.glsl
// Secondary rays of a G-buffer pixel (docs/shading.md section 9): the reflected ray (mirror share
// plus interface reflection) or the transmitted ray, with its path weight and root rule. Every hit
// pixel writes its child; a child whose weight is not worth following gets weight 0 and alpha 0
// (dead), and the next set's mark pass leaves it out of the stencil.

void bg_spawn(bool transmitted, vec4 hit, vec4 nrm, vec4 base, vec4 coat, float transparency, float ior,
              vec4 ray_d, vec4 weight, float min_weight, out vec4 origin, out vec4 dir, out vec4 w_out)
{
    vec3 d = ray_d.xyz;
    vec3 n = nrm.xyz;
    float index = bg_hit_index(hit.w);
    bool thin = bg_hit_thin(hit.w);
    bool entering = hit.w > 0.0;
    float v = dot(n, -d);
    float cos_i = clamp(v, 0.0, 1.0);
    float opaque = 1.0 - transparency;

    float fresnel = 0.0;
    float cos_t = 0.0;
    float eta = 1.0;
    if (transparency > 0.0 && !thin) {
        float n1 = entering ? 1.0 : ior;
        float n2 = entering ? ior : 1.0;
        fresnel = bg_fresnel(cos_i, n1, n2, cos_t);
        eta = n1 / n2;
    }

    vec3 w;
    vec3 next;
    bool skip_it;
    if (!transmitted) {
        vec3 mirror = bg_mirror_weight(cos_i, base.rgb, nrm.w, coat.w >= 0.0, coat.rgb, coat.w);
        w = weight.rgb * (opaque * mirror + transparency * fresnel);
        next = d - 2.0 * dot(d, n) * n;
        // A ray reflected inside a closed object stays inside it (far root); any other leaves.
        skip_it = thin || entering;
    } else {
        w = weight.rgb * (transparency * (1.0 - fresnel));
        next = thin ? d : eta * d + (eta * cos_i - cos_t) * n;
        skip_it = thin || !entering;
    }
    float m = bg_max3(w);
    float len = length(next);
    bool live = m > 0.0 && m >= min_weight && len > 0.0;
    origin = vec4(hit.xyz, skip_it ? index : -1.0);
    // A dead ray keeps its direction: it is traced only when the stencil skip is off, and then with
    // weight 0 it adds nothing, as a live ray of weight 0 would.
    dir = vec4(len > 0.0 ? next / len : vec3(0.0), skip_it ? -1.0 : index);
    w_out = live ? vec4(w, 1.0) : vec4(0.0);
}
