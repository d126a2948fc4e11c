/* The intersection pass of a batch of objects (docs/gpu_pipeline.md): each object's root
 * by its shape's code, the nearest kept exactly as the depth test between one-object passes would
 * keep it, then the winner's material evaluated at the hit (texture lookups only for textured
 * parameters unless specialisation is off), its depth and the G-buffer slots the scene's features
 * ask for. The source is unrolled per object with per-object uniforms (no dynamic indexing, which
 * old hardware lacks) and per-texture samplers (GLSL 1.10 indexes samplers by constants only).
 * Material constants are uniforms, so a value-only re-commit reuses the compiled program. */
#include <stdio.h>
#include <string.h>

#include "../common/alloc.h"
#include "gpu_internal.h"

static const char *const shape_file[BG_SHAPE_COUNT_] = {
    "bg_shape_sphere.glsl", "bg_shape_plane.glsl", "bg_shape_box.glsl", "bg_shape_cylinder.glsl",
    "bg_shape_rectangle.glsl"};
static const char *const uv_file[BG_UV_COUNT_] = {NULL, "bg_uv_spherical.glsl", "bg_uv_planar.glsl",
                                                  "bg_uv_box.glsl", "bg_uv_cylindrical.glsl"};

static bool is_thin(bg_shape s)
{
    return s == BG_SHAPE_PLANE || s == BG_SHAPE_RECTANGLE;
}

/* One material parameter: a uniform constant and an optional texture lane. */
typedef struct param {
    const char *name;    /* GLSL local and uniform suffix */
    bool color;          /* vec3 (rgb of the texel) or float (one channel) */
    uint32_t texture;    /* 1-based scene texture, 0 none */
    int channel;
    const char *clamp;   /* GLSL clamp applied after texturing */
    bool used;
    int sampler;         /* input index of its texture lane, -1 none */
} param;

enum { P_BASE_C, P_BASE_R, P_BASE_P, P_AMBIENT, P_EMISSION, P_TRANSPARENCY, P_COAT_C, P_COAT_R, P_COAT_P, P_COUNT };

static void describe(const bg_material *m, const gpu_features *f, param p[P_COUNT])
{
    const char *unit = "clamp(%s, 0.0, 1.0)", *positive = "max(%s, vec3(0.0))";
    param list[P_COUNT] = {
        {"base_c", true, m->base.reflectance.texture, 0, unit, true, -1},
        {"base_r", false, m->base.roughness.texture, m->base.roughness.channel, unit, true, -1},
        {"base_p", false, m->base.isotropy.texture, m->base.isotropy.channel, unit, true, -1},
        {"ambient", true, m->ambient.texture, 0, positive, true, -1},
        {"emission", true, m->emission.texture, 0, positive, true, -1},
        {"transparency", false, m->transparency.texture, m->transparency.channel, unit, f->transparent, -1},
        {"coat_c", true, m->has_coat ? m->coat.reflectance.texture : 0, 0, unit, f->coat, -1},
        {"coat_r", false, m->has_coat ? m->coat.roughness.texture : 0, m->coat.roughness.channel, unit, f->coat, -1},
        {"coat_p", false, m->has_coat ? m->coat.isotropy.texture : 0, m->coat.isotropy.channel, unit,
         f->coat && f->aniso, -1},
    };
    memcpy(p, list, sizeof list);
}

/* GL takes matrices column by column; ours are row-major (m[row * n + col]). */
static void column_major(const double *m, int n, float *out)
{
    for (int c = 0; c < n; c++)
        for (int r = 0; r < n; r++)
            out[c * n + r] = (float)m[r * n + c];
}


static const char *const shape_name[BG_SHAPE_COUNT_] = {"sphere", "plane", "box", "cylinder", "rectangle"};
static const char *const uv_name[BG_UV_COUNT_] = {"none", "spherical", "planar", "box", "cylindrical"};

/* Uniform storage as old hardware allocates it: every float, vec2 or vec3 takes a whole vec4. */
static int slots(macs_uniform_type t)
{
    return t == MACS_UNIFORM_MAT4 ? 16 : t == MACS_UNIFORM_MAT3 ? 12 : 4;
}

