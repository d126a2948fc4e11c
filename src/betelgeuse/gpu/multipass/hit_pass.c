/* The intersection pass of a batch of objects (docs/gpu_pipeline.md): each object's root
 * by its shape's code, the nearest kept exactly as the depth test between one-object passes would
 * keep it, then the winner's material evaluated at the hit (texture lookups only for textured
 * parameters unless specialisation is off), its depth and the G-buffer slots the scene's features
 * ask for. The source is unrolled per object with per-object uniforms (no dynamic indexing, which
 * old hardware lacks) and per-texture samplers (GLSL 1.10 indexes samplers by constants only).
 * Material constants are uniforms, so a value-only re-commit reuses the compiled program.
 *
 * What an object declares is described once (member_describe): the batch planner's uniform budget
 * (bgi_gpu_hit_object_needs) and the pass's declarations are both read from that description. */
#include <stdio.h>
#include <string.h>

#include "../../common/alloc.h"
#include "../../common/shapes.h"
#include "multipass.h"

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

/* Each parameter samples at most one texture. */
typedef char every_parameter_textured_fits[GPU_P_COUNT_ <= GPU_HIT_MAX_TEXTURES ? 1 : -1];

/* Whether the pass declares parameter p: base and ambient terms always, the others when the scene's
 * features have them. */
static bool param_used(gpu_param p, const gpu_features *f)
{
    switch (p) {
    case GPU_P_TRANSPARENCY: return f->transparent;
    case GPU_P_COAT_C:
    case GPU_P_COAT_R: return f->coat;
    case GPU_P_COAT_P: return f->coat && f->aniso;
    default: return true;
    }
}

static void describe(const bg_material *m, const gpu_features *f, param p[GPU_P_COUNT_])
{
    for (int i = 0; i < GPU_P_COUNT_; i++) {
        gpu_param k = (gpu_param)i;
        double value[3];
        param *q = &p[i];
        q->name = bgi_gpu_param_local(k);
        q->color = bgi_gpu_param_is_color(k);
        bgi_gpu_param_of(m, k, value, &q->texture, &q->channel);
        /* A material without a coat has the constants of no coat (bgi_gpu_param_value), untextured. */
        if ((k == GPU_P_COAT_C || k == GPU_P_COAT_R || k == GPU_P_COAT_P) && !m->has_coat)
            q->texture = 0;
        q->clamp = bgi_gpu_param_is_unit(k) ? "clamp(%s, 0.0, 1.0)" : "max(%s, vec3(0.0))";
        q->used = param_used(k, f);
        q->sampler = -1;
    }
}

/* Whether a parameter reads a texture lane: its own texture, or in generic mode (every used
 * parameter samples) the white texel where it has none. */
static bool samples_texture(const param *p, const gpu_features *f)
{
    return p->used && (p->texture || f->generic);
}

/* GL takes matrices column by column; ours are row-major (m[row * n + col]). */
static void column_major(const double *m, int n, float *out)
{
    for (int c = 0; c < n; c++)
        for (int r = 0; r < n; r++)
            out[c * n + r] = (float)m[r * n + c];
}

/* The uniforms of an object besides its material parameters: the name (%d: the object's place in
 * the pass) and type of each. Which of them an object declares, member_describe decides. */
typedef enum object_uniform {
    U_INDEX,           /* its object index (the hit code and the skip and inside tests) */
    U_TO_OBJECT,       /* world (camera-relative) to prototype */
    U_NORMAL_TO_WORLD, /* inverse transpose of the linear part */
    U_TO_WORLD3,       /* the linear part, for tangents (only with the TANGENT slot) and a mesh's offset */
    U_UV_SCALE,        /* only for an object that samples a texture */
    U_IOR,             /* only with transparency */
    U_MESH_BASE,       /* a mesh's root node and first triangle texels in the mesh textures */
    U_COUNT
} object_uniform;

static const struct {
    const char *format;
    macs_uniform_type type;
} object_uniform_row[U_COUNT] = {
    [U_INDEX] = {"bg_index_%d", MACS_UNIFORM_FLOAT},
    [U_TO_OBJECT] = {"bg_to_object_%d", MACS_UNIFORM_MAT4},
    [U_NORMAL_TO_WORLD] = {"bg_normal_to_world_%d", MACS_UNIFORM_MAT3},
    [U_TO_WORLD3] = {"bg_to_world3_%d", MACS_UNIFORM_MAT3},
    [U_UV_SCALE] = {"bg_uv_scale_%d", MACS_UNIFORM_VEC2},
    [U_IOR] = {"bg_m%d_ior", MACS_UNIFORM_FLOAT},
    [U_MESH_BASE] = {"bg_mesh_%d", MACS_UNIFORM_VEC2},
};

