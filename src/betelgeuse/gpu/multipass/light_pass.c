/* Shadow and lighting passes (docs/gpu_pipeline.md). Lights go in groups of four: one
 * shadow pass per shadow-casting object and group multiplies a 0 into the RGBA visibility channel of
 * each light the object blocks; one lighting pass per group adds the Schlick terms of its lights,
 * unrolled to the group's exact size, into the accumulation texture. Ambient and emission, already
 * weighted in the G-buffer's ONCE slot, are added by a pass of their own. */
#include <stdio.h>
#include <string.h>

#include "../../common/scramble.h"
#include "multipass.h"

static int group_size(const bg_scene_state *state, int group)
{
    int n = (int)state->light_count - group * GPU_LIGHTS_PER_GROUP;
    return n > GPU_LIGHTS_PER_GROUP ? GPU_LIGHTS_PER_GROUP : (n < 0 ? 0 : n);
}

/* The most uniforms light_uniforms declares. */
#define LIGHT_UNIFORM_COUNT 10

/* The uniform arrays of a group of `count` lights, appended to u[*n ..]; with area lights, their
 * shapes and the uniforms of the sample that places their points. */
static void light_uniforms(macs_uniform_desc *u, int *n, int count, bool area)
{
    u[(*n)++] = (macs_uniform_desc){"bg_lpos", MACS_UNIFORM_VEC4, count};
    u[(*n)++] = (macs_uniform_desc){"bg_lrad", MACS_UNIFORM_VEC3, count};
    u[(*n)++] = (macs_uniform_desc){"bg_latt", MACS_UNIFORM_VEC3, count};
    u[(*n)++] = (macs_uniform_desc){"bg_lspot", MACS_UNIFORM_VEC4, count};
    u[(*n)++] = (macs_uniform_desc){"bg_lexp", MACS_UNIFORM_FLOAT, count};
    if (!area)
        return;
    u[(*n)++] = (macs_uniform_desc){"bg_ledge_u", MACS_UNIFORM_VEC4, count};
    u[(*n)++] = (macs_uniform_desc){"bg_ledge_v", MACS_UNIFORM_VEC4, count};
    u[(*n)++] = (macs_uniform_desc){"bg_pixel_at", MACS_UNIFORM_VEC2, 0};
    u[(*n)++] = (macs_uniform_desc){"bg_sample_of", MACS_UNIFORM_VEC4, 0};
    u[(*n)++] = (macs_uniform_desc){"bg_sample_perm", MACS_UNIFORM_VEC4, 0};
}

/* Where light i of a group (k in the scene) is at this sample, as the arguments of bg_light_at:
 * declares its point (an area light's, bg_area_light.glsl, of the light's own dimension of the
 * scramble) into main and prints the position and radiance expressions into pos and rad. */
static void light_place(gpu_text *main, bool area, int i, int k, const char *indent, char *pos, char *rad, size_t size)
{
    if (!area) {
        snprintf(pos, size, "bg_lpos[%d]", i);
        snprintf(rad, size, "bg_lrad[%d]", i);
        return;
    }
    bgi_gpu_text_printf(main, "%svec4 bg_q%d = bg_area_light_pos(bg_h.xyz, bg_lpos[%d], bg_ledge_u[%d], bg_ledge_v[%d], "
                              "bg_sample_square(bg_ph, %d.0, bg_sample_of, bg_sample_perm));\n",
                        indent, i, i, i, i, BGI_DIMENSION_LIGHT(k));
    snprintf(pos, size, "bg_q%d", i);
    snprintf(rad, size, "bg_area_light_radiance(bg_h.xyz, bg_q%d, bg_ledge_u[%d], bg_ledge_v[%d], bg_lrad[%d])", i, i, i, i);
}

