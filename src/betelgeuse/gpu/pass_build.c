/* Builds the passes of a frame for one scene structure and image size (docs/gpu_pipeline.md): camera
 * rays, live-pixel marking, per-object intersection, background, shadows, lights, ambient and
 * emission, secondary rays and the resolve. Ray-map inputs are bound per ray set by gpu_frame.c at
 * the fixed input positions named in gpu_internal.h. */
#include <stdio.h>
#include <string.h>

#include "../common/alloc.h"
#include "gpu_internal.h"

void gpu_pass_desc_init(macs_pass_desc *d, const char *main, const macs_input_desc *inputs,
                        macs_texture *const *input_tex, int input_count, const macs_uniform_desc *uniforms,
                        int uniform_count, const macs_output_desc *outputs, macs_texture *const *output_tex,
                        int output_count)
{
    memset(d, 0, sizeof *d);
    d->main = main;
    d->inputs = inputs;
    d->input_count = input_count;
    d->input_textures = input_tex;
    d->uniforms = uniforms;
    d->uniform_count = uniform_count;
    d->outputs = outputs;
    d->output_count = output_count;
    d->output_textures = output_tex;
}

bg_status gpu_pass_create(bg_renderer *r, const char *what, const char *const *files, const char *extra,
                          macs_pass_desc *desc, macs_pass **out)
{
    gpu_text t;
    gpu_text_init(&t, &r->allocator);
    const char *seen[32];
    int n = 0;
    for (int i = 0; files && files[i]; i++) {
        if (!gpu_text_snippet(&t, files[i], seen, &n, 32)) {
            gpu_text_free(&t);
            return gpu_fail(r, BG_ERR_GL, "bg_render_gpu: %s: shader file %s (or one it requires) is missing", what,
                            files[i]);
        }
    }
    gpu_text_append(&t, extra);
    if (t.failed) {
        gpu_text_free(&t);
        return gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "bg_render_gpu: out of memory assembling the %s", what);
    }
    desc->functions = t.s;
    macs_status ms = macs_pass_create(r->ctx, desc, out);
    gpu_text_free(&t);
    if (ms != MACS_OK) {
        *out = NULL;
        return gpu_fail_macs(r, ms, what);
    }
    return BG_OK;
}

bg_status gpu_pass_try(bg_renderer *r, const char *what, const char *functions, macs_pass_desc *desc, bool trial,
                       macs_pass **out, bool *rejected)
{
    desc->functions = functions;
    /* A batch's failure is forgotten only if nothing was wrong before it. */
    bool clean = macs_context_error(r->ctx) == MACS_OK;
    macs_status ms = macs_pass_create(r->ctx, desc, out);
    if (ms == MACS_OK)
        return BG_OK;
    *out = NULL;
    if (trial && clean && (ms == MACS_ERR_SHADER_COMPILE || ms == MACS_ERR_SHADER_LINK)) {
        /* The longer shader of a batch is beyond this GL: the caller falls back to smaller passes. */
        if (r->log) {
            char message[GPU_MESSAGE_SIZE];
            snprintf(message, sizeof message, "bg_render_gpu: %s: the batched shader was refused (%s), "
                     "falling back to one object per pass: %s", what, macs_status_string(ms),
                     macs_context_error_message(r->ctx));
            r->log(BG_LOG_WARNING, message, r->log_user);
        }
        macs_context_clear_error(r->ctx);
        if (rejected)
            *rejected = true;
        return BG_OK;
    }
    return gpu_fail_macs(r, ms, what);
}

/* A pass over the live (and, with hit_bits, hit or missed) pixels with one or two ray-map inputs. */
static bg_status simple_pass(bg_renderer *r, const char *what, const char *const *files, const char *main,
                             const macs_input_desc *inputs, int input_count, macs_texture *const *input_tex,
                             const macs_uniform_desc *uniforms, int uniform_count, const char *value,
                             macs_texture *const *outputs, int output_count, macs_blend blend,
                             const macs_stencil_state *stencil, macs_pass **out)
{
    macs_output_desc out_desc[3] = {{"out0", value}, {"out1", NULL}, {"out2", NULL}};
    macs_pass_desc desc;
    gpu_pass_desc_init(&desc, main, inputs, input_tex, input_count, uniforms, uniform_count, out_desc, outputs,
                       output_count);
    desc.blend = blend;
    if (stencil) {
        desc.depth_stencil = r->depth;
        desc.stencil = *stencil;
    }
    if (output_count == 3) {
        /* Ray-map writers name their three outputs o0..o2 in main. */
        out_desc[0].value = "bg_o0";
        out_desc[1].value = "bg_o1";
        out_desc[2].value = "bg_o2";
        out_desc[1].name = "out1";
        out_desc[2].name = "out2";
    }
    return gpu_pass_create(r, what, files, NULL, &desc, out);
}