/* The uniforms of every intersection pass whatever its objects (set per level: bgi_gpu_hit_pass_set_dmax),
 * then the one of a pass with a mesh: the mesh textures' geometry. */
static const macs_uniform_desc shared_uniforms[] = {{"bg_dmax", MACS_UNIFORM_FLOAT, 0},
                                                    {"bg_mesh_dims", MACS_UNIFORM_VEC4, 0}};
#define SHARED_UNIFORM_COUNT ((int)(sizeof shared_uniforms / sizeof shared_uniforms[0]))

#define UNIFORM_NAME_SIZE 28

/* One object of the pass: its parameters, the textures it samples and the uniforms it declares. */
typedef struct member {
    uint32_t object;
    param p[GPU_P_COUNT_];
    uint32_t textures[GPU_HIT_MAX_TEXTURES]; /* distinct scene textures it samples, 0 the white texel */
    int texture_count;
    bool need_uv; /* it samples some texture */
    bool mesh;    /* a mesh object: its test walks its mesh's tree */
    bool glossy;  /* its material is glossy: a negative ior marks it in the G-buffer */
    bool declares[U_COUNT];
    char object_uniform[U_COUNT][UNIFORM_NAME_SIZE];
    char param_uniform[GPU_P_COUNT_][UNIFORM_NAME_SIZE];
    macs_uniform_desc uniforms[U_COUNT + GPU_P_COUNT_]; /* what it declares, names pointing into the above */
    int uniform_count;
} member;

int bgi_gpu_hit_texture_lane(uint32_t *lanes, int *lane_count, uint32_t texture)
{
    for (int k = 0; k < *lane_count; k++)
        if (lanes[k] == texture)
            return k;
    lanes[*lane_count] = texture;
    return (*lane_count)++;
}

/* Describes object `object` as member j of a pass. */
static void member_describe(const bg_renderer *r, const bg_scene_state *state, uint32_t object, int j, member *mb)
{
    const gpu_features *f = &r->multipass->features;
    mb->object = object;
    describe(&state->materials[state->objects[object].material], f, mb->p);
    mb->texture_count = 0;
    for (int i = 0; i < GPU_P_COUNT_; i++)
        if (samples_texture(&mb->p[i], f))
            bgi_gpu_hit_texture_lane(mb->textures, &mb->texture_count, mb->p[i].texture);
    mb->need_uv = mb->texture_count > 0;
    mb->mesh = state->objects[object].shape == BGI_SHAPE_MESH;
    mb->glossy = state->materials[state->objects[object].material].glossy;

    mb->declares[U_INDEX] = mb->declares[U_TO_OBJECT] = mb->declares[U_NORMAL_TO_WORLD] = true;
    mb->declares[U_TO_WORLD3] = f->slot[GPU_SLOT_TANGENT] || mb->mesh;
    mb->declares[U_UV_SCALE] = mb->need_uv;
    mb->declares[U_IOR] = f->transparent;
    mb->declares[U_MESH_BASE] = mb->mesh;
    mb->uniform_count = 0;
    for (int u = 0; u < U_COUNT; u++) {
        snprintf(mb->object_uniform[u], UNIFORM_NAME_SIZE, object_uniform_row[u].format, j);
        if (mb->declares[u])
            mb->uniforms[mb->uniform_count++] =
                (macs_uniform_desc){mb->object_uniform[u], object_uniform_row[u].type, 0};
    }
    for (int i = 0; i < GPU_P_COUNT_; i++) {
        snprintf(mb->param_uniform[i], UNIFORM_NAME_SIZE, "bg_m%d_%s", j, mb->p[i].name);
        if (mb->p[i].used)
            mb->uniforms[mb->uniform_count++] =
                (macs_uniform_desc){mb->param_uniform[i], mb->p[i].color ? MACS_UNIFORM_VEC3 : MACS_UNIFORM_FLOAT, 0};
    }
}

int bgi_gpu_hit_object_needs(const bg_renderer *r, const bg_scene_state *state, uint32_t object,
                         uint32_t textures[GPU_HIT_MAX_TEXTURES], int *texture_count)
{
    member mb;
    member_describe(r, state, object, 0, &mb);
    memcpy(textures, mb.textures, (size_t)mb.texture_count * sizeof *textures);
    *texture_count = mb.texture_count;
    return bgi_gpu_uniform_components(mb.uniforms, mb.uniform_count);
}

int bgi_gpu_hit_shared_components(void)
{
    return bgi_gpu_uniform_components(shared_uniforms, SHARED_UNIFORM_COUNT);
}

/* How parameter q samples its lane's texture (the white texel when it has none). */
static gpu_texture_mode param_mode(const bg_renderer *r, const bg_scene_state *state, const param *q)
{
    return bgi_gpu_texture_mode(q->texture ? &state->textures[q->texture - 1] : NULL, bgi_gpu_srgb_table(r));
}