bg_status bgi_gpu_set_light_uniforms(bg_renderer *r, macs_pass *pass, const bg_scene_state *state, int first, int count)
{
    float pos[4 * GPU_LIGHTS_PER_GROUP], rad[3 * GPU_LIGHTS_PER_GROUP], att[3 * GPU_LIGHTS_PER_GROUP];
    float spot[4 * GPU_LIGHTS_PER_GROUP], ex[GPU_LIGHTS_PER_GROUP];
    float eu[4 * GPU_LIGHTS_PER_GROUP], ev[4 * GPU_LIGHTS_PER_GROUP];
    for (int i = 0; i < count; i++) {
        gpu_packed_light p = bgi_gpu_light_pack(state, (uint32_t)(first + i));
        memcpy(&pos[4 * i], p.pos, sizeof p.pos);
        memcpy(&rad[3 * i], p.rad, sizeof p.rad);
        memcpy(&att[3 * i], p.att, sizeof p.att);
        memcpy(&spot[4 * i], p.spot, sizeof p.spot);
        ex[i] = p.exponent;
        memcpy(&eu[4 * i], p.edge_u, sizeof p.edge_u);
        memcpy(&ev[4 * i], p.edge_v, sizeof p.edge_v);
    }
    macs_status ms = macs_pass_set_uniform(pass, "bg_lpos", pos);
    if (!ms)
        ms = macs_pass_set_uniform(pass, "bg_lrad", rad);
    if (!ms)
        ms = macs_pass_set_uniform(pass, "bg_latt", att);
    if (!ms)
        ms = macs_pass_set_uniform(pass, "bg_lspot", spot);
    if (!ms)
        ms = macs_pass_set_uniform(pass, "bg_lexp", ex);
    if (!ms && r->multipass->features.area)
        ms = macs_pass_set_uniform(pass, "bg_ledge_u", eu);
    if (!ms && r->multipass->features.area)
        ms = macs_pass_set_uniform(pass, "bg_ledge_v", ev);
    return ms ? bgi_gpu_fail_macs(r, ms, "light uniforms") : BG_OK;
}

/* The three uniforms of the view's sample on one pass (NULL: none to set). */
static macs_status set_sample(macs_pass *pass, const float at[2], const float of[4], const float perm[4])
{
    if (!pass)
        return MACS_OK;
    macs_status ms = macs_pass_set_uniform(pass, "bg_pixel_at", at);
    if (!ms)
        ms = macs_pass_set_uniform(pass, "bg_sample_of", of);
    if (!ms)
        ms = macs_pass_set_uniform(pass, "bg_sample_perm", perm);
    return ms;
}

bg_status bgi_gpu_sample_uniforms_set(bg_renderer *r)
{
    const gpu_features *f = &r->multipass->features;
    if (!f->lens && !f->area && !f->glossy)
        return BG_OK;
    float at[2], of[4], perm[4];
    bgi_gpu_pixel_at(&r->view, at);
    bgi_gpu_sample_of(&r->view, of);
    bgi_gpu_sample_perm(&r->view, perm);
    gpu_passes *p = &r->multipass->passes;
    macs_status ms = f->lens ? set_sample(p->camera, at, of, perm) : MACS_OK;
    if (!ms && f->glossy)
        ms = set_sample(p->reflect, at, of, perm);
    for (int i = 0; f->area && i < p->shadow_count && !ms; i++)
        ms = set_sample(p->shadow[i].pass, at, of, perm);
    for (int g = 0; f->area && g < p->group_count && !ms; g++)
        ms = set_sample(p->light[g], at, of, perm);
    return ms ? bgi_gpu_fail_macs(r, ms, "sample uniforms") : BG_OK;
}

/* Live hit pixels only: both stencil bits set (or only the hit bit when the stencil skip is off). */
static void hit_stencil(const bg_renderer *r, macs_stencil_state *s)
{
    bool live_too = !(r->multipass->key.disable_skips & BG_SKIP_STENCIL);
    s->test = true;
    s->func = MACS_COMPARE_EQUAL;
    s->ref = GPU_STENCIL_HIT | (live_too ? GPU_STENCIL_LIVE : 0u);
    s->read_mask = s->ref;
    s->write_mask = 0;
}

/* The uniforms of one caster of a shadow pass (%d: its place in the pass); a mesh caster's last. */
typedef enum caster_uniform { C_INDEX, C_TO_OBJECT, C_MESH_BASE, C_COUNT } caster_uniform;
static const struct {
    const char *format;
    macs_uniform_type type;
} caster_uniform_row[C_COUNT] = {
    [C_INDEX] = {"bg_index_%d", MACS_UNIFORM_FLOAT},
    [C_TO_OBJECT] = {"bg_to_object_%d", MACS_UNIFORM_MAT4},
    [C_MESH_BASE] = {"bg_mesh_%d", MACS_UNIFORM_VEC2},
};

