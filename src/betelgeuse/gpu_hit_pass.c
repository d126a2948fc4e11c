/* The intersection pass of one object (DESIGN.md section 3.2.1): the object's shape and UV mapping
 * files, its material evaluated at the hit (texture lookups only for textured parameters unless
 * specialisation is off), depth t / dmax, and the G-buffer slots the scene's features ask for.
 * Material constants are uniforms, so a value-only re-commit reuses the compiled program. */
#include <stdio.h>
#include <string.h>

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

bg_status gpu_hit_pass_build(bg_renderer *r, const bg_scene_state *state, uint32_t index, macs_pass **out)
{
    const gpu_features *f = &r->features;
    const bg_object_data *obj = &state->objects[index];
    const bg_material *m = &state->materials[obj->material];
    param p[P_COUNT];
    describe(m, f, p);

    /* Texture lanes: distinct scene textures become inputs 3.. ; in generic mode every used
     * parameter samples something, the white texel where the material has no texture. */
    macs_input_desc inputs[3 + P_COUNT];
    macs_texture *input_tex[3 + P_COUNT];
    char input_names[P_COUNT][24];
    uint32_t lane_texture[P_COUNT];
    int input_count = 3, lanes = 0;
    inputs[0].name = "bg_ray_origin";
    inputs[1].name = "bg_ray_dir";
    inputs[2].name = "bg_ray_weight";
    input_tex[0] = input_tex[1] = input_tex[2] = NULL;
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
    }
    bool need_uv = lanes > 0;
    bool need_tangent = f->slot[GPU_SLOT_TANGENT];

    macs_uniform_desc uniforms[24];
    int nu = 0;
    uniforms[nu++] = (macs_uniform_desc){"bg_index", MACS_UNIFORM_FLOAT, 0};
    uniforms[nu++] = (macs_uniform_desc){"bg_dmax", MACS_UNIFORM_FLOAT, 0};
    uniforms[nu++] = (macs_uniform_desc){"bg_to_object", MACS_UNIFORM_MAT4, 0};
    uniforms[nu++] = (macs_uniform_desc){"bg_normal_to_world", MACS_UNIFORM_MAT3, 0};
    if (need_tangent)
        uniforms[nu++] = (macs_uniform_desc){"bg_to_world3", MACS_UNIFORM_MAT3, 0};
    if (need_uv)
        uniforms[nu++] = (macs_uniform_desc){"bg_uv_scale", MACS_UNIFORM_VEC2, 0};
    char uniform_names[P_COUNT][24];
    for (int i = 0; i < P_COUNT; i++) {
        if (!p[i].used)
            continue;
        snprintf(uniform_names[i], sizeof uniform_names[i], "bg_m_%s", p[i].name);
        uniforms[nu++] = (macs_uniform_desc){uniform_names[i], p[i].color ? MACS_UNIFORM_VEC3 : MACS_UNIFORM_FLOAT, 0};
    }
    if (f->transparent)
        uniforms[nu++] = (macs_uniform_desc){"bg_m_ior", MACS_UNIFORM_FLOAT, 0};

    /* main: the root, depth, attributes, material. */
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
                    "float bg_t;\nvec3 bg_po, bg_no;\nbool bg_first;\n"
                    "if (!bg_hit_root(bg_ro, bg_rd, bg_index, bg_to_object, bg_t, bg_po, bg_no, bg_first))\n"
                    "    discard;\n"
                    "gl_FragDepth = bg_depth(bg_t, bg_dmax);\n"
                    "vec3 bg_p = bg_ro.xyz + bg_t * bg_rd.xyz;\n"
                    "bool bg_entering;\n");
    gpu_text_printf(&main, "vec3 bg_n = bg_hit_normal(bg_normal_to_world, bg_no, bg_rd.xyz, %s, bg_first, bg_entering);\n",
                    is_thin(obj->shape) ? "true" : "false");
    gpu_text_printf(&main, "float bg_code = bg_hit_code(bg_index, %s, bg_entering);\n",
                    is_thin(obj->shape) ? "true" : "false");
    if (need_uv || need_tangent)
        gpu_text_append(&main, "vec3 bg_dpdu;\nvec2 bg_uv = bg_uv_map(bg_po, bg_dpdu);\n");
    if (need_uv)
        gpu_text_append(&main, "bg_uv *= bg_uv_scale;\n");
    if (need_tangent)
        gpu_text_append(&main, "vec3 bg_tg = bg_tangent(bg_to_world3 * bg_dpdu, bg_n);\n");
    for (int i = 0; i < P_COUNT; i++) {
        if (!p[i].used)
            continue;
        char value[128];
        if (p[i].sampler >= 0) {
            char lane[16];
            if (p[i].color)
                snprintf(lane, sizeof lane, "rgb");
            else
                snprintf(lane, sizeof lane, "%c", "rgba"[p[i].channel & 3]);
            snprintf(value, sizeof value, "bg_m_%s * texture2D(bg_tex%d, bg_uv).%s", p[i].name, p[i].sampler, lane);
        } else {
            snprintf(value, sizeof value, "bg_m_%s", p[i].name);
        }
        char clamped[192];
        snprintf(clamped, sizeof clamped, p[i].clamp, value);
        gpu_text_printf(&main, "%s bg_%s = %s;\n", p[i].color ? "vec3" : "float", p[i].name, clamped);
    }
    if (!f->transparent)
        gpu_text_append(&main, "float bg_transparency = 0.0;\n");
    /* A negative coat roughness uniform marks a material without a coat. */
    if (f->coat)
        gpu_text_append(&main, "if (bg_m_coat_r < 0.0) bg_coat_r = -1.0;\n");
    gpu_text_append(&main, "float bg_opaque = 1.0 - bg_transparency;\n");

    macs_output_desc outputs[GPU_SLOT_COUNT];
    macs_texture *output_tex[GPU_SLOT_COUNT];
    int no = 0;
    /* ONCE carries the ior lane only with transparency, TANGENT the coat's isotropy only with coats. */
    char once_value[128], tangent_value[64];
    snprintf(once_value, sizeof once_value, "vec4(bg_w.rgb * (bg_emission + bg_opaque * bg_ambient), %s)",
             f->transparent ? "bg_m_ior" : "1.0");
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

    const char *files[6];
    int nf = 0;
    files[nf++] = "bg_stage_hit.glsl";
    files[nf++] = shape_file[obj->shape];
    if (need_uv || need_tangent)
        files[nf++] = uv_file[obj->uv_mapping];
    if (need_tangent)
        files[nf++] = "bg_tangent.glsl";
    files[nf] = NULL;

    bg_status st = BG_OK;
    if (main.failed)
        st = gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "bg_render_gpu: out of memory building the intersection shader");
    else
        st = gpu_pass_create(r, "intersection pass", files, NULL, &desc, out);
    gpu_text_free(&main);
    if (st != BG_OK)
        return st;

    /* Constants of the object and its material. */
    macs_pass *pass = *out;
    float fi = (float)index, m16[16], m9[9];
    macs_status ms = macs_pass_set_uniform(pass, "bg_index", &fi);
    gpu_origin_to_object(state, index, m16);
    if (!ms)
        ms = macs_pass_set_uniform(pass, "bg_to_object", m16);
    column_major(&obj->normal_to_world[0][0], 3, m9);
    if (!ms)
        ms = macs_pass_set_uniform(pass, "bg_normal_to_world", m9);
    if (!ms && need_tangent) {
        double l3[3][3];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                l3[i][j] = obj->to_world[i][j];
        column_major(&l3[0][0], 3, m9);
        ms = macs_pass_set_uniform(pass, "bg_to_world3", m9);
    }
    if (!ms && need_uv) {
        float uv[2] = {(float)obj->uv_scale[0], (float)obj->uv_scale[1]};
        ms = macs_pass_set_uniform(pass, "bg_uv_scale", uv);
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
            ms = macs_pass_set_uniform(pass, uniform_names[i], v);
        } else {
            float v = (float)scalars[i]->value;
            if (i == P_COAT_R && !m->has_coat)
                v = -1.0f;
            if (i == P_COAT_P && !m->has_coat)
                v = 1.0f;
            ms = macs_pass_set_uniform(pass, uniform_names[i], &v);
        }
    }
    if (!ms && f->transparent) {
        float ior = (float)m->ior;
        ms = macs_pass_set_uniform(pass, "bg_m_ior", &ior);
    }
    if (ms)
        return gpu_fail_macs(r, ms, "intersection pass uniforms");
    return BG_OK;
}

bg_status gpu_hit_pass_set_dmax(bg_renderer *r, macs_pass *pass, double dmax)
{
    float v = (float)dmax;
    macs_status ms = macs_pass_set_uniform(pass, "bg_dmax", &v);
    return ms ? gpu_fail_macs(r, ms, "intersection pass dmax") : BG_OK;
}