static macs_stencil_state stencil_equal(unsigned ref, unsigned mask)
{
    macs_stencil_state s;
    memset(&s, 0, sizeof s);
    s.test = true;
    s.func = MACS_COMPARE_EQUAL;
    s.ref = ref;
    s.read_mask = mask;
    s.write_mask = 0;
    return s;
}

static bg_status build_ray_passes(bg_renderer *r, const bg_scene_state *state, const bg_render_settings *settings)
{
    gpu_passes *p = &r->passes;
    bool stencil_skip = !(r->key.disable_skips & BG_SKIP_STENCIL);
    gpu_ray_set *set0 = NULL;
    bg_status st = gpu_ray_set_get(r, 0, &set0);
    if (st != BG_OK)
        return st;

    /* Camera rays. */
    {
        macs_uniform_desc u[6] = {{"bg_size", MACS_UNIFORM_VEC2, 0},    {"bg_eye", MACS_UNIFORM_VEC3, 0},
                                  {"bg_forward", MACS_UNIFORM_VEC3, 0}, {"bg_right", MACS_UNIFORM_VEC3, 0},
                                  {"bg_up", MACS_UNIFORM_VEC3, 0},      {"bg_tan_half", MACS_UNIFORM_VEC2, 0}};
        macs_texture *outs[3] = {set0->origin, set0->dir, set0->weight};
        const char *files[] = {"bg_stage_camera.glsl", NULL};
        st = simple_pass(r, "camera pass", files,
                         "vec4 bg_o0, bg_o1, bg_o2;\n"
                         "bg_camera_ray(gl_FragCoord.xy, bg_size, bg_eye, bg_forward, bg_right, bg_up, bg_tan_half, "
                         "bg_o0, bg_o1, bg_o2);\n",
                         NULL, 0, NULL, u, 6, NULL, outs, 3, MACS_BLEND_NONE, NULL, &p->camera);
        if (st != BG_OK)
            return st;
        const bg_camera_data *c = &state->camera;
        float size[2] = {(float)r->width, (float)r->height};
        float eye[3];
        gpu_origin_point(state, &c->camera.position, eye); /* (0, 0, 0): the frame's origin */
        float fw[3], rt[3], up[3];
        for (int i = 0; i < 3; i++) {
            fw[i] = (float)c->forward[i];
            rt[i] = (float)c->right[i];
            up[i] = (float)c->up[i];
        }
        double aspect = (double)r->width / (double)r->height;
        float th[2] = {(float)(aspect * c->tan_half_fov_y), (float)c->tan_half_fov_y};
        macs_status ms = macs_pass_set_uniform(p->camera, "bg_size", size);
        if (!ms) ms = macs_pass_set_uniform(p->camera, "bg_eye", eye);
        if (!ms) ms = macs_pass_set_uniform(p->camera, "bg_forward", fw);
        if (!ms) ms = macs_pass_set_uniform(p->camera, "bg_right", rt);
        if (!ms) ms = macs_pass_set_uniform(p->camera, "bg_up", up);
        if (!ms) ms = macs_pass_set_uniform(p->camera, "bg_tan_half", th);
        if (ms)
            return gpu_fail_macs(r, ms, "camera pass uniforms");
    }

    /* Marking: counts a set's live rays (occlusion query) and, with the stencil skip on, sets their
     * live bit so that every later pass of the set rejects dead pixels before shading them. */
    {
        macs_input_desc in[1] = {{"bg_ray_weight"}};
        macs_texture *in_tex[1] = {NULL};
        macs_texture *outs[1] = {r->accum};
        macs_stencil_state s;
        memset(&s, 0, sizeof s);
        if (stencil_skip) {
            s.test = true;
            s.func = MACS_COMPARE_ALWAYS;
            s.ref = GPU_STENCIL_LIVE;
            s.write_mask = GPU_STENCIL_LIVE;
            s.pass = MACS_STENCIL_OP_REPLACE;
        }
        macs_pass_desc desc;
        macs_output_desc od = {"none", "vec4(0.0)"};
        gpu_pass_desc_init(&desc, "if (texture2D(bg_ray_weight, macs_uv).a <= 0.0) discard;\n", in, in_tex, 1, NULL, 0,
                           &od, outs, 1);
        desc.depth_stencil = r->depth;
        desc.stencil = s;
        desc.color_mask = MACS_COLOR_MASK_NONE;
        st = gpu_pass_create(r, "mark pass", NULL, NULL, &desc, &p->mark);
        if (st != BG_OK)
            return st;
    }

    /* Background where a live ray missed every object: the hit bit is clear. */
    if (settings->background[0] > 0.0 || settings->background[1] > 0.0 || settings->background[2] > 0.0) {
        macs_input_desc in[1] = {{"bg_ray_weight"}};
        macs_texture *in_tex[1] = {NULL};
        macs_uniform_desc u[1] = {{"bg_background", MACS_UNIFORM_VEC3, 0}};
        macs_texture *outs[1] = {r->accum};
        macs_stencil_state s = stencil_skip ? stencil_equal(GPU_STENCIL_LIVE, GPU_STENCIL_LIVE | GPU_STENCIL_HIT)
                                            : stencil_equal(0, GPU_STENCIL_HIT);
        st = simple_pass(r, "background pass", NULL, "vec4 bg_w = texture2D(bg_ray_weight, macs_uv);\n", in, 1, in_tex,
                         u, 1, "vec4(bg_w.rgb * bg_background, 0.0)", outs, 1, MACS_BLEND_ADD, &s, &p->background);
        if (st != BG_OK)
            return st;
        float bgc[3] = {(float)settings->background[0], (float)settings->background[1], (float)settings->background[2]};
        macs_status ms = macs_pass_set_uniform(p->background, "bg_background", bgc);
        if (ms)
            return gpu_fail_macs(r, ms, "background uniforms");
    }

    /* Secondary rays: every live hit pixel writes its child; the next set's mark pass counts them. */
    bool want_bounce = r->key.bounces && (r->features.bounce || (r->key.disable_skips & BG_SKIP_BOUNCE_CULL));
    if (want_bounce) {
        const gpu_features *f = &r->features;
        for (int kind = 0; kind < 2; kind++) {
            if (kind == 1 && !f->transparent)
                break;
            macs_input_desc in[8];
            macs_texture *in_tex[8];
            int ni = 0;
            in[ni].name = "bg_ray_dir", in_tex[ni++] = NULL;    /* GPU_SPAWN_IN_DIR */
            in[ni].name = "bg_ray_weight", in_tex[ni++] = NULL; /* GPU_SPAWN_IN_WEIGHT */
            in[ni].name = "bg_g_hit", in_tex[ni++] = r->gbuffer[GPU_SLOT_HIT];
            in[ni].name = "bg_g_normal", in_tex[ni++] = r->gbuffer[GPU_SLOT_NORMAL];
            if (kind == 0)
                in[ni].name = "bg_g_base", in_tex[ni++] = r->gbuffer[GPU_SLOT_BASE];
            if (kind == 0 && f->slot[GPU_SLOT_COAT])
                in[ni].name = "bg_g_coat", in_tex[ni++] = r->gbuffer[GPU_SLOT_COAT];
            if (f->transparent) {
                in[ni].name = "bg_g_xparent", in_tex[ni++] = r->gbuffer[GPU_SLOT_XPARENT];
                in[ni].name = "bg_g_once", in_tex[ni++] = r->gbuffer[GPU_SLOT_ONCE];
            }
            macs_uniform_desc u[1] = {{"bg_min_weight", MACS_UNIFORM_FLOAT, 0}};
            gpu_text main;
            gpu_text_init(&main, &r->allocator);
            gpu_text_append(&main, "vec4 bg_o0, bg_o1, bg_o2;\n");
            gpu_text_printf(&main,
                            "bg_spawn(%s, texture2D(bg_g_hit, macs_uv), texture2D(bg_g_normal, macs_uv), %s, %s, %s, %s, "
                            "texture2D(bg_ray_dir, macs_uv), texture2D(bg_ray_weight, macs_uv), bg_min_weight, "
                            "bg_o0, bg_o1, bg_o2);\n",
                            kind ? "true" : "false", kind == 0 ? "texture2D(bg_g_base, macs_uv)" : "vec4(0.0)",
                            kind == 0 && f->slot[GPU_SLOT_COAT] ? "texture2D(bg_g_coat, macs_uv)" : "vec4(0.0, 0.0, 0.0, -1.0)",
                            f->transparent ? "texture2D(bg_g_xparent, macs_uv).a" : "0.0",
                            f->transparent ? "texture2D(bg_g_once, macs_uv).a" : "1.0");
            macs_texture *outs[3] = {set0->origin, set0->dir, set0->weight}; /* rebound per child set */
            macs_stencil_state s = stencil_skip ? stencil_equal(GPU_STENCIL_LIVE | GPU_STENCIL_HIT,
                                                                GPU_STENCIL_LIVE | GPU_STENCIL_HIT)
                                                : stencil_equal(GPU_STENCIL_HIT, GPU_STENCIL_HIT);
            const char *files[] = {"bg_stage_spawn.glsl", NULL};
            if (main.failed)
                st = gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "bg_render_gpu: out of memory building the spawn shader");
            else
                st = simple_pass(r, kind ? "refraction pass" : "reflection pass", files, main.s, in, ni, in_tex, u, 1,
                                 NULL, outs, 3, MACS_BLEND_NONE, &s, kind ? &p->refract : &p->reflect);
            gpu_text_free(&main);
            if (st != BG_OK)
                return st;
            float mw = (float)settings->min_weight;
            macs_status ms = macs_pass_set_uniform(kind ? p->refract : p->reflect, "bg_min_weight", &mw);
            if (ms)
                return gpu_fail_macs(r, ms, "spawn uniforms");
        }
    }

    /* Resolve to the output encoding, into an RGBA8 target read back by gpu_frame.c. */
    {
        macs_input_desc in[1] = {{"bg_accum"}};
        macs_texture *in_tex[1] = {r->accum};
        macs_texture *outs[1] = {r->encoded};
        const char *files[] = {"bg_stage_resolve.glsl", NULL};
        st = simple_pass(r, "resolve pass", files, "vec3 bg_l = texture2D(bg_accum, macs_uv).rgb;\n", in, 1, in_tex,
                         NULL, 0,
                         settings->encoding == BG_ENCODING_LINEAR ? "vec4(bg_encode(bg_l, false), 1.0)"
                                                                  : "vec4(bg_encode(bg_l, true), 1.0)",
                         outs, 1, MACS_BLEND_NONE, NULL, &p->resolve);
        if (st != BG_OK)
            return st;
    }
    return BG_OK;
}

