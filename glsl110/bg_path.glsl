#version 110
// requires: bg_common.glsl bg_hit_code.glsl bg_brdf.glsl bg_fresnel.glsl bg_basis.glsl bg_scramble.glsl bg_glossy.glsl bg_area_light.glsl
// One hit of the fused plan's path integrator (docs/shading.md 13): the light the hit meets (a miss,
// an emitter), the lights sampled towards it (next-event estimation) and the way on, with what each
// way weighs. The twin of src/betelgeuse/cpu/path.c. The surface arrives packed as
// bg_fused_light.glsl says; a ray is (ro.xyz, skip) and (rd.xyz, inside) as in bg_fused_trace.glsl,
// its path weight beta and level in cw, and pb is the density it was drawn from f with (0: the camera
// ray, or a Dirac way). way = (P_f, P_refl, P_refr, r_g): the shares of the three ways on (13.3 step
// 5) and the roughness of the lobe the f way mixes with the cosine.

// Generated per scene (gpu/fused/fused_source.c), as for bg_fused_trace.glsl:
bool bg_fused_nearest(vec4 ro, vec4 rd, out float t, out float win, out vec3 p_obj, out vec3 n_obj,
                      out bool first_root);
// The hit's surface; once is the material's emission (0 for a visible area light's object, which
// sets bg_path_light) plus, with settings.path_ambient, the opaque share of its ambient term.
void bg_fused_surface(float win, vec3 p_obj, vec3 n_obj, bool first_root, vec3 d, out float code, out vec4 nrm,
                      out vec4 base, out vec4 coat, out vec4 tangent, out vec3 once, out vec2 xparent);
// Adds lw x every light's and the lighting environment's estimate at a hit of the given level.
void bg_fused_path_direct(vec3 p, vec4 nrm, vec4 base, vec4 coat, vec4 tangent, vec3 view, float self, vec3 lw,
                          float level, vec4 way, inout vec3 radiance);
// What a ray of direction d drawn with density pb sees where it meets nothing, MIS weight included.
vec3 bg_fused_path_miss(vec3 d, float pb);
// What the visible area light's object bg_path_light gives the ray from o along d that meets it at
// distance t, MIS weight included, and in a 1 (0 for any other object, which gives nothing here).
vec4 bg_fused_path_emitted(vec3 o, vec3 d, float t, float pb);

// The power heuristic p^2 / (p^2 + q^2) for the way of density p against the other's q, from the
// smaller ratio so that no square overflows; 1 where the other way cannot draw the direction.
float bg_power_heuristic(float p, float q)
{
    if (!(q > 0.0))
        return 1.0;
    if (!(p > 0.0))
        return 0.0;
    float r = p > q ? q / p : p / q;
    float r2 = r * r;
    return p > q ? 1.0 / (1.0 + r2) : r2 / (1.0 + r2);
}

// The shares of the three ways on at a hit (13.3 step 5), with reach whether lights reach it (3):
// W_f = opaque rho, W_refl = opaque m + T F, W_refr = T (1 - F), each share its largest channel over
// their sum (all 0: no way on), and r_g, the coat's roughness if the material has one, else the base's.
vec4 bg_path_ways(bool reach, vec4 hit, vec4 nrm, vec4 base, vec4 coat, vec2 xparent, vec3 d)
{
    float transparency = xparent.x, ior = abs(xparent.y);
    bool thin = bg_hit_thin(hit.w);
    bool entering = hit.w > 0.0;
    float cos_i = clamp(dot(nrm.xyz, -d), 0.0, 1.0);
    float opaque = 1.0 - transparency;
    float fresnel = 0.0, cos_t = 0.0;
    if (transparency > 0.0 && !thin)
        fresnel = bg_fresnel(cos_i, entering ? 1.0 : ior, entering ? ior : 1.0, cos_t);
    bool has_coat = coat.w >= 0.0;
    vec3 mirror = bg_mirror_weight(cos_i, base.rgb, nrm.w, has_coat, coat.rgb, coat.w);
    float m_refl = bg_max3(opaque * mirror + transparency * fresnel);
    float m_refr = transparency * (1.0 - fresnel);
    float m_f = 0.0;
    if (reach) {
        vec3 split = bg_schlick_split(nrm.w);
        vec3 rho = bg_schlick_s(base.rgb, cos_i) * (split.x + split.y);
        if (has_coat) {
            vec3 split_c = bg_schlick_split(coat.w);
            vec3 s_c = bg_schlick_s(coat.rgb, cos_i);
            rho = s_c * (split_c.x + split_c.y) + (1.0 - s_c) * rho;
        }
        m_f = bg_max3(opaque * rho);
    }
    float sum = m_f + m_refl + m_refr;
    float r_g = has_coat ? coat.w : nrm.w;
    if (!(sum > 0.0))
        return vec4(0.0, 0.0, 0.0, r_g);
    return vec4(m_f / sum, m_refl / sum, m_refr / sum, r_g);
}