/* Whether some member samples a GL_LINEAR texture (srgb false: the pass then filters in the shader)
 * or an 8-bit sRGB one (srgb true: the pass then decodes through the table bg_srgb_table). */
static bool members_sample(const bg_renderer *r, const bg_scene_state *state, const member *m, int count, bool srgb)
{
    for (int j = 0; j < count; j++)
        for (int i = 0; i < GPU_P_COUNT_; i++) {
            if (m[j].p[i].sampler < 0)
                continue;
            gpu_texture_mode mode = param_mode(r, state, &m[j].p[i]);
            if (srgb ? mode.srgb : mode.linear)
                return true;
        }
    return false;
}

/* The functions of the pass: each distinct shape's root and each distinct UV mapping, renamed by
 * suffix so that they coexist in one program. */
static bool hit_functions(gpu_text *t, const bg_renderer *r, const bg_scene_state *state, const member *m, int count,
                          bool need_tangent)
{
    const char *seen[48];
    int n = 0;
    bool ok = bgi_gpu_text_snippet(t, "bg_stage_hit.glsl", seen, &n, 48);
    if (members_sample(r, state, m, count, false))
        ok = ok && bgi_gpu_text_snippet(t, "bg_texture_filter.glsl", seen, &n, 48);
    if (members_sample(r, state, m, count, true))
        ok = ok && bgi_gpu_text_snippet(t, "bg_texture_srgb.glsl", seen, &n, 48);
    if (need_tangent)
        ok = ok && bgi_gpu_text_snippet(t, "bg_tangent.glsl", seen, &n, 48);
    int meshes = 0;
    for (int j = 0; j < count; j++)
        meshes += m[j].mesh ? 1 : 0;
    if (meshes > 0) {
        ok = ok && bgi_gpu_text_snippet(t, "bg_tree_textures.glsl", seen, &n, 48) &&
             bgi_gpu_mesh_library(t, seen, &n, 48);
        if (ok)
            bgi_gpu_mesh_pass_walks(meshes, bgi_gpu_meshes_filters(state), t);
    }
    uint32_t objects[GPU_BATCH_MAX];
    for (int j = 0; j < count; j++)
        objects[j] = m[j].object;
    static const char *const root[] = {"bg_hit_root", NULL};
    ok = ok && bgi_gpu_text_shape_stages(t, state, objects, count, "bg_hit_root.glsl", root, seen, &n, 48);
    static const char *const uv[] = {"bg_uv_map", NULL};
    bool uv_done[BG_UV_COUNT_] = {false};
    for (int j = 0; j < count && ok; j++) {
        bg_uv_mapping mapping = state->objects[m[j].object].uv_mapping;
        if (!m[j].mesh && (m[j].need_uv || need_tangent) && !uv_done[mapping]) {
            uv_done[mapping] = true;
            ok = bgi_gpu_uv_file(mapping) && bgi_gpu_text_snippet_renamed(t, bgi_gpu_uv_file(mapping), uv,
                                                                          bgi_gpu_uv_suffix(mapping), seen, &n, 48);
        }
    }
    return ok;
}

/* Sets a member's object constants (those it declares) into the pass. */
static macs_status set_object_uniforms(macs_pass *pass, const bg_scene_state *state, const gpu_meshes *meshes,
                                       const member *mb)
{
    const bg_object_data *obj = &state->objects[mb->object];
    float fi = (float)mb->object, m16[16], m9[9];
    macs_status ms = macs_pass_set_uniform(pass, mb->object_uniform[U_INDEX], &fi);
    bgi_gpu_origin_to_object(state, mb->object, m16);
    if (!ms)
        ms = macs_pass_set_uniform(pass, mb->object_uniform[U_TO_OBJECT], m16);
    column_major(&obj->normal_to_world[0][0], 3, m9);
    if (!ms)
        ms = macs_pass_set_uniform(pass, mb->object_uniform[U_NORMAL_TO_WORLD], m9);
    if (!ms && mb->declares[U_TO_WORLD3]) {
        double l3[3][3];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                l3[i][j] = obj->to_world[i][j];
        column_major(&l3[0][0], 3, m9);
        ms = macs_pass_set_uniform(pass, mb->object_uniform[U_TO_WORLD3], m9);
    }
    if (!ms && mb->declares[U_UV_SCALE]) {
        float uv[2] = {(float)obj->uv_scale[0], (float)obj->uv_scale[1]};
        ms = macs_pass_set_uniform(pass, mb->object_uniform[U_UV_SCALE], uv);
    }
    if (!ms && mb->declares[U_MESH_BASE])
        ms = macs_pass_set_uniform(pass, mb->object_uniform[U_MESH_BASE], &meshes->base[2 * (size_t)mb->object]);
    return ms;
}