/* One object of the pass: its parameters, whether it samples textures, its uniforms' names. */
typedef struct member {
    uint32_t object;
    param p[P_COUNT];
    bool need_uv;
    char name[P_COUNT + 6][28];
} member;

int gpu_hit_object_needs(const bg_renderer *r, const bg_scene_state *state, uint32_t object,
                         uint32_t textures[GPU_HIT_MAX_TEXTURES], int *texture_count)
{
    const gpu_features *f = &r->features;
    const bg_object_data *obj = &state->objects[object];
    param p[P_COUNT];
    describe(&state->materials[obj->material], f, p);
    int comps = slots(MACS_UNIFORM_FLOAT) + slots(MACS_UNIFORM_MAT4) + slots(MACS_UNIFORM_MAT3);
    if (f->slot[GPU_SLOT_TANGENT])
        comps += slots(MACS_UNIFORM_MAT3);
    if (f->transparent)
        comps += slots(MACS_UNIFORM_FLOAT);
    *texture_count = 0;
    for (int i = 0; i < P_COUNT; i++) {
        if (!p[i].used)
            continue;
        comps += slots(p[i].color ? MACS_UNIFORM_VEC3 : MACS_UNIFORM_FLOAT);
        if (!p[i].texture && !f->generic)
            continue;
        bool seen = false;
        for (int k = 0; k < *texture_count; k++)
            seen = seen || textures[k] == p[i].texture;
        if (!seen)
            textures[(*texture_count)++] = p[i].texture;
    }
    if (*texture_count > 0)
        comps += slots(MACS_UNIFORM_VEC2); /* uv scale */
    return comps;
}

int gpu_hit_shared_components(void)
{
    return slots(MACS_UNIFORM_FLOAT); /* dmax */
}

/* The functions of the pass: each distinct shape's root and each distinct UV mapping, renamed by
 * suffix so that they coexist in one program. */
static bool hit_functions(gpu_text *t, const bg_scene_state *state, const member *m, int count, bool need_tangent)
{
    const char *seen[48];
    int n = 0;
    bool ok = gpu_text_snippet(t, "bg_stage_hit.glsl", seen, &n, 48);
    if (need_tangent)
        ok = ok && gpu_text_snippet(t, "bg_tangent.glsl", seen, &n, 48);
    static const char *const span[] = {"bg_shape_span", NULL};
    static const char *const root[] = {"bg_shape_span", "bg_hit_root", NULL};
    static const char *const uv[] = {"bg_uv_map", NULL};
    bool shape_done[BG_SHAPE_COUNT_] = {false}, uv_done[BG_UV_COUNT_] = {false};
    for (int j = 0; j < count && ok; j++) {
        const bg_object_data *o = &state->objects[m[j].object];
        if (!shape_done[o->shape]) {
            shape_done[o->shape] = true;
            ok = gpu_text_snippet_renamed(t, shape_file[o->shape], span, shape_name[o->shape], seen, &n, 48) &&
                 gpu_text_snippet_renamed(t, "bg_hit_root.glsl", root, shape_name[o->shape], seen, &n, 48);
        }
        if ((m[j].need_uv || need_tangent) && !uv_done[o->uv_mapping] && ok) {
            uv_done[o->uv_mapping] = true;
            ok = uv_file[o->uv_mapping] &&
                 gpu_text_snippet_renamed(t, uv_file[o->uv_mapping], uv, uv_name[o->uv_mapping], seen, &n, 48);
        }
    }
    return ok;
}