/* Room for the longest name with any int (the compiler checks formats against INT_MIN). */
typedef char caster_names[C_COUNT][32];

/* Names and declares caster j's uniforms into u[0 ..]; returns how many (C_MESH_BASE for a mesh only). */
static int caster_uniforms(int j, bool mesh, caster_names names, macs_uniform_desc *u)
{
    int n = mesh ? C_COUNT : C_MESH_BASE;
    for (int c = 0; c < n; c++) {
        snprintf(names[c], sizeof names[c], caster_uniform_row[c].format, j);
        u[c] = (macs_uniform_desc){names[c], caster_uniform_row[c].type, 0};
    }
    return n;
}

/* A mesh caster's, the larger. */
int bgi_gpu_shadow_object_components(void)
{
    caster_names names;
    macs_uniform_desc u[C_COUNT];
    return bgi_gpu_uniform_components(u, caster_uniforms(0, true, names, u));
}

int bgi_gpu_shadow_shared_components(int lights, bool area)
{
    macs_uniform_desc u[LIGHT_UNIFORM_COUNT + 1];
    int n = 0;
    light_uniforms(u, &n, lights, area);
    u[n++] = (macs_uniform_desc){"bg_mesh_dims", MACS_UNIFORM_VEC4, 0};
    return bgi_gpu_uniform_components(u, n);
}

/* What a shadow pass description points at while the pass is made. */
typedef struct shadow_pass_parts {
    const uint32_t *casters;
    const bool *blocks;
    int count, group, lights;
    bool mesh[GPU_BATCH_MAX]; /* caster j is a mesh (its test walks the mesh's tree) */
    int meshes;               /* mesh casters that block */
    bool on_meshes;           /* the scene has meshes: a point on one starts its segments off it */
    bool area;                /* the scene has area lights: each light is its point at this sample */
    caster_names names[GPU_BATCH_MAX];
    macs_uniform_desc uniforms[GPU_BATCH_MAX * C_COUNT + LIGHT_UNIFORM_COUNT + 1];
    int uniform_count;
} shadow_pass_parts;

/* Every caster's uniforms, then the group's light arrays, then the mesh textures' geometry. */
static void add_shadow_uniforms(shadow_pass_parts *sp)
{
    sp->uniform_count = 0;
    for (int j = 0; j < sp->count; j++)
        sp->uniform_count += caster_uniforms(j, sp->mesh[j], sp->names[j], &sp->uniforms[sp->uniform_count]);
    light_uniforms(sp->uniforms, &sp->uniform_count, sp->lights, sp->area);
    if (sp->meshes > 0)
        sp->uniforms[sp->uniform_count++] = (macs_uniform_desc){"bg_mesh_dims", MACS_UNIFORM_VEC4, 0};
}

/* Per light, the segment is found once and tested against every object of the batch; a point
 * never tests the analytic object it lies on (a convex object cannot shadow its own lit surface).
 * A point on a mesh starts its segments off the surface and skips only its own triangle, so a mesh
 * shadows itself (docs/shading.md 2.10); a light whose mesh walk ran out of steps without a block
 * gets visibility 1/2, which the light pass reads as "unknown" and marks the pixel for the CPU. */