/* Sets a member's material constants (its used parameters and the ior) into the pass. */
static macs_status set_material_uniforms(macs_pass *pass, const bg_scene_state *state, const member *mb)
{
    const bg_material *m = &state->materials[state->objects[mb->object].material];
    const param *p = mb->p;
    macs_status ms = MACS_OK;
    for (int i = 0; i < GPU_P_COUNT_ && !ms; i++) {
        if (!p[i].used)
            continue;
        float v[3];
        bgi_gpu_param_value(state, m, (gpu_param)i, v);
        ms = macs_pass_set_uniform(pass, mb->param_uniform[i], v);
    }
    if (!ms && mb->declares[U_IOR]) {
        float ior = (float)m->ior;
        ms = macs_pass_set_uniform(pass, mb->object_uniform[U_IOR], &ior);
    }
    return ms;
}

/* A mesh winner's normal, hit code, UV and tangent (docs/shading.md 2.10), and the offset of the
 * rays that leave it, which the MESH slot carries to the shadow and spawn passes. */
static void emit_mesh_geometry(gpu_text *t, const bg_scene_state *state, const member *mb, int j, bool need_tangent)
{
    /* An open mesh (BG_SIDES_BOTH) is thin, as a plane: its filter record says so. */
    char thin[96];
    snprintf(thin, sizeof thin, (bgi_gpu_meshes_filters(state) & GPU_MESH_OPEN) ? "bg_mesh_open(bg_mesh_tris, bg_mesh_dims, bg_mesh_%d.y)"
                                                                : "false", j);
    bgi_gpu_text_printf(t, "    vec2 bg_uv;\n    vec3 bg_dpdu, bg_g;\n    float bg_off;\n"
                           "    bg_mesh_attributes(bg_mesh_tris, bg_mesh_dims, bg_mesh_%d.y + 6.0 * bg_tri, bg_bary, bg_first, "
                           "bg_normal_to_world_%d, bg_to_world3_%d, bg_p, bg_rd.xyz, %.1f, bg_g, bg_n, bg_uv, bg_dpdu, bg_off);\n"
                           "    bg_entering = bg_first;\n    bg_code = bg_hit_code(bg_index_%d, %s, bg_entering);\n"
                           "    bg_mesh_ov = bg_g * bg_off;\n",
                        j, j, j, GPU_MESH_OFFSET_ULPS, j, thin);
    if (mb->need_uv)
        bgi_gpu_text_printf(t, "    bg_uv *= bg_uv_scale_%d;\n", j);
    if (need_tangent)
        bgi_gpu_text_printf(t, "    bg_tg = bg_tangent(bg_to_world3_%d * bg_dpdu, bg_n);\n", j);
}

/* An analytic winner's normal, hit code, UV and tangent (docs/shading.md 3). */
static void emit_shape_geometry(gpu_text *t, const bg_object_data *obj, const member *mb, int j, bool need_tangent)
{
    const char *thin = bg_shape_thin(obj->shape) ? "true" : "false";
    bgi_gpu_text_printf(t, "    bg_n = bg_hit_normal(bg_normal_to_world_%d, bg_no, bg_rd.xyz, %s, bg_first, bg_entering);\n",
                    j, thin);
    bgi_gpu_text_printf(t, "    bg_code = bg_hit_code(bg_index_%d, %s, bg_entering);\n", j, thin);
    if (mb->need_uv || need_tangent)
        bgi_gpu_text_printf(t, "    vec3 bg_dpdu;\n    vec2 bg_uv = bg_uv_map_%s(bg_po, bg_dpdu);\n", bgi_gpu_uv_suffix(obj->uv_mapping));
    if (mb->need_uv)
        bgi_gpu_text_printf(t, "    bg_uv *= bg_uv_scale_%d;\n", j);
    if (need_tangent)
        bgi_gpu_text_printf(t, "    bg_tg = bg_tangent(bg_to_world3_%d * bg_dpdu, bg_n);\n", j);
}