// p_f(L) of 13.3 step 5: the density of the cosine and lobe mix of roughness r at the unit direction
// l above the unit normal n, seen from view.
float bg_path_f_pdf(vec3 n, vec3 view, vec3 l, float r)
{
    float ln = dot(l, n);
    if (!(ln > 0.0))
        return 0.0;
    float b = 4.0 * r * (1.0 - r);
    float q_c = 1.0 - 0.5 * b;
    float pdf = q_c * ln / 3.14159265358979;
    if (!(b > 0.0))
        return pdf;
    vec3 h = view + l;
    if (!(bg_maxabs3(h) > 0.0))
        return pdf;
    h = normalize(h);
    float t = min(dot(n, h), 1.0), vh = dot(view, h);
    float z_den = 1.0 + r * t * t - t * t;
    float z = z_den > 0.0 ? r / (z_den * z_den) : 0.0;
    if (t > 0.0 && vh > 0.0)
        pdf += (1.0 - q_c) * z * t / (4.0 * 3.14159265358979 * vh);
    return pdf;
}

// p_b(L): the density with which the f way draws l at a hit of shares way (0 where it cannot).
float bg_path_pb(vec3 n, vec3 view, vec3 l, vec4 way)
{
    return way.x > 0.0 ? way.x * bg_path_f_pdf(n, view, l, way.w) : 0.0;
}

// An area light of the path integrator (13.1, 13.3 step 3) as the point light bg_fused_light
// evaluates: its point q at the sample uv (bg_area_light_pos), and the radiance e that makes that
// light's pi f e v' the estimate w f Le v' / p_l; false when it brings nothing (behind a rectangle,
// inside a sphere). le = (Le, 1 where the light is visible and so weighed against p_b).
bool bg_path_area(vec3 p, vec3 n, vec3 view, vec4 way, vec4 pos, vec4 edge_u, vec4 edge_v, vec4 le, vec2 uv,
                  out vec4 q, out vec3 e)
{
    const float pi = 3.14159265358979;
    q = bg_area_light_pos(p, pos, edge_u, edge_v, uv);
    e = vec3(0.0);
    vec3 to = q.xyz - p;
    float dist2 = dot(to, to);
    if (!(dist2 > 0.0))
        return false;
    vec3 l = to * (1.0 / sqrt(dist2));
    float p_l;
    if (edge_u.w > 1.5) {
        vec3 n_l = normalize(cross(normalize(edge_u.xyz), normalize(edge_v.xyz)));
        float cos_l = -dot(n_l, l);
        float area = length(cross(edge_u.xyz, edge_v.xyz));
        if (!(cos_l > 0.0) || !(area > 0.0))
            return false;
        p_l = dist2 / (area * cos_l);
    } else {
        vec3 c = pos.xyz - p;
        float d2 = dot(c, c), r2 = edge_v.w * edge_v.w;
        if (!(d2 > r2))
            return false;
        float x = r2 / d2;
        p_l = 1.0 / (2.0 * pi * (x / (1.0 + sqrt(1.0 - x))));
    }
    float w = le.w > 0.5 ? bg_power_heuristic(p_l, bg_path_pb(n, view, l, way)) : 1.0;
    e = le.rgb * (w / (pi * p_l));
    return bg_max3(e) > 0.0;
}

// A visible area light's object met by the ray from o along d at distance t (13.3 step 2): Le on its
// front (a rectangle's n_l side, a sphere's outside), weighed against the light's own density of
// that direction from o when the ray was drawn from f (pb > 0).
vec3 bg_path_emitted(vec3 o, vec3 d, float t, float pb, vec4 pos, vec4 edge_u, vec4 edge_v, vec4 le)
{
    float p_l;
    if (edge_u.w > 1.5) {
        vec3 n_l = normalize(cross(normalize(edge_u.xyz), normalize(edge_v.xyz)));
        float cos_l = -dot(d, n_l);
        if (!(cos_l > 0.0))
            return vec3(0.0);
        p_l = t * t / (length(cross(edge_u.xyz, edge_v.xyz)) * cos_l);
    } else {
        vec3 c = pos.xyz - o;
        float d2 = dot(c, c), r2 = edge_v.w * edge_v.w;
        if (!(d2 > r2))
            return vec3(0.0);
        float x = r2 / d2;
        p_l = 1.0 / (6.28318530717959 * (x / (1.0 + sqrt(1.0 - x))));
    }
    return pb > 0.0 ? le.rgb * bg_power_heuristic(pb, p_l) : le.rgb;
}