static void emit_shadow_main(const bg_renderer *r, const bg_scene_state *state, const shadow_pass_parts *sp,
                             gpu_text *main)
{
    bool skip_facing = !(r->multipass->key.disable_skips & BG_SKIP_FACING);
    bgi_gpu_text_append(main, "vec4 bg_h = texture2D(bg_g_hit, macs_uv);\n");
    bool any = false;
    for (int j = 0; j < sp->count; j++)
        any = any || sp->blocks[j];
    /* One that casts nothing blocks nothing. */
    if (!any)
        bgi_gpu_text_append(main, "if (true)\n    discard;\n");
    bgi_gpu_text_append(main, "float bg_self = bg_hit_index(bg_h.w);\n");
    if (sp->area)
        bgi_gpu_text_append(main, "float bg_ph = bg_pixel_hash(gl_FragCoord.xy, bg_pixel_at);\n");
    if (sp->count == 1 && !sp->mesh[0])
        bgi_gpu_text_append(main, "if (bg_self == bg_index_0) discard;\n");
    bgi_gpu_text_append(main, "vec3 bg_n = texture2D(bg_g_normal, macs_uv).xyz;\n"
                          "vec4 bg_vis = vec4(1.0);\nvec3 bg_l, bg_e;\nfloat bg_dist;\nvec3 bg_p = bg_h.xyz;\n");
    if (sp->on_meshes)
        bgi_gpu_text_printf(main, "vec4 bg_m = texture2D(bg_g_mesh, macs_uv);\n"
                                  "if (bg_m.w < %.1f + 0.5) discard; // the CPU renders this pixel\n",
                            GPU_MESH_SHORT);
    if (sp->meshes > 0)
        bgi_gpu_text_printf(main, "bg_tree_left = %d.0;\n", bgi_gpu_mesh_pass_budget(sp->meshes * sp->lights));
    for (int i = 0; i < sp->lights; i++) {
        char pos[128], rad[128];
        light_place(main, sp->area, i, sp->group * GPU_LIGHTS_PER_GROUP + i, "", pos, rad, sizeof pos);
        bgi_gpu_text_printf(main,
                        "if (bg_light_at(bg_h.xyz, %s, %s, bg_latt[%d], bg_lspot[%d], bg_lexp[%d], "
                        "bg_l, bg_dist, bg_e)%s) {\n",
                        pos, rad, i, i, i, skip_facing ? " && !(dot(bg_n, bg_l) <= 0.0)" : "");
        if (sp->on_meshes)
            bgi_gpu_text_append(main, "    bg_p = bg_m.w >= 0.0 ? bg_h.xyz + (dot(bg_l, bg_m.xyz) >= 0.0 ? 1.0 : -1.0) * bg_m.xyz "
                                      ": bg_h.xyz;\n");
        if (sp->meshes > 0)
            bgi_gpu_text_append(main, "    bg_tree_short = 0.0;\n");
        bgi_gpu_text_append(main, "    if (false");
        for (int j = 0; j < sp->count; j++) {
            if (!sp->blocks[j])
                continue;
            if (sp->mesh[j]) {
                bgi_gpu_text_printf(main, "\n        || bg_mesh_blocked(bg_p, bg_l, bg_dist, bg_to_object_%d, bg_mesh_%d, "
                                      "bg_self == bg_index_%d ? bg_m.w : -1.0)", j, j, j);
                continue;
            }
            const char *shape = bgi_gpu_shape_suffix(state->objects[sp->casters[j]].shape);
            bgi_gpu_text_printf(main, "\n        || (bg_self != bg_index_%d && bg_segment_blocked_%s(bg_p, bg_l, bg_dist, "
                                  "bg_to_object_%d))", j, shape, j);
        }
        bgi_gpu_text_printf(main, ")\n        bg_vis.%c = 0.0;\n", "xyzw"[i]);
        if (sp->meshes > 0)
            bgi_gpu_text_printf(main, "    else if (bg_tree_short > 0.0)\n        bg_vis.%c = 0.5;\n", "xyzw"[i]);
        bgi_gpu_text_append(main, "}\n");
    }
    bgi_gpu_text_append(main, "if (min(min(bg_vis.x, bg_vis.y), min(bg_vis.z, bg_vis.w)) > 0.5) discard;\n");
}

/* The light functions and each caster shape's segment test, renamed so that shapes share the program. */
static bool shadow_functions(gpu_text *t, const bg_scene_state *state, const shadow_pass_parts *sp)
{
    const char *seen[32];
    int n = 0;
    static const char *const stage[] = {"bg_segment_blocked", "bg_shadow_visibility", NULL};
    bool ok = bgi_gpu_text_snippet(t, "bg_hit_code.glsl", seen, &n, 32) && bgi_gpu_text_snippet(t, "bg_light.glsl", seen, &n, 32) &&
              (!sp->area || (bgi_gpu_text_snippet(t, "bg_scramble.glsl", seen, &n, 32) &&
                             bgi_gpu_text_snippet(t, "bg_area_light.glsl", seen, &n, 32))) &&
              bgi_gpu_text_shape_stages(t, state, sp->casters, sp->count, "bg_stage_shadow.glsl", stage, seen, &n, 32);
    if (ok && sp->meshes > 0) {
        ok = bgi_gpu_text_snippet(t, "bg_tree_textures.glsl", seen, &n, 32) &&
             bgi_gpu_mesh_library(t, seen, &n, 32);
        if (ok)
            bgi_gpu_mesh_pass_walks(sp->meshes * sp->lights, bgi_gpu_meshes_filters(state), t);
    }
    return ok;
}