/* The winner's material parameters and index of refraction from member mb's uniforms. */
static void emit_params(gpu_text *t, const bg_renderer *r, const bg_scene_state *state, const member *mb,
                        bool transparent, bool coat, bool glossy)
{
    const param *p = mb->p;
    for (int i = 0; i < GPU_P_COUNT_; i++) {
        if (!p[i].used)
            continue;
        char value[320];
        if (p[i].sampler >= 0) {
            char lane[8], sampler[24], texel[192];
            if (p[i].color)
                snprintf(lane, sizeof lane, "rgb");
            else
                snprintf(lane, sizeof lane, "%c", "rgba"[p[i].channel & 3]);
            snprintf(sampler, sizeof sampler, "bg_tex%d", p[i].sampler);
            if (!bgi_gpu_texture_lookup(texel, sizeof texel, sampler, "bg_uv", param_mode(r, state, &p[i])))
                t->failed = true; /* cannot happen: every name above is short */
            snprintf(value, sizeof value, "%s * %s.%s", mb->param_uniform[i], texel, lane);
        } else {
            snprintf(value, sizeof value, "%s", mb->param_uniform[i]);
        }
        char clamped[384];
        snprintf(clamped, sizeof clamped, p[i].clamp, value);
        bgi_gpu_text_printf(t, "    bg_%s = %s;\n", p[i].name, clamped);
    }
    /* A negative coat roughness uniform marks a material without a coat. */
    if (coat)
        bgi_gpu_text_printf(t, "    if (%s < 0.0) bg_coat_r = -1.0;\n", mb->param_uniform[GPU_P_COAT_R]);
    if (transparent)
        bgi_gpu_text_printf(t, "    bg_ior = %s;\n", mb->object_uniform[U_IOR]);
    else if (glossy)
        bgi_gpu_text_append(t, "    bg_ior = 1.0;\n");
    if (mb->glossy)
        bgi_gpu_text_append(t, "    bg_ior = -bg_ior;\n");
}

/* The winner's surface: normal, hit code, UV, tangent and material, all from member j's uniforms. */
static void emit_surface(gpu_text *t, const bg_renderer *r, const bg_scene_state *state, const member *mb, int j,
                         bool need_tangent, bool transparent, bool coat, bool glossy)
{
    const bg_object_data *obj = &state->objects[mb->object];
    if (mb->mesh)
        emit_mesh_geometry(t, state, mb, j, need_tangent);
    else
        emit_shape_geometry(t, obj, mb, j, need_tangent);
    emit_params(t, r, state, mb, transparent, coat, glossy);
}

/* Texture lanes: distinct scene textures of the batch become inputs 3.. ; in generic mode every
 * used parameter samples something, the white texel where the material has no texture. The mesh
 * texture follows them in a pass with a mesh. */
#define MAX_INPUTS (6 + GPU_BATCH_MAX * GPU_HIT_MAX_TEXTURES)
#define MAX_UNIFORMS (SHARED_UNIFORM_COUNT + GPU_BATCH_MAX * (U_COUNT + GPU_P_COUNT_))

/* Everything a pass description points at while the pass is made. */
typedef struct hit_pass_parts {
    member *members;
    int count;
    int meshes; /* members that are meshes */
    uint32_t lane_texture[MAX_INPUTS];
    int lanes;
    macs_input_desc inputs[MAX_INPUTS];
    macs_texture *input_tex[MAX_INPUTS];
    char input_names[MAX_INPUTS][24];
    int input_count;
    macs_uniform_desc uniforms[MAX_UNIFORMS];
    int uniform_count;
    macs_output_desc outputs[GPU_SLOT_COUNT];
    macs_texture *output_tex[GPU_SLOT_COUNT];
    int output_count;
    char once_value[128], tangent_value[64], mesh_value[64];
} hit_pass_parts;

/* Describes objects first .. of the batch and gives each sampling parameter its lane. */
static void describe_members(const bg_renderer *r, const bg_scene_state *state, uint32_t first, hit_pass_parts *hp)
{
    hp->lanes = 0;
    hp->meshes = 0;
    for (int j = 0; j < hp->count; j++) {
        member *mb = &hp->members[j];
        member_describe(r, state, first + (uint32_t)j, j, mb);
        hp->meshes += mb->mesh ? 1 : 0;
        for (int i = 0; i < GPU_P_COUNT_; i++)
            if (samples_texture(&mb->p[i], &r->multipass->features))
                mb->p[i].sampler = bgi_gpu_hit_texture_lane(hp->lane_texture, &hp->lanes, mb->p[i].texture);
    }
}

/* The ray maps (rebound per ray set: GPU_HIT_IN_*), then one sampler per texture lane, the mesh
 * textures and the sRGB table where a member decodes through it. */
