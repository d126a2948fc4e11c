/* The path integrator's part of the fused shader (docs/shading.md 13, docs/gpu_pipeline.md "The
 * path integrator"): what fused_source.c generates in place of the Whitted tree when
 * settings.integrator is BG_INTEGRATOR_PATH. The hit itself is glsl110/bg_path.glsl; generated here
 * are what depends on the scene (its lights and visible lights, its environment) and the chain that
 * follows one ray per hit.
 *
 * GLSL 1.10 bounds a loop by a constant, so the chain runs at most max_depth + 1 times (a constant
 * of the program, as max_depth is part of the layout): every hit of a path, the camera ray's
 * included. A path that ends sooner (a miss, no way on, roulette) leaves the loop by break. */
#include <stdio.h>

#include "../../common/scramble.h"
#include "fused.h"

/* The environment's filtered radiance in direction d (docs/shading.md 7.1), what a miss sees and
 * what the lighting environment brings along a sampled direction. */
static void emit_env_radiance(const gpu_fused_layout *l, gpu_text *t)
{
    char sampler[24], texel[192];
    snprintf(sampler, sizeof sampler, "bg_tex%d", l->env_sampler);
    if (!bgi_gpu_texture_lookup(texel, sizeof texel, sampler, "bg_env_uv(d, bg_env_info)", l->sampler_modes[l->env_sampler]))
        t->failed = true; /* cannot happen: every name above is short */
    bgi_gpu_text_printf(t, "vec3 bg_fused_env_radiance(vec3 d)\n{\n    return bg_env_info.x * %s.rgb;\n}\n", texel);
}

/* The importance tables where the environment has them, else any sampler: bg_env_direction and
 * bg_env_pdf read them only when bg_env_info.w says they exist. */
static const char *marginal(const gpu_fused_layout *l)
{
    return l->env_importance ? "bg_env_marginal" : "bg_tex0";
}

static const char *conditional(const gpu_fused_layout *l)
{
    return l->env_importance ? "bg_env_conditional" : "bg_tex0";
}

/* 13.3 step 1: the background, or the environment, weighed against its own sampling where it lights
 * and the ray was drawn from f. */
static void emit_miss(const gpu_fused_layout *l, gpu_text *t)
{
    bgi_gpu_text_append(t, "vec3 bg_fused_path_miss(vec3 d, float pb)\n{\n");
    if (!l->env)
        bgi_gpu_text_append(t, "    return bg_background;\n");
    else if (!l->env_light)
        bgi_gpu_text_append(t, "    return bg_fused_env_radiance(d);\n");
    else
        bgi_gpu_text_printf(t, "    vec3 le = bg_fused_env_radiance(d);\n"
                               "    return pb > 0.0 ? le * bg_power_heuristic(pb, bg_env_pdf(d, %s, %s, bg_env_info)) : le;\n",
                            marginal(l), conditional(l));
    bgi_gpu_text_append(t, "}\n");
}

/* 13.3 step 2: the visible area light whose object the ray met (bg_path_light, set by
 * bg_fused_surface), by an if-chain over the visible lights, each with its constant index. */
static void emit_emitted(const gpu_fused_layout *l, gpu_text *t)
{
    bgi_gpu_text_append(t, "vec4 bg_fused_path_emitted(vec3 o, vec3 d, float t, float pb)\n{\n");
    for (uint32_t k = 0; k < l->material_count && l->visible_lights; k++) {
        const gpu_fused_material *m = &l->materials[k];
        if (!m->used || !m->light)
            continue;
        unsigned i = (unsigned)(m->light - 1);
        bgi_gpu_text_printf(t, "    if (bg_path_light == %u.0)\n"
                               "        return vec4(bg_path_emitted(o, d, t, pb, bg_lpos[%u], bg_ledge_u[%u], bg_ledge_v[%u], "
                               "bg_lpath[%u]), 1.0);\n",
                            i, i, i, i, i);
    }
    bgi_gpu_text_append(t, "    return vec4(0.0);\n}\n");
}

/* One light's estimate at a hit of level `level` (13.3 step 3): light i (a number or the loop's)
 * from its point of dimension 1 + 2 (i + level S). A Dirac light is Whitted's term; an area light
 * is its point as a point light of the path's radiance (bg_path_area). */