/* Signed side of point p (w = 1) or direction p (w = 0) relative to the plane of object o. */
static double plane_side(const bg_object_data *o, const double p[3], double w)
{
    const double(*nm)[3] = o->normal_to_world;
    double n[3] = {nm[0][1], nm[1][1], nm[2][1]};
    double q[3] = {o->to_world[0][3], o->to_world[1][3], o->to_world[2][3]};
    return (p[0] - w * q[0]) * n[0] + (p[1] - w * q[1]) * n[1] + (p[2] - w * q[2]) * n[2];
}

/* Whether a plane can block a light of the group from any other object's surface: only if some
 * other object reaches the far side of the plane from that light (or the light is on the plane,
 * or another plane, which reaches everywhere, exists). Points on the plane itself are never tested
 * against it. */
static bool plane_can_shadow(const bg_scene_state *state, uint32_t o, int group)
{
    const bg_object_data *plane = &state->objects[o];
    uint32_t first = (uint32_t)group * GPU_LIGHTS_PER_GROUP;
    for (uint32_t k = first; k < state->light_count && k < first + GPU_LIGHTS_PER_GROUP; k++) {
        const bg_light *l = &state->lights[k];
        double side;
        if (l->type == BG_LIGHT_DIRECTIONAL) {
            double towards[3] = {-l->direction.x, -l->direction.y, -l->direction.z};
            side = plane_side(plane, towards, 0.0);
        } else {
            double at[3] = {l->position.x, l->position.y, l->position.z};
            side = plane_side(plane, at, 1.0);
        }
        if (side == 0.0)
            return true;
        for (uint32_t j = 0; j < state->object_count; j++) {
            const bg_object_data *other = &state->objects[j];
            if (j == o)
                continue;
            if (!other->bounded)
                return true;
            for (int c = 0; c < 8; c++) {
                double p[3] = {(c & 1) ? other->bounds_max[0] : other->bounds_min[0],
                               (c & 2) ? other->bounds_max[1] : other->bounds_min[1],
                               (c & 4) ? other->bounds_max[2] : other->bounds_min[2]};
                if (plane_side(plane, p, 1.0) * side <= 0.0)
                    return true;
            }
        }
    }
    return false;
}