/* Sets the constants of member j (object and material) into the pass. */
static macs_status set_member_uniforms(const bg_renderer *r, macs_pass *pass, const bg_scene_state *state,
                                       const member *mb, bool need_tangent)
{
    const gpu_features *f = &r->features;
    uint32_t index = mb->object;
    const bg_object_data *obj = &state->objects[index];
    const bg_material *m = &state->materials[obj->material];
    const param *p = mb->p;
    float fi = (float)index, m16[16], m9[9];
    macs_status ms = macs_pass_set_uniform(pass, mb->name[P_COUNT + 0], &fi);
    gpu_origin_to_object(state, index, m16);
    if (!ms)
        ms = macs_pass_set_uniform(pass, mb->name[P_COUNT + 1], m16);
    column_major(&obj->normal_to_world[0][0], 3, m9);
    if (!ms)
        ms = macs_pass_set_uniform(pass, mb->name[P_COUNT + 2], m9);
    if (!ms && need_tangent) {
        double l3[3][3];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                l3[i][j] = obj->to_world[i][j];
        column_major(&l3[0][0], 3, m9);
        ms = macs_pass_set_uniform(pass, mb->name[P_COUNT + 3], m9);
    }
    if (!ms && mb->need_uv) {
        float uv[2] = {(float)obj->uv_scale[0], (float)obj->uv_scale[1]};
        ms = macs_pass_set_uniform(pass, mb->name[P_COUNT + 4], uv);
    }
    const bg_color_param *colors[P_COUNT] = {&m->base.reflectance, NULL, NULL, &m->ambient, &m->emission, NULL,
                                             &m->coat.reflectance, NULL, NULL};
    const bg_scalar_param *scalars[P_COUNT] = {NULL, &m->base.roughness, &m->base.isotropy, NULL, NULL,
                                               &m->transparency, NULL, &m->coat.roughness, &m->coat.isotropy};
    for (int i = 0; i < P_COUNT && !ms; i++) {
        if (!p[i].used)
            continue;
        if (p[i].color) {
            const bg_color_param *c = colors[i];
            double rgb[3] = {c->r, c->g, c->b};
            /* The scene's ambient light folds into the material's ambient colour here. */
            if (i == P_AMBIENT)
                for (int k = 0; k < 3; k++)
                    rgb[k] *= state->ambient[k];
            float v[3] = {(float)rgb[0], (float)rgb[1], (float)rgb[2]};
            if (i == P_COAT_C && !m->has_coat)
                v[0] = v[1] = v[2] = 0.0f;
            ms = macs_pass_set_uniform(pass, mb->name[i], v);
        } else {
            float v = (float)scalars[i]->value;
            if (i == P_COAT_R && !m->has_coat)
                v = -1.0f;
            if (i == P_COAT_P && !m->has_coat)
                v = 1.0f;
            ms = macs_pass_set_uniform(pass, mb->name[i], &v);
        }
    }
    if (!ms && f->transparent) {
        float ior = (float)m->ior;
        ms = macs_pass_set_uniform(pass, mb->name[P_COUNT + 5], &ior);
    }
    return ms;
}

/* The winner's surface: normal, hit code, UV, tangent and material, all from member j's uniforms. */
static void emit_surface(gpu_text *t, const bg_scene_state *state, const member *mb, int j, bool need_tangent,
                         bool transparent, bool coat)
{
    const bg_object_data *obj = &state->objects[mb->object];
    const char *thin = is_thin(obj->shape) ? "true" : "false";
    gpu_text_printf(t, "    bg_n = bg_hit_normal(bg_normal_to_world_%d, bg_no, bg_rd.xyz, %s, bg_first, bg_entering);\n",
                    j, thin);
    gpu_text_printf(t, "    bg_code = bg_hit_code(bg_index_%d, %s, bg_entering);\n", j, thin);
    if (mb->need_uv || need_tangent)
        gpu_text_printf(t, "    vec3 bg_dpdu;\n    vec2 bg_uv = bg_uv_map_%s(bg_po, bg_dpdu);\n", uv_name[obj->uv_mapping]);
    if (mb->need_uv)
        gpu_text_printf(t, "    bg_uv *= bg_uv_scale_%d;\n", j);
    if (need_tangent)
        gpu_text_printf(t, "    bg_tg = bg_tangent(bg_to_world3_%d * bg_dpdu, bg_n);\n", j);
    const param *p = mb->p;
    for (int i = 0; i < P_COUNT; i++) {
        if (!p[i].used)
            continue;
        char value[128];
        if (p[i].sampler >= 0) {
            char lane[8];
            if (p[i].color)
                snprintf(lane, sizeof lane, "rgb");
            else
                snprintf(lane, sizeof lane, "%c", "rgba"[p[i].channel & 3]);
            snprintf(value, sizeof value, "%s * texture2D(bg_tex%d, bg_uv).%s", mb->name[i], p[i].sampler, lane);
        } else {
            snprintf(value, sizeof value, "%s", mb->name[i]);
        }
        char clamped[192];
        snprintf(clamped, sizeof clamped, p[i].clamp, value);
        gpu_text_printf(t, "    bg_%s = %s;\n", p[i].name, clamped);
    }
    /* A negative coat roughness uniform marks a material without a coat. */
    if (coat)
        gpu_text_printf(t, "    if (%s < 0.0) bg_coat_r = -1.0;\n", mb->name[P_COAT_R]);
    if (transparent)
        gpu_text_printf(t, "    bg_ior = %s;\n", mb->name[P_COUNT + 5]);
}