/* Sets each caster's index and transform, then the group's lights. */
static bg_status set_shadow_uniforms(bg_renderer *r, macs_pass *pass, const bg_scene_state *state,
                                     const shadow_pass_parts *sp)
{
    macs_status ms = MACS_OK;
    for (int j = 0; j < sp->count && !ms; j++) {
        float m16[16], fi = (float)sp->casters[j];
        bgi_gpu_origin_to_object(state, sp->casters[j], m16);
        ms = macs_pass_set_uniform(pass, sp->names[j][C_INDEX], &fi);
        if (!ms)
            ms = macs_pass_set_uniform(pass, sp->names[j][C_TO_OBJECT], m16);
        if (!ms && sp->mesh[j])
            ms = macs_pass_set_uniform(pass, sp->names[j][C_MESH_BASE], &r->meshes.base[2 * (size_t)sp->casters[j]]);
    }
    if (!ms && sp->meshes > 0)
        ms = macs_pass_set_uniform(pass, "bg_mesh_dims", r->meshes.dims);
    if (ms)
        return bgi_gpu_fail_macs(r, ms, "shadow pass uniforms");
    return bgi_gpu_set_light_uniforms(r, pass, state, sp->group * GPU_LIGHTS_PER_GROUP, sp->lights);
}

bg_status bgi_gpu_shadow_pass_build(bg_renderer *r, const bg_scene_state *state, const uint32_t *casters,
                                const bool *blocks, int count, int group, bool trial, macs_pass **out,
                                bool *rejected)
{
    *out = NULL;
    if (rejected)
        *rejected = false;
    if (count < 1 || count > GPU_BATCH_MAX)
        return bgi_gpu_fail(r, BG_ERR_LIMIT, "shadow batch of %d objects", count);
    shadow_pass_parts sp;
    sp.casters = casters;
    sp.blocks = blocks;
    sp.count = count;
    sp.group = group;
    sp.lights = group_size(state, group);
    sp.meshes = 0;
    sp.on_meshes = r->multipass->features.mesh;
    sp.area = r->multipass->features.area;
    for (int j = 0; j < count; j++) {
        sp.mesh[j] = state->objects[casters[j]].shape == BGI_SHAPE_MESH;
        sp.meshes += sp.mesh[j] && blocks[j] ? 1 : 0;
    }
    add_shadow_uniforms(&sp);

    gpu_text main, functions;
    bgi_gpu_text_init(&main, &r->allocator);
    bgi_gpu_text_init(&functions, &r->allocator);
    emit_shadow_main(r, state, &sp, &main);
    bool have = shadow_functions(&functions, state, &sp);

    macs_input_desc inputs[5] = {{"bg_g_hit"}, {"bg_g_normal"}, {"bg_g_mesh"}, {"bg_mesh_nodes"}, {"bg_mesh_tris"}};
    macs_texture *input_tex[5] = {r->multipass->gbuffer[GPU_SLOT_HIT], r->multipass->gbuffer[GPU_SLOT_NORMAL], r->multipass->gbuffer[GPU_SLOT_MESH],
                                  r->meshes.nodes,
                                  r->meshes.triangles};
    int input_count = sp.meshes > 0 ? 5 : sp.on_meshes ? 3 : 2;
    macs_output_desc output = {"visibility", "bg_vis"};
    macs_texture *output_tex[1] = {r->multipass->vis};
    macs_pass_desc desc;
    bgi_gpu_pass_desc_init(&desc, main.s, inputs, input_tex, input_count, sp.uniforms, sp.uniform_count, &output,
                           output_tex, 1);
    desc.depth_stencil = r->multipass->depth;
    hit_stencil(r, &desc.stencil);
    desc.blend = MACS_BLEND_MULTIPLY;

    bg_status st = bgi_gpu_pass_from_texts(r, "shadow pass", &main, &functions, have, &desc, trial, out, rejected);
    if (st != BG_OK || !*out)
        return st;
    return set_shadow_uniforms(r, *out, state, &sp);
}