/* Whether object o needs a shadow pass for a light group: it must cast shadows, some other object
 * must exist for it to shadow (a lone convex object can only shadow itself, which is never tested),
 * and a plane must have something on its far side from one of the group's lights. */
static bool shadow_needed(const bg_scene_state *state, uint32_t o, int group)
{
    if (!state->objects[o].casts_shadows || state->object_count < 2)
        return false;
    return state->objects[o].bounded || plane_can_shadow(state, o, group);
}

/* Builds the planned intersection batches; a batch whose shader GL refuses becomes one pass per
 * object (the order, and so every tie, stays the same). */
static bg_status build_hit_batches(bg_renderer *r, const bg_scene_state *state)
{
    gpu_passes *p = &r->passes;
    int n = (int)state->object_count;
    gpu_batch *plan = bg_alloc(&r->allocator, (size_t)(n ? n : 1) * sizeof *plan);
    if (!plan)
        return gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "bg_render_gpu: out of memory for %u objects", state->object_count);
    int planned = gpu_batch_plan_hits(r, state, plan);
    bg_status st = BG_OK;
    for (int b = 0; b < planned && st == BG_OK; b++) {
        bool rejected = false;
        gpu_batch *out = &p->hit[p->hit_count];
        *out = plan[b];
        st = gpu_hit_pass_build(r, state, (uint32_t)plan[b].first, plan[b].count, plan[b].count > 1, &out->pass,
                                &rejected);
        if (st == BG_OK && !rejected) {
            p->hit_count++;
            continue;
        }
        for (int j = 0; j < plan[b].count && st == BG_OK; j++) {
            out = &p->hit[p->hit_count];
            *out = (gpu_batch){NULL, plan[b].first + j, 1, 0};
            st = gpu_hit_pass_build(r, state, (uint32_t)out->first, 1, false, &out->pass, NULL);
            if (st == BG_OK)
                p->hit_count++;
        }
    }
    bg_free(&r->allocator, plan);
    return st;
}