bg_status gpu_hit_pass_build(bg_renderer *r, const bg_scene_state *state, uint32_t first, int count, bool trial,
                             macs_pass **out, bool *rejected)
{
    const gpu_features *f = &r->features;
    *out = NULL;
    if (rejected)
        *rejected = false;
    if (count < 1 || count > GPU_BATCH_MAX)
        return gpu_fail(r, BG_ERR_LIMIT, "bg_render_gpu: intersection batch of %d objects", count);
    member *mbs = bg_alloc(&r->allocator, (size_t)count * sizeof *mbs);
    if (!mbs)
        return gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "bg_render_gpu: out of memory building an intersection pass");
    bool need_tangent = f->slot[GPU_SLOT_TANGENT];

    /* Texture lanes: distinct scene textures of the batch become inputs 3.. ; in generic mode every
     * used parameter samples something, the white texel where the material has no texture. */
    enum { MAX_INPUTS = 3 + GPU_BATCH_MAX * P_COUNT };
    macs_input_desc inputs[MAX_INPUTS];
    macs_texture *input_tex[MAX_INPUTS];
    char input_names[MAX_INPUTS][24];
    uint32_t lane_texture[MAX_INPUTS];
    int input_count = 3, lanes = 0;
    inputs[0].name = "bg_ray_origin";
    inputs[1].name = "bg_ray_dir";
    inputs[2].name = "bg_ray_weight";
    input_tex[0] = input_tex[1] = input_tex[2] = NULL;

    enum { MAX_UNIFORMS = 1 + GPU_BATCH_MAX * (P_COUNT + 6) };
    macs_uniform_desc uniforms[MAX_UNIFORMS];
    int nu = 0;
    uniforms[nu++] = (macs_uniform_desc){"bg_dmax", MACS_UNIFORM_FLOAT, 0};
    for (int j = 0; j < count; j++) {
        member *mb = &mbs[j];
        mb->object = first + (uint32_t)j;
        const bg_object_data *obj = &state->objects[mb->object];
        describe(&state->materials[obj->material], f, mb->p);
        param *p = mb->p;
        mb->need_uv = false;
        for (int i = 0; i < P_COUNT; i++) {
            if (!p[i].used || (!p[i].texture && !f->generic))
                continue;
            int lane = -1;
            for (int k = 0; k < lanes; k++)
                if (lane_texture[k] == p[i].texture)
                    lane = k;
            if (lane < 0) {
                lane = lanes++;
                lane_texture[lane] = p[i].texture;
                snprintf(input_names[lane], sizeof input_names[lane], "bg_tex%d", lane);
                inputs[input_count].name = input_names[lane];
                input_tex[input_count] = p[i].texture ? r->textures[p[i].texture - 1] : r->white;
                input_count++;
            }
            p[i].sampler = lane;
            mb->need_uv = true;
        }
        static const char *const fixed[6] = {"bg_index", "bg_to_object", "bg_normal_to_world", "bg_to_world3",
                                             "bg_uv_scale", "bg_m%d_ior"};
        static const macs_uniform_type fixed_type[6] = {MACS_UNIFORM_FLOAT, MACS_UNIFORM_MAT4, MACS_UNIFORM_MAT3,
                                                        MACS_UNIFORM_MAT3, MACS_UNIFORM_VEC2, MACS_UNIFORM_FLOAT};
        bool fixed_used[6] = {true, true, true, need_tangent, mb->need_uv, f->transparent};
        for (int i = 0; i < 6; i++) {
            if (i == 5)
                snprintf(mb->name[P_COUNT + i], sizeof mb->name[0], fixed[i], j);
            else
                snprintf(mb->name[P_COUNT + i], sizeof mb->name[0], "%s_%d", fixed[i], j);
            if (fixed_used[i])
                uniforms[nu++] = (macs_uniform_desc){mb->name[P_COUNT + i], fixed_type[i], 0};
        }
        for (int i = 0; i < P_COUNT; i++) {
            snprintf(mb->name[i], sizeof mb->name[i], "bg_m%d_%s", j, p[i].name);
            if (p[i].used)
                uniforms[nu++] = (macs_uniform_desc){mb->name[i], p[i].color ? MACS_UNIFORM_VEC3 : MACS_UNIFORM_FLOAT, 0};
        }
    }

    /* main: every member's root, the nearest by the depth buffer's own comparison (strict, so the
     * member drawn first in one-object order wins a tie, as LESS between passes decides), then the
     * winner's surface in a static branch per member. */
    gpu_text main;
    gpu_text_init(&main, &r->allocator);
    /* Writing gl_FragDepth makes GL test the stencil after the shader, so a dead ray is also
     * rejected here, before any intersection work (the same pixels as the stencil rejects). */
    gpu_text_append(&main, "vec4 bg_w = texture2D(bg_ray_weight, macs_uv);\n");
    if (!(r->key.disable_skips & BG_SKIP_STENCIL))
        gpu_text_append(&main, "if (bg_w.a <= 0.0)\n    discard;\n");
    gpu_text_append(&main,
                    "vec4 bg_ro = texture2D(bg_ray_origin, macs_uv);\n"
                    "vec4 bg_rd = texture2D(bg_ray_dir, macs_uv);\n"
                    "float bg_t = 0.0, bg_z = 1.0, bg_key = 33554432.0, bg_win = -1.0;\n"
                    "vec3 bg_po = vec3(0.0), bg_no = vec3(0.0, 1.0, 0.0);\nbool bg_first = true;\n");
    const char *fixed24 = r->float_depth ? "false" : "true";
    for (int j = 0; j < count; j++) {
        const bg_object_data *obj = &state->objects[mbs[j].object];
        gpu_text_printf(&main,
                        "{\n    float bg_tj, bg_zj;\n    vec3 bg_poj, bg_noj;\n    bool bg_fj;\n"
                        "    if (bg_hit_root_%s(bg_ro, bg_rd, bg_index_%d, bg_to_object_%d, bg_tj, bg_poj, bg_noj, bg_fj)) {\n"
                        "        bg_zj = bg_depth(bg_tj, bg_dmax);\n"
                        "        float bg_kj = bg_depth_key(bg_zj, %s);\n"
                        "        if (bg_kj < bg_key) {\n"
                        "            bg_key = bg_kj; bg_win = %d.0; bg_t = bg_tj; bg_z = bg_zj;\n"
                        "            bg_po = bg_poj; bg_no = bg_noj; bg_first = bg_fj;\n"
                        "        }\n    }\n}\n",
                        shape_name[obj->shape], j, j, fixed24, j);
    }
    gpu_text_append(&main, "if (bg_win < 0.0)\n    discard;\ngl_FragDepth = bg_z;\n"
                           "vec3 bg_p = bg_ro.xyz + bg_t * bg_rd.xyz;\n"
                           "bool bg_entering;\nvec3 bg_n;\nfloat bg_code;\n");
    if (need_tangent)
        gpu_text_append(&main, "vec3 bg_tg;\n");
    for (int i = 0; i < P_COUNT; i++)
        if (mbs[0].p[i].used) /* which parameters are used depends on the features only */
            gpu_text_printf(&main, "%s bg_%s;\n", mbs[0].p[i].color ? "vec3" : "float", mbs[0].p[i].name);
    if (f->transparent)
        gpu_text_append(&main, "float bg_ior;\n");
    for (int j = 0; j < count; j++) {
        if (count == 1)
            gpu_text_append(&main, "{\n");
        else if (j == count - 1)
            gpu_text_append(&main, "else {\n");
        else
            gpu_text_printf(&main, "%sif (bg_win == %d.0) {\n", j ? "else " : "", j);
        emit_surface(&main, state, &mbs[j], j, need_tangent, f->transparent, f->coat);
        gpu_text_append(&main, "}\n");
    }
    if (!f->transparent)
        gpu_text_append(&main, "float bg_transparency = 0.0;\n");
    gpu_text_append(&main, "float bg_opaque = 1.0 - bg_transparency;\n");

    macs_output_desc outputs[GPU_SLOT_COUNT];
    macs_texture *output_tex[GPU_SLOT_COUNT];
    int no = 0;
    /* ONCE carries the ior lane only with transparency, TANGENT the coat's isotropy only with coats. */
    char once_value[128], tangent_value[64];
    snprintf(once_value, sizeof once_value, "vec4(bg_w.rgb * (bg_emission + bg_opaque * bg_ambient), %s)",
             f->transparent ? "bg_ior" : "1.0");
    snprintf(tangent_value, sizeof tangent_value, "vec4(bg_tg, %s)", f->coat ? "bg_coat_p" : "1.0");
    const char *const slot_value[GPU_SLOT_COUNT] = {
        "vec4(bg_p, bg_code)",      "vec4(bg_n, bg_base_r)", "vec4(bg_base_c, bg_base_p)",
        once_value,                 "vec4(bg_w.rgb * bg_opaque, bg_transparency)",
        tangent_value,              "vec4(bg_coat_c, bg_coat_r)",
    };
    static const char *const slot_name[GPU_SLOT_COUNT] = {"hit", "normal", "base", "once", "xparent", "tangent", "coat"};
    for (int s = 0; s < GPU_SLOT_COUNT; s++) {
        if (!f->slot[s])
            continue;
        outputs[no].name = slot_name[s];
        outputs[no].value = slot_value[s];
        output_tex[no] = r->gbuffer[s];
        no++;
    }

    bool stencil_skip = !(r->key.disable_skips & BG_SKIP_STENCIL);
    macs_pass_desc desc;
    gpu_pass_desc_init(&desc, main.s, inputs, input_tex, input_count, uniforms, nu, outputs, output_tex, no);
    desc.depth_stencil = r->depth;
    desc.depth.test = true;
    desc.depth.write = true;
    desc.depth.func = MACS_COMPARE_LESS;
    desc.stencil.test = true;
    desc.stencil.func = stencil_skip ? MACS_COMPARE_EQUAL : MACS_COMPARE_ALWAYS;
    desc.stencil.ref = GPU_STENCIL_LIVE | GPU_STENCIL_HIT;
    desc.stencil.read_mask = GPU_STENCIL_LIVE;
    desc.stencil.write_mask = GPU_STENCIL_HIT;
    desc.stencil.pass = MACS_STENCIL_OP_REPLACE;

    gpu_text functions;
    gpu_text_init(&functions, &r->allocator);
    bool have = hit_functions(&functions, state, mbs, count, need_tangent);
    bg_status st = BG_OK;
    if (main.failed || functions.failed)
        st = gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "bg_render_gpu: out of memory building the intersection shader");
    else if (!have)
        st = gpu_fail(r, BG_ERR_GL, "bg_render_gpu: intersection pass: a shape or UV mapping shader file is missing");
    else
        st = gpu_pass_try(r, "intersection pass", functions.s, &desc, trial, out, rejected);
    gpu_text_free(&main);
    gpu_text_free(&functions);
    if (st == BG_OK && *out) {
        macs_status ms = MACS_OK;
        for (int j = 0; j < count && !ms; j++)
            ms = set_member_uniforms(r, *out, state, &mbs[j], need_tangent);
        if (ms)
            st = gpu_fail_macs(r, ms, "intersection pass uniforms");
    }
    bg_free(&r->allocator, mbs);
    return st;
}

bg_status gpu_hit_pass_set_dmax(bg_renderer *r, macs_pass *pass, double dmax)
{
    float v = (float)dmax;
    macs_status ms = macs_pass_set_uniform(pass, "bg_dmax", &v);
    return ms ? gpu_fail_macs(r, ms, "intersection pass dmax") : BG_OK;
}