static void add_inputs(const bg_renderer *r, const bg_scene_state *state, hit_pass_parts *hp)
{
    static const char *const ray_maps[3] = {"bg_ray_origin", "bg_ray_dir", "bg_ray_weight"};
    hp->input_count = 0;
    for (int k = 0; k < 3; k++) {
        hp->inputs[hp->input_count].name = ray_maps[k];
        hp->input_tex[hp->input_count++] = NULL;
    }
    for (int lane = 0; lane < hp->lanes; lane++) {
        uint32_t texture = hp->lane_texture[lane];
        snprintf(hp->input_names[lane], sizeof hp->input_names[lane], "bg_tex%d", lane);
        hp->inputs[hp->input_count].name = hp->input_names[lane];
        hp->input_tex[hp->input_count++] = texture ? r->multipass->textures[texture - 1] : r->multipass->white;
    }
    if (hp->meshes > 0) {
        hp->inputs[hp->input_count].name = "bg_mesh_nodes";
        hp->input_tex[hp->input_count++] = r->meshes.nodes;
        hp->inputs[hp->input_count].name = "bg_mesh_tris";
        hp->input_tex[hp->input_count++] = r->meshes.triangles;
    }
    if (members_sample(r, state, hp->members, hp->count, true)) {
        hp->inputs[hp->input_count].name = "bg_srgb_table";
        hp->input_tex[hp->input_count++] = r->scene_textures.srgb_table;
    }
}

/* The shared uniforms, then each member's as it described them. */
static void add_uniforms(hit_pass_parts *hp)
{
    hp->uniform_count = 0;
    for (int k = 0; k < (hp->meshes > 0 ? SHARED_UNIFORM_COUNT : 1); k++)
        hp->uniforms[hp->uniform_count++] = shared_uniforms[k];
    for (int j = 0; j < hp->count; j++)
        for (int k = 0; k < hp->members[j].uniform_count; k++)
            hp->uniforms[hp->uniform_count++] = hp->members[j].uniforms[k];
}

/* The G-buffer slots the features ask for. */
static void add_outputs(const bg_renderer *r, hit_pass_parts *hp)
{
    const gpu_features *f = &r->multipass->features;
    /* ONCE carries the ior lane only with transparency or glossy materials (negative for these),
     * TANGENT the coat's isotropy only with coats. */
    snprintf(hp->once_value, sizeof hp->once_value, "vec4(bg_w.rgb * (bg_emission + bg_opaque * bg_ambient), %s)",
             f->transparent || f->glossy ? "bg_ior" : "1.0");
    snprintf(hp->tangent_value, sizeof hp->tangent_value, "vec4(bg_tg, %s)", f->coat ? "bg_coat_p" : "1.0");
    /* A pass without a mesh hits none: no offset, no triangle. */
    if (hp->meshes > 0)
        snprintf(hp->mesh_value, sizeof hp->mesh_value, "vec4(bg_mesh_ov, bg_short ? %.1f : bg_tri)", GPU_MESH_SHORT);
    else
        snprintf(hp->mesh_value, sizeof hp->mesh_value, "vec4(0.0, 0.0, 0.0, -1.0)");
    const char *const slot_value[GPU_SLOT_COUNT] = {
        "vec4(bg_p, bg_code)",      "vec4(bg_n, bg_base_r)", "vec4(bg_base_c, bg_base_p)",
        hp->once_value,             "vec4(bg_w.rgb * bg_opaque, bg_transparency)",
        hp->tangent_value,          "vec4(bg_coat_c, bg_coat_r)", hp->mesh_value,
    };
    static const char *const slot_name[GPU_SLOT_COUNT] = {"hit", "normal", "base", "once", "xparent", "tangent", "coat",
                                                          "mesh"};
    hp->output_count = 0;
    for (int s = 0; s < GPU_SLOT_COUNT; s++) {
        if (!f->slot[s])
            continue;
        hp->outputs[hp->output_count].name = slot_name[s];
        hp->outputs[hp->output_count].value = slot_value[s];
        hp->output_tex[hp->output_count++] = r->multipass->gbuffer[s];
    }
}

/* main, first half: every member's root, the nearest by the depth buffer's own comparison (strict,
 * so the member drawn first in one-object order wins a tie, as LESS between passes decides). */