static void emit_light_term(const gpu_fused_layout *l, gpu_text *t, const char *i, const char *indent)
{
    static const char *const dirac = "radiance += lw * bg_fused_light(p, nrm, base, coat, tangent, view, self, "
                                     "bg_lpos[%s], bg_lrad[%s], bg_latt[%s], bg_lspot[%s], bg_lexp[%s]);\n";
    if (!l->area) {
        bgi_gpu_text_append(t, indent);
        bgi_gpu_text_printf(t, dirac, i, i, i, i, i);
        return;
    }
    int slots = (int)l->light_count + 1;
    int first = BGI_DIMENSION_PATH_LIGHT(0, 0, slots), per_light = BGI_DIMENSION_PATH_LIGHT(1, 0, slots) - first;
    int per_level = BGI_DIMENSION_PATH_LIGHT(0, 1, slots) - first;
    bgi_gpu_text_printf(t, "%s{\n%s    vec4 q;\n%s    vec3 e;\n%s    if (bg_ledge_u[%s].w < 0.5)\n%s        ", indent, indent,
                        indent, indent, i, indent);
    bgi_gpu_text_printf(t, dirac, i, i, i, i, i);
    bgi_gpu_text_printf(t, "%s    else if (bg_path_area(p, nrm.xyz, view, way, bg_lpos[%s], bg_ledge_u[%s], bg_ledge_v[%s], "
                           "bg_lpath[%s], bg_sample_square(bg_ph, %d.0 + %d.0 * float(%s) + %d.0 * level, bg_sample_of, "
                           "bg_sample_perm), q, e))\n"
                           "%s        radiance += lw * bg_fused_light(p, nrm, base, coat, tangent, view, self, q, e, "
                           "vec3(1.0, 0.0, 0.0), vec4(0.0, 0.0, 0.0, -2.0), 0.0);\n%s}\n",
                        indent, i, i, i, i, first, per_light, i, per_level, indent, indent);
}

/* Every light in the scene's order, then the environment where it lights, as a directional light of
 * its sampled direction whose radiance is the filtered environment there over its density. */
static void emit_direct(const gpu_fused_layout *l, gpu_text *t)
{
    bgi_gpu_text_append(t, "void bg_fused_path_direct(vec3 p, vec4 nrm, vec4 base, vec4 coat, vec4 tangent, vec3 view, "
                           "float self, vec3 lw, float level, vec4 way, inout vec3 radiance)\n{\n");
    bgi_gpu_fused_each_light(l, t, emit_light_term);
    if (l->env_light) {
        int slots = (int)l->light_count + 1;
        int first = BGI_DIMENSION_PATH_LIGHT((int)l->light_count, 0, slots);
        int per_level = BGI_DIMENSION_PATH_LIGHT((int)l->light_count, 1, slots) - first;
        bgi_gpu_text_printf(t, "    vec3 env_l;\n    float env_pdf;\n    vec2 env_texel;\n"
                               "    if (bg_env_direction(bg_sample_square(bg_ph, %d.0 + %d.0 * level, bg_sample_of, "
                               "bg_sample_perm), %s, %s, bg_env_info, env_l, env_pdf, env_texel)) {\n"
                               "        float env_w = bg_power_heuristic(env_pdf, bg_path_pb(nrm.xyz, view, env_l, way));\n"
                               "        vec3 env_e = bg_fused_env_radiance(env_l) * (env_w / (3.14159265358979 * env_pdf));\n"
                               "        radiance += lw * bg_fused_light(p, nrm, base, coat, tangent, view, self, "
                               "vec4(-env_l, 1.0), env_e, vec3(1.0, 0.0, 0.0), vec4(0.0, 0.0, 0.0, -2.0), 0.0);\n    }\n",
                            first, per_level, marginal(l), conditional(l));
    }
    bgi_gpu_text_append(t, "}\n");
}

void bgi_gpu_fused_path_functions(const gpu_fused_layout *l, gpu_text *t)
{
    bgi_gpu_text_append(t, "// ---- generated: the path integrator's lights and emitters\n");
    if (l->env)
        emit_env_radiance(l, t);
    emit_miss(l, t);
    emit_emitted(l, t);
    emit_direct(l, t);
}

/* The way on (13.3 steps 5 and 6) from the hit just traced: f, reflect or transmit by the event
 * point's e1, roulette by its e2 from BG_PATH_ROULETTE_DEPTH on; bg_pb is the new ray's p_b. */