bg_status bgi_gpu_light_pass_build(bg_renderer *r, const bg_scene_state *state, int group, bool vis, macs_pass **out)
{
    const gpu_features *f = &r->multipass->features;
    int count = group_size(state, group);
    bool skip_facing = !(r->multipass->key.disable_skips & BG_SKIP_FACING);
    if (count == 0) {
        /* Ambient and emission alone: they are already weighted in the G-buffer. With meshes, the
         * alpha counts the hits whose walk ran out of steps (multipass_frame.c hands those pixels to the CPU). */
        macs_input_desc in[2] = {{"bg_g_once"}, {"bg_g_mesh"}};
        macs_texture *in_tex[2] = {r->multipass->gbuffer[GPU_SLOT_ONCE], r->multipass->gbuffer[GPU_SLOT_MESH]};
        macs_output_desc output = {"radiance", f->mesh ? "vec4(texture2D(bg_g_once, macs_uv).rgb, "
                                                         "texture2D(bg_g_mesh, macs_uv).w < -1.5 ? 1.0 : 0.0)"
                                                       : "vec4(texture2D(bg_g_once, macs_uv).rgb, 0.0)"};
        macs_texture *output_tex[1] = {r->multipass->accum};
        macs_pass_desc desc;
        bgi_gpu_pass_desc_init(&desc, NULL, in, in_tex, f->mesh ? 2 : 1, NULL, 0, &output, output_tex, 1);
        desc.depth_stencil = r->multipass->depth;
        hit_stencil(r, &desc.stencil);
        desc.blend = MACS_BLEND_ADD;
        (void)vis;
        return bgi_gpu_pass_create(r, "ambient and emission pass", NULL, NULL, &desc, out);
    }
    macs_input_desc inputs[10];
    macs_texture *input_tex[10];
    int ni = 0;
#define INPUT(input_name, texture) (inputs[ni].name = (input_name), input_tex[ni++] = (texture))
    INPUT("bg_g_hit", r->multipass->gbuffer[GPU_SLOT_HIT]);
    INPUT("bg_g_normal", r->multipass->gbuffer[GPU_SLOT_NORMAL]);
    INPUT("bg_g_base", r->multipass->gbuffer[GPU_SLOT_BASE]);
    INPUT("bg_ray_dir", NULL);
    /* The light weight is the path weight x opaque; without transparency that is the path weight. */
    if (f->slot[GPU_SLOT_XPARENT])
        INPUT("bg_g_xparent", r->multipass->gbuffer[GPU_SLOT_XPARENT]);
    else
        INPUT("bg_ray_weight", NULL);
    if (f->slot[GPU_SLOT_TANGENT])
        INPUT("bg_g_tangent", r->multipass->gbuffer[GPU_SLOT_TANGENT]);
    if (f->slot[GPU_SLOT_COAT])
        INPUT("bg_g_coat", r->multipass->gbuffer[GPU_SLOT_COAT]);
    if (vis)
        INPUT("bg_vis", r->multipass->vis);
#undef INPUT
    bool area = f->area;
    macs_uniform_desc uniforms[LIGHT_UNIFORM_COUNT];
    int nu = 0;
    if (count > 0)
        light_uniforms(uniforms, &nu, count, area);

    gpu_text main;
    bgi_gpu_text_init(&main, &r->allocator);
    bgi_gpu_text_append(&main, "vec4 bg_h = texture2D(bg_g_hit, macs_uv);\n"
                           "vec4 bg_nr = texture2D(bg_g_normal, macs_uv);\n"
                           "vec4 bg_b = texture2D(bg_g_base, macs_uv);\n"
                           "vec3 bg_view = -texture2D(bg_ray_dir, macs_uv).xyz;\n");
    bgi_gpu_text_printf(&main, "vec3 bg_lw = texture2D(%s, macs_uv).rgb;\n",
                    f->slot[GPU_SLOT_XPARENT] ? "bg_g_xparent" : "bg_ray_weight");
    /* Without the tangent slot every isotropy is 1, where the azimuth term is exactly 1 whatever
     * the tangent, so the normal stands in for it. */
    bgi_gpu_text_append(&main, f->slot[GPU_SLOT_TANGENT] ? "vec4 bg_tg = texture2D(bg_g_tangent, macs_uv);\n"
                                                     : "vec4 bg_tg = vec4(bg_nr.xyz, 1.0);\n");
    bgi_gpu_text_append(&main, f->slot[GPU_SLOT_COAT] ? "vec4 bg_c = texture2D(bg_g_coat, macs_uv);\n"
                                                  : "vec4 bg_c = vec4(0.0, 0.0, 0.0, -1.0);\n");
    bgi_gpu_text_append(&main, vis ? "vec4 bg_v = texture2D(bg_vis, macs_uv);\n" : "vec4 bg_v = vec4(1.0);\n");
    bgi_gpu_text_append(&main, "vec3 bg_sum = vec3(0.0);\nfloat bg_any = 0.0;\nfloat bg_unknown = 0.0;\n");
    if (area)
        bgi_gpu_text_append(&main, "float bg_ph = bg_pixel_hash(gl_FragCoord.xy, bg_pixel_at);\n");
    /* A visibility strictly between 0 and 1 is a shadow walk that ran out of steps (shadow pass):
     * the alpha counts it, and multipass_frame.c hands the pixel to the CPU reference. */
    for (int i = 0; i < count && vis && f->mesh; i++)
        bgi_gpu_text_printf(&main, "if (bg_v.%c > 0.0 && bg_v.%c < 1.0)\n    bg_unknown = 1.0;\n", "xyzw"[i], "xyzw"[i]);
    {
        /* A dead ray (weight 0) gets no light work, like the stencil does for it; with the stencil
         * skip off it is shaded and multiplied by 0, as every pixel is. */
        bgi_gpu_text_printf(&main, "if (bg_hit_outside(bg_h.w) && dot(bg_nr.xyz, bg_view) > 0.0%s) {\n    vec4 bg_term;\n",
                        (r->multipass->key.disable_skips & BG_SKIP_STENCIL) ? "" : " && bg_max3(bg_lw) > 0.0");
        for (int i = 0; i < count; i++) {
            char pos[128], rad[128];
            light_place(&main, area, i, group * GPU_LIGHTS_PER_GROUP + i, "    ", pos, rad, sizeof pos);
            bgi_gpu_text_printf(&main,
                            "    bg_term = bg_light_term(bg_h.xyz, bg_nr.xyz, bg_view, bg_tg.xyz, bg_b.rgb, bg_nr.w, bg_b.a, "
                            "bg_c.w >= 0.0, bg_c.rgb, bg_c.w, bg_tg.w, %s, %s, bg_latt[%d], bg_lspot[%d], "
                            "bg_lexp[%d], bg_v.%c, %s);\n"
                            "    bg_sum += bg_lw * bg_term.rgb;\n    bg_any += bg_term.a;\n",
                            pos, rad, i, i, i, "xyzw"[i], skip_facing ? "true" : "false");
        }
        bgi_gpu_text_append(&main, "}\n");
    }
    /* Adding nothing changes nothing: a pixel no light reaches skips the blend. */
    bgi_gpu_text_append(&main, "if (bg_any == 0.0 && bg_unknown == 0.0) discard;\n");

    macs_output_desc output = {"radiance", "vec4(bg_sum, bg_unknown)"};
    macs_texture *output_tex[1] = {r->multipass->accum};
    macs_pass_desc desc;
    bgi_gpu_pass_desc_init(&desc, main.s, inputs, input_tex, ni, uniforms, nu, &output, output_tex, 1);
    desc.depth_stencil = r->multipass->depth;
    hit_stencil(r, &desc.stencil);
    desc.blend = MACS_BLEND_ADD;

    const char *point_files[] = {"bg_hit_code.glsl", "bg_stage_light.glsl", NULL};
    const char *area_files[] = {"bg_hit_code.glsl", "bg_stage_light.glsl", "bg_scramble.glsl", "bg_area_light.glsl", NULL};
    const char **files = area ? area_files : point_files;
    bg_status st = main.failed ? bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory building a light shader")
                               : bgi_gpu_pass_create(r, "light pass", files, NULL, &desc, out);
    bgi_gpu_text_free(&main);
    if (st != BG_OK)
        return st;
    return bgi_gpu_set_light_uniforms(r, *out, state, group * GPU_LIGHTS_PER_GROUP, count);
}