static void emit_nearest_root(const bg_renderer *r, const bg_scene_state *state, const hit_pass_parts *hp,
                              gpu_text *main)
{
    /* Writing gl_FragDepth makes GL test the stencil after the shader, so a dead ray is also
     * rejected here, before any intersection work (the same pixels as the stencil rejects). */
    bgi_gpu_text_append(main, "vec4 bg_w = texture2D(bg_ray_weight, macs_uv);\n");
    if (!(r->multipass->key.disable_skips & BG_SKIP_STENCIL))
        bgi_gpu_text_append(main, "if (bg_w.a <= 0.0)\n    discard;\n");
    bgi_gpu_text_append(main,
                    "vec4 bg_ro = texture2D(bg_ray_origin, macs_uv);\n"
                    "vec4 bg_rd = texture2D(bg_ray_dir, macs_uv);\n"
                    "float bg_t = 0.0, bg_z = 1.0, bg_key = 33554432.0, bg_win = -1.0;\n"
                    "vec3 bg_po = vec3(0.0), bg_no = vec3(0.0, 1.0, 0.0);\nbool bg_first = true;\n");
    const char *fixed24 = r->float_depth ? "false" : "true";
    /* A mesh's walk spends the pass's steps (mesh_source.c); the winner's triangle and weights. */
    if (hp->meshes > 0)
        bgi_gpu_text_printf(main, "bg_tree_left = %d.0;\nbg_tree_short = 0.0;\nfloat bg_tri = -1.0;\n"
                                  "vec3 bg_bary = vec3(0.0);\n",
                            bgi_gpu_mesh_pass_budget(hp->meshes));
    for (int j = 0; j < hp->count; j++) {
        const bg_object_data *obj = &state->objects[hp->members[j].object];
        if (hp->members[j].mesh) {
            bgi_gpu_text_printf(main,
                            "{\n    float bg_tj, bg_zj;\n    bool bg_fj;\n"
                            "    if (bg_mesh_nearest(bg_ro, bg_rd, bg_index_%d, bg_to_object_%d, bg_mesh_%d, "
                            "bg_win >= 0.0 ? bg_t : 1e38, bg_tj, bg_fj)) {\n"
                            "        bg_zj = bg_depth(bg_tj, bg_dmax);\n"
                            "        float bg_kj = bg_depth_key(bg_zj, %s);\n"
                            "        if (bg_kj < bg_key) {\n"
                            "            bg_key = bg_kj; bg_win = %d.0; bg_t = bg_tj; bg_z = bg_zj;\n"
                            "            bg_po = vec3(0.0); bg_no = vec3(0.0, 1.0, 0.0); bg_first = bg_fj;\n"
                            "            bg_tri = bg_mesh_tri_j; bg_bary = bg_mesh_bary_j;\n"
                            "        }\n    }\n}\n",
                            j, j, j, fixed24, j);
            continue;
        }
        bgi_gpu_text_printf(main,
                        "{\n    float bg_tj, bg_zj;\n    vec3 bg_poj, bg_noj;\n    bool bg_fj;\n"
                        "    if (bg_hit_root_%s(bg_ro, bg_rd, bg_index_%d, bg_to_object_%d, bg_tj, bg_poj, bg_noj, bg_fj)) {\n"
                        "        bg_zj = bg_depth(bg_tj, bg_dmax);\n"
                        "        float bg_kj = bg_depth_key(bg_zj, %s);\n"
                        "        if (bg_kj < bg_key) {\n"
                        "            bg_key = bg_kj; bg_win = %d.0; bg_t = bg_tj; bg_z = bg_zj;\n"
                        "            bg_po = bg_poj; bg_no = bg_noj; bg_first = bg_fj;\n"
                        "        }\n    }\n}\n",
                        bgi_gpu_shape_suffix(obj->shape), j, j, fixed24, j);
    }
}

/* main, second half: the winner's surface in a static branch per member. */
static void emit_winner_surface(const bg_renderer *r, const bg_scene_state *state, const hit_pass_parts *hp,
                                gpu_text *main)
{
    const gpu_features *f = &r->multipass->features;
    bool need_tangent = f->slot[GPU_SLOT_TANGENT];
    /* A pixel whose walk ran out is kept at depth 0, marked in the MESH slot for the CPU reference
     * (multipass_frame.c), whatever it met. */
    if (hp->meshes > 0)
        bgi_gpu_text_append(main, "bool bg_short = bg_tree_short > 0.0;\nif (bg_win < 0.0 && !bg_short)\n    discard;\n"
                                  "gl_FragDepth = bg_short ? 0.0 : bg_z;\nvec3 bg_mesh_ov = vec3(0.0);\n");
    else
        bgi_gpu_text_append(main, "if (bg_win < 0.0)\n    discard;\ngl_FragDepth = bg_z;\n");
    bgi_gpu_text_append(main, "vec3 bg_p = bg_ro.xyz + bg_t * bg_rd.xyz;\n"
                          "bool bg_entering;\nvec3 bg_n;\nfloat bg_code;\n");
    if (need_tangent)
        bgi_gpu_text_append(main, "vec3 bg_tg;\n");
    const param *p0 = hp->members[0].p; /* which parameters are used depends on the features only */
    for (int i = 0; i < GPU_P_COUNT_; i++)
        if (p0[i].used)
            bgi_gpu_text_printf(main, "%s bg_%s;\n", p0[i].color ? "vec3" : "float", p0[i].name);
    if (f->transparent || f->glossy)
        bgi_gpu_text_append(main, "float bg_ior;\n");
    for (int j = 0; j < hp->count; j++) {
        if (hp->count == 1)
            bgi_gpu_text_append(main, "{\n");
        else if (j == hp->count - 1)
            bgi_gpu_text_append(main, "else {\n");
        else
            bgi_gpu_text_printf(main, "%sif (bg_win == %d.0) {\n", j ? "else " : "", j);
        emit_surface(main, r, state, &hp->members[j], j, need_tangent, f->transparent, f->coat, f->glossy);
        bgi_gpu_text_append(main, "}\n");
    }
    if (!f->transparent)
        bgi_gpu_text_append(main, "float bg_transparency = 0.0;\n");
    bgi_gpu_text_append(main, "float bg_opaque = 1.0 - bg_transparency;\n");
}