static void emit_way_on(const gpu_fused_layout *l, gpu_text *t)
{
    int event = BGI_DIMENSION_PATH_EVENT(0), event_step = BGI_DIMENSION_PATH_EVENT(1) - event;
    int direction = BGI_DIMENSION_PATH_DIRECTION(0), direction_step = BGI_DIMENSION_PATH_DIRECTION(1) - direction;
    bgi_gpu_text_printf(t, "    if (!(bg_way.x + bg_way.y + bg_way.z > 0.0))\n        break;\n"
                           "    vec2 bg_ev = bg_sample_square(bg_ph, %d.0 + %d.0 * bg_cw.a, bg_sample_of, bg_sample_perm);\n"
                           "    vec2 bg_xi = bg_sample_square(bg_ph, %d.0 + %d.0 * bg_cw.a, bg_sample_of, bg_sample_perm);\n"
                           "    vec2 bg_pick = bg_path_pick(bg_way, bg_ev.x);\n"
                           "    if (bg_pick.x > 2.5)\n        break;\n"
                           "    vec4 bg_o1, bg_d1, bg_w1;\n"
                           "    if (bg_pick.x < 0.5) {\n"
                           "        bg_path_f_ray(bg_hit, bg_nrm, bg_base, bg_coat, bg_tg, bg_xp.x, bg_rd.xyz, bg_cw.rgb, bg_way, "
                           "bg_pick.y, bg_xi, bg_o1, bg_d1, bg_w1, bg_pb);\n"
                           "    } else {\n"
                           "        bool bg_through = bg_pick.x > 1.5;\n"
                           "        bg_spawn(bg_through, bg_hit, bg_nrm, bg_base, bg_coat, bg_xp.x, abs(bg_xp.y), bg_rd, "
                           "vec4(bg_cw.rgb / (bg_through ? bg_way.z : bg_way.y), 1.0), 0.0, bg_o1, bg_d1, bg_w1);\n",
                        event, event_step, direction, direction_step);
    /* A glossy material's reflected ray from its lobe, of the direction point of its level. */
    if (l->glossy)
        bgi_gpu_text_append(t, "        if (!bg_through && bg_xp.y < 0.0)\n"
                               "            bg_glossy_child(bg_rd.xyz, bg_nrm, bg_coat, bg_xi, bg_d1, bg_w1);\n");
    bgi_gpu_text_append(t, "        bg_pb = 0.0;\n    }\n");
    if (l->mesh)
        bgi_gpu_text_append(t, "    bg_mesh_leave(bg_hit, bg_o1, bg_d1);\n");
    bgi_gpu_text_printf(t, "    if (bg_cw.a >= %d.0) {\n"
                           "        float bg_q = min(1.0, bg_max3(bg_w1.rgb));\n"
                           "        bg_w1 = bg_ev.y < bg_q ? vec4(bg_w1.rgb / bg_q, bg_w1.a) : vec4(0.0);\n    }\n"
                           "    if (bg_w1.a <= 0.0)\n        break;\n"
                           "    bg_ro = bg_o1;\n    bg_rd = bg_d1;\n    bg_cw = vec4(bg_w1.rgb, bg_cw.a + 1.0);\n",
                        BG_PATH_ROULETTE_DEPTH);
}

void bgi_gpu_fused_path_main(const gpu_fused_layout *l, gpu_text *t)
{
    const char *ray = "bg_fused_path_ray(bg_ro, bg_rd, bg_cw, bg_pb, bg_last, bg_radiance, bg_hit, bg_nrm, bg_base, "
                      "bg_coat, bg_tg, bg_xp, bg_way)";
    bgi_gpu_text_printf(t, "vec4 bg_tg, bg_way;\nfloat bg_pb = 0.0;\nconst float bg_last = %d.0;\n", l->max_depth);
    if (l->max_depth == 0) {
        bgi_gpu_text_printf(t, "%s;\n", ray);
        return;
    }
    /* loop_rays is max_depth + 1 (fused_layout.c): the constant bound of every hit of a path. */
    bgi_gpu_text_printf(t, "for (int bg_i = 0; bg_i < %d; bg_i++) {\n    if (!%s || bg_cw.a >= %d.0)\n        break;\n",
                        l->loop_rays, ray, l->max_depth);
    emit_way_on(l, t);
    bgi_gpu_text_append(t, "}\n");
}