/* Builds one planned shadow batch, or one pass per object where GL refuses the batched shader. */
static bg_status build_shadow_batch(bg_renderer *r, const bg_scene_state *state, const gpu_batch *planned)
{
    gpu_passes *p = &r->passes;
    bool rejected = false;
    gpu_batch *out = &p->shadow[p->shadow_count];
    *out = *planned;
    bg_status st = gpu_shadow_pass_build(r, state, &p->casters[planned->first], &p->caster_blocks[planned->first],
                                         planned->count, planned->group, planned->count > 1, &out->pass, &rejected);
    if (st == BG_OK && !rejected) {
        p->shadow_count++;
        return BG_OK;
    }
    for (int j = 0; j < planned->count && st == BG_OK; j++) {
        out = &p->shadow[p->shadow_count];
        *out = (gpu_batch){NULL, planned->first + j, 1, planned->group};
        st = gpu_shadow_pass_build(r, state, &p->casters[out->first], &p->caster_blocks[out->first], 1,
                                   planned->group, false, &out->pass, NULL);
        if (st == BG_OK)
            p->shadow_count++;
    }
    return st;
}

bg_status gpu_passes_build(bg_renderer *r, const bg_scene_state *state, const bg_render_settings *settings)
{
    gpu_passes *p = &r->passes;
    int groups = (int)((state->light_count + GPU_LIGHTS_PER_GROUP - 1) / GPU_LIGHTS_PER_GROUP);
    p->object_count = (int)state->object_count;
    p->group_count = groups;
    size_t n_hit = state->object_count ? state->object_count : 1;
    size_t n_shadow = (size_t)state->object_count * (size_t)(groups ? groups : 1);
    if (!n_shadow)
        n_shadow = 1;
    p->hit = bg_alloc(&r->allocator, n_hit * sizeof *p->hit);
    p->shadow = bg_alloc(&r->allocator, n_shadow * sizeof *p->shadow);
    p->casters = bg_alloc(&r->allocator, n_shadow * sizeof *p->casters);
    p->caster_blocks = bg_alloc(&r->allocator, n_shadow * sizeof *p->caster_blocks);
    p->light = bg_alloc(&r->allocator, (size_t)(groups ? groups : 1) * sizeof *p->light);
    if (!p->hit || !p->shadow || !p->casters || !p->caster_blocks || !p->light)
        return gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "bg_render_gpu: out of memory for %u objects", state->object_count);
    memset(p->light, 0, (size_t)(groups ? groups : 1) * sizeof *p->light);

    bg_status st = build_ray_passes(r, state, settings);
    if (st == BG_OK)
        st = build_hit_batches(r, state);

    /* Shadow casters group by group. With the cull switched off the objects it would drop are in
     * too, without a test and in batches of their own, so that the pass count shows the saving. */
    bool cull = !(r->key.disable_skips & BG_SKIP_SHADOW_CULL);
    bool any_shadow = false;
    for (int g = 0; g < groups && st == BG_OK; g++) {
        for (int kept = 1; kept >= 0 && st == BG_OK; kept--) {
            if (!kept && cull)
                break;
            int first = p->caster_count;
            for (uint32_t o = 0; o < state->object_count; o++) {
                if (shadow_needed(state, o, g) != (kept == 1))
                    continue;
                p->casters[p->caster_count] = o;
                p->caster_blocks[p->caster_count++] = kept == 1;
            }
            int n = p->caster_count - first;
            if (n == 0)
                continue;
            any_shadow = true;
            gpu_batch *plan = bg_alloc(&r->allocator, (size_t)n * sizeof *plan);
            if (!plan)
                return gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "bg_render_gpu: out of memory for shadow passes");
            int planned = gpu_batch_plan_shadows(r, state, g, first, n, plan);
            for (int b = 0; b < planned && st == BG_OK; b++)
                st = build_shadow_batch(r, state, &plan[b]);
            bg_free(&r->allocator, plan);
        }
    }
    /* Ambient and emission get a pass of their own rather than riding on the first light pass: the
     * addition order into the accumulation (and so every rounding) then never depends on whether
     * the light pass's inputs fit the texture units, and generic and specialised shaders agree. */
    for (int g = 0; g < groups && st == BG_OK; g++)
        st = gpu_light_pass_build(r, state, g, any_shadow, &p->light[g]);
    if (st == BG_OK)
        st = gpu_light_pass_build(r, state, groups, false, &p->once);
    return st;
}

void gpu_passes_release(bg_renderer *r)
{
    gpu_passes *p = &r->passes;
    macs_pass_destroy(p->camera);
    macs_pass_destroy(p->mark);
    macs_pass_destroy(p->background);
    macs_pass_destroy(p->once);
    macs_pass_destroy(p->reflect);
    macs_pass_destroy(p->refract);
    macs_pass_destroy(p->resolve);
    int groups = p->group_count;
    for (int b = 0; p->hit && b < p->hit_count; b++)
        macs_pass_destroy(p->hit[b].pass);
    for (int b = 0; p->shadow && b < p->shadow_count; b++)
        macs_pass_destroy(p->shadow[b].pass);
    for (int g = 0; p->light && g < groups; g++)
        macs_pass_destroy(p->light[g]);
    bg_free(&r->allocator, p->hit);
    bg_free(&r->allocator, p->shadow);
    bg_free(&r->allocator, p->casters);
    bg_free(&r->allocator, p->caster_blocks);
    bg_free(&r->allocator, p->light);
    memset(p, 0, sizeof *p);
}