/* Depth LESS as between one-object passes; the stencil keeps live rays and marks their hits. */
static void set_depth_stencil(const bg_renderer *r, macs_pass_desc *desc)
{
    bool stencil_skip = !(r->multipass->key.disable_skips & BG_SKIP_STENCIL);
    desc->depth_stencil = r->multipass->depth;
    desc->depth.test = true;
    desc->depth.write = true;
    desc->depth.func = MACS_COMPARE_LESS;
    desc->stencil.test = true;
    desc->stencil.func = stencil_skip ? MACS_COMPARE_EQUAL : MACS_COMPARE_ALWAYS;
    desc->stencil.ref = GPU_STENCIL_LIVE | GPU_STENCIL_HIT;
    desc->stencil.read_mask = GPU_STENCIL_LIVE;
    desc->stencil.write_mask = GPU_STENCIL_HIT;
    desc->stencil.pass = MACS_STENCIL_OP_REPLACE;
}

/* Assembles the shader and makes the pass (with trial, *out may stay NULL: bgi_gpu_pass_try). */
static bg_status create_pass(bg_renderer *r, const bg_scene_state *state, hit_pass_parts *hp, bool trial,
                             macs_pass **out, bool *rejected)
{
    bool need_tangent = r->multipass->features.slot[GPU_SLOT_TANGENT];
    gpu_text main, functions;
    bgi_gpu_text_init(&main, &r->allocator);
    bgi_gpu_text_init(&functions, &r->allocator);
    emit_nearest_root(r, state, hp, &main);
    emit_winner_surface(r, state, hp, &main);
    bool have = hit_functions(&functions, r, state, hp->members, hp->count, need_tangent);

    macs_pass_desc desc;
    bgi_gpu_pass_desc_init(&desc, main.s, hp->inputs, hp->input_tex, hp->input_count, hp->uniforms, hp->uniform_count,
                       hp->outputs, hp->output_tex, hp->output_count);
    set_depth_stencil(r, &desc);
    return bgi_gpu_pass_from_texts(r, "intersection pass", &main, &functions, have, &desc, trial, out, rejected);
}

/* Sets every member's constants into the made pass. */
static bg_status set_members_uniforms(bg_renderer *r, macs_pass *pass, const bg_scene_state *state,
                                      const hit_pass_parts *hp)
{
    macs_status ms = MACS_OK;
    if (hp->meshes > 0)
        ms = macs_pass_set_uniform(pass, "bg_mesh_dims", r->meshes.dims);
    for (int j = 0; j < hp->count && !ms; j++) {
        ms = set_object_uniforms(pass, state, &r->meshes, &hp->members[j]);
        if (!ms)
            ms = set_material_uniforms(pass, state, &hp->members[j]);
    }
    return ms ? bgi_gpu_fail_macs(r, ms, "intersection pass uniforms") : BG_OK;
}

bg_status bgi_gpu_hit_pass_build(bg_renderer *r, const bg_scene_state *state, uint32_t first, int count, bool trial,
                             macs_pass **out, bool *rejected)
{
    *out = NULL;
    if (rejected)
        *rejected = false;
    if (count < 1 || count > GPU_BATCH_MAX)
        return bgi_gpu_fail(r, BG_ERR_LIMIT, "intersection batch of %d objects", count);
    hit_pass_parts hp;
    hp.members = bgi_alloc(&r->allocator, (size_t)count * sizeof *hp.members);
    if (!hp.members)
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory building an intersection pass");
    hp.count = count;
    describe_members(r, state, first, &hp);
    add_inputs(r, state, &hp);
    add_uniforms(&hp);
    add_outputs(r, &hp);
    bg_status st = create_pass(r, state, &hp, trial, out, rejected);
    if (st == BG_OK && *out)
        st = set_members_uniforms(r, *out, state, &hp);
    bgi_free(&r->allocator, hp.members);
    return st;
}

bg_status bgi_gpu_hit_pass_set_dmax(bg_renderer *r, macs_pass *pass, double dmax)
{
    float v = (float)dmax;
    macs_status ms = macs_pass_set_uniform(pass, "bg_dmax", &v);
    return ms ? bgi_gpu_fail_macs(r, ms, "intersection pass dmax") : BG_OK;
}