// The way on for the event e1 (13.3 step 5): 0 f, 1 reflect, 2 transmit, 3 none, in x, and in y e1
// rescaled to [0, 1) within the f way's interval. Where rounding leaves e1 past the shares' sum the
// way is reflect, and none if reflect has no share (the CPU's order of tests).
vec2 bg_path_pick(vec4 way, float e1)
{
    if (e1 < way.x)
        return vec2(0.0, e1 / way.x);
    if (e1 < way.x + way.y || !(way.z > 0.0))
        return vec2(way.y > 0.0 ? 1.0 : 3.0, 0.0);
    return vec2(2.0, 0.0);
}

// The f way's ray (13.3 step 5): its direction from the cosine (when e < q_c) or the lobe, from the
// direction point xi; its origin and root rule those of a reflected ray; its weight
// beta opaque f (L.n) / p_b, alpha 1, or 0 when there is no way on; pb = p_b of its direction.
void bg_path_f_ray(vec4 hit, vec4 nrm, vec4 base, vec4 coat, vec4 tangent, float transparency, vec3 d, vec3 beta,
                   vec4 way, float e, vec2 xi, out vec4 origin, out vec4 dir, out vec4 w, out float pb)
{
    vec3 n = nrm.xyz, view = -d;
    float r = way.w;
    float q_c = 1.0 - 2.0 * r * (1.0 - r);
    vec3 l;
    if (e < q_c) {
        vec3 a, b;
        bg_basis_across(n, a, b);
        vec2 xy = bg_sample_disc(xi);
        l = xy.x * a + xy.y * b + sqrt(max(0.0, 1.0 - dot(xy, xy))) * n;
    } else {
        l = bg_glossy_reflect(d, n, r, xi);
    }
    float len = length(l);
    l = len > 0.0 ? l / len : n;
    float ln = dot(l, n);
    pb = bg_path_pb(n, view, l, way);
    origin = vec4(hit.xyz, bg_hit_index(hit.w));
    dir = vec4(l, -1.0);
    w = vec4(0.0);
    if (!(len > 0.0) || !(ln > 0.0) || !(pb > 0.0))
        return;
    vec3 f = bg_brdf(n, tangent.xyz, view, l, base.rgb, nrm.w, base.a, coat.w >= 0.0, coat.rgb, coat.w, tangent.w);
    w = vec4(beta * ((1.0 - transparency) * ln / pb) * f, 1.0);
    if (!(bg_max3(w.rgb) > 0.0))
        w = vec4(0.0);
}

// One hit of the path (13.3 steps 1-3): adds the miss's or the hit's own light and the lights
// sampled towards the hit to radiance; false where the path ends: a miss, or a visible area light's
// object, which emits and does nothing else. On a hit, hit is (position, hit code), the surface is
// nrm, base, coat, tangent, xparent, and way its shares of the ways on. The lights are weighed
// against the f way's density of their direction, except at the last level (cw.a = last): no way
// on follows there, so they take weight 1.
bool bg_fused_path_ray(vec4 ro, vec4 rd, vec4 cw, float pb, float last, inout vec3 radiance, out vec4 hit,
                       out vec4 nrm, out vec4 base, out vec4 coat, out vec4 tangent, out vec2 xparent, out vec4 way)
{
    hit = vec4(0.0);
    nrm = vec4(0.0);
    base = vec4(0.0);
    coat = vec4(0.0, 0.0, 0.0, -1.0);
    tangent = vec4(0.0);
    xparent = vec2(0.0, 1.0);
    way = vec4(0.0);
    float t, win;
    vec3 p_obj, n_obj;
    bool first_root;
    if (!bg_fused_nearest(ro, rd, t, win, p_obj, n_obj, first_root)) {
        radiance += cw.rgb * bg_fused_path_miss(rd.xyz, pb);
        return false;
    }
    float code;
    vec3 once;
    bg_fused_surface(win, p_obj, n_obj, first_root, rd.xyz, code, nrm, base, coat, tangent, once, xparent);
    vec3 p = ro.xyz + t * rd.xyz;
    hit = vec4(p, code);
    vec4 emitter = bg_fused_path_emitted(ro.xyz, rd.xyz, t, pb);
    radiance += cw.rgb * (once + emitter.rgb);
    if (emitter.a > 0.5)
        return false;
    // Lights reach the hit as in Whitted's (section 7); a perfect mirror has no non-Dirac part, so
    // neither its lights nor its f way are traced.
    float opaque = 1.0 - xparent.x;
    vec3 view = -rd.xyz;
    bool reach = opaque > 0.0 && bg_hit_outside(code) && dot(nrm.xyz, view) > 0.0;
    way = bg_path_ways(reach, hit, nrm, base, coat, xparent, rd.xyz);
    bool diffuse = nrm.w > 0.0 || coat.w > 0.0;
    if (reach && diffuse)
        bg_fused_path_direct(p, nrm, base, coat, tangent, view, win, cw.rgb * opaque, cw.a,
                             cw.a >= last ? vec4(0.0, way.yzw) : way, radiance);
    return true;
}
