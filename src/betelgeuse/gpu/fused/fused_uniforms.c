/* The fused shader's uniforms, from one list (GPU_FUSED_UNIFORMS in fused.h and GPU_PARAMS in
 * shared/shared.h): their declarations, the uniform budget they take, their values per render, and
 * the names the generated source uses. A new uniform is one new row there and, for a row of
 * GPU_FUSED_UNIFORMS, one value function here.
 *
 * Every position is camera-relative (origin.c): the eye is the origin of the GPU's frame. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "../../common/alloc.h"
#include "fused.h"

/* Names are short ("bg_m12_transparency"): this is room for any index. */
#define NAME_SIZE 40

typedef void (*value_fn)(const gpu_fused_values *v, uint32_t i, float *out);

typedef struct row {
    gpu_fused_scope scope;
    const char *name;
    macs_uniform_type type;
    gpu_fused_need need;
    value_fn value; /* NULL for a material parameter: param_value */
    int param;      /* the gpu_param of a parameter row, else -1 */
} row;

/* ---- values ---- */

static void copy3(const double *d, float *out)
{
    for (int i = 0; i < 3; i++)
        out[i] = (float)d[i];
}

/* The full frame's: a window's pixels take the frame's camera rays (docs/shading.md 1.1). */
static void image_size(const gpu_fused_values *v, uint32_t i, float *out)
{
    (void)i;
    out[0] = (float)v->view->pixels.frame_width;
    out[1] = (float)v->view->pixels.frame_height;
}

static void pixel_shift(const gpu_fused_values *v, uint32_t i, float *out)
{
    (void)i;
    out[0] = v->view->shift[0];
    out[1] = v->view->shift[1];
}

static void pixel_at(const gpu_fused_values *v, uint32_t i, float *out)
{
    (void)i;
    bgi_gpu_pixel_at(v->view, out);
}

static void sample_of(const gpu_fused_values *v, uint32_t i, float *out)
{
    (void)i;
    bgi_gpu_sample_of(v->view, out);
}

static void sample_perm(const gpu_fused_values *v, uint32_t i, float *out)
{
    (void)i;
    bgi_gpu_sample_perm(v->view, out);
}

static void lens(const gpu_fused_values *v, uint32_t i, float *out)
{
    (void)i;
    bgi_gpu_lens(v->state, out);
}

static void env_info(const gpu_fused_values *v, uint32_t i, float *out)
{
    (void)i;
    bgi_gpu_env_info(v->state, out);
}

static void camera_forward(const gpu_fused_values *v, uint32_t i, float *out)
{
    (void)i;
    copy3(v->state->camera.forward, out);
}

static void camera_right(const gpu_fused_values *v, uint32_t i, float *out)
{
    (void)i;
    copy3(v->state->camera.right, out);
}

static void camera_up(const gpu_fused_values *v, uint32_t i, float *out)
{
    (void)i;
    copy3(v->state->camera.up, out);
}

static void camera_tan_half(const gpu_fused_values *v, uint32_t i, float *out)
{
    (void)i;
    bgi_gpu_camera_half(v->state, v->view, out);
}

static void background(const gpu_fused_values *v, uint32_t i, float *out)
{
    (void)i;
    copy3(v->settings->background, out);
}

/* (encode into bytes, sRGB): one program serves RGBA8 in either encoding and RGBA32F. */
static void output_encoding(const gpu_fused_values *v, uint32_t i, float *out)
{
    (void)i;
    out[0] = v->float_output ? 0.0f : 1.0f;
    out[1] = v->settings->encoding == BG_ENCODING_SRGB ? 1.0f : 0.0f;
}

static void min_weight(const gpu_fused_values *v, uint32_t i, float *out)
{
    (void)i;
    out[0] = (float)v->settings->min_weight;
}

static void tree_node_dims(const gpu_fused_values *v, uint32_t i, float *out)
{
    (void)i;
    memcpy(out, v->tree->nodes, sizeof v->tree->nodes);
}

static void tree_object_dims(const gpu_fused_values *v, uint32_t i, float *out)
{
    (void)i;
    memcpy(out, v->tree->objects, sizeof v->tree->objects);
}

static void tree_mesh_dims(const gpu_fused_values *v, uint32_t i, float *out)
{
    (void)i;
    memcpy(out, v->meshes->dims, sizeof v->meshes->dims);
}

static void tree_node_count(const gpu_fused_values *v, uint32_t i, float *out)
{
    (void)i;
    out[0] = v->tree->node_count;
}

/* Field `offset` of gpu_packed_light, n floats, for every light one after another: the array
 * uniforms of the light rows. */
static void light_rows(const gpu_fused_values *v, size_t offset, size_t n, float *out)
{
    for (uint32_t k = 0; k < v->state->light_count; k++) {
        gpu_packed_light p = bgi_gpu_light_pack(v->state, k);
        memcpy(out + n * k, (const char *)&p + offset, n * sizeof(float));
    }
}

/* The value functions of the light rows, one field each. */
#define LIGHT_ROW_(fn, field, n)                                            \
    static void fn(const gpu_fused_values *v, uint32_t i, float *out)       \
    {                                                                       \
        (void)i;                                                            \
        light_rows(v, offsetof(gpu_packed_light, field), n, out);           \
    }
LIGHT_ROW_(light_position, pos, 4)
LIGHT_ROW_(light_radiance, rad, 3)
LIGHT_ROW_(light_attenuation, att, 3)
LIGHT_ROW_(light_spot, spot, 4)
LIGHT_ROW_(light_exponent, exponent, 1)
LIGHT_ROW_(light_edge_u, edge_u, 4)
LIGHT_ROW_(light_edge_v, edge_v, 4)
#undef LIGHT_ROW_

/* The path integrator's area light (docs/shading.md 13.1): its radiance Le = pi col I / A for a
 * rectangle, col I / R^2 for a sphere, computed in double; w 1 where the light is visible (its object
 * may be met by chance, so the two ways of meeting it are weighted by the power heuristic), else 0.
 * A Dirac light is (0, 0, 0, 0): it keeps Whitted's packing. */
static void light_path(const gpu_fused_values *v, uint32_t i, float *out)
{
    (void)i;
    const bg_scene_state *state = v->state;
    for (uint32_t k = 0; k < state->light_count; k++) {
        const bg_light *l = &state->lights[k];
        double scale = 0.0;
        if (l->type == BG_LIGHT_RECTANGLE) {
            const bg_vec3 *u = &l->edge_u, *e = &l->edge_v;
            double c[3] = {u->y * e->z - u->z * e->y, u->z * e->x - u->x * e->z, u->x * e->y - u->y * e->x};
            double area = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
            scale = area > 0.0 ? 3.14159265358979323846 / area : 0.0;
        } else if (l->type == BG_LIGHT_SPHERE && l->radius > 0.0) {
            scale = 1.0 / (l->radius * l->radius);
        }
        bool visible = false;
        for (uint32_t j = 0; j < state->object_count; j++)
            visible |= state->objects[j].light == k + 1;
        for (int c = 0; c < 3; c++)
            out[4 * k + c] = (float)(l->color[c] * l->intensity * scale);
        out[4 * k + 3] = visible && scale > 0.0 ? 1.0f : 0.0f;
    }
}

/* GL takes matrices column by column; the scene's are row-major. */
static void column_major3(const double *m, float *out)
{
    for (int c = 0; c < 3; c++)
        for (int r = 0; r < 3; r++)
            out[c * 3 + r] = (float)m[r * 3 + c];
}

static void object_id(const gpu_fused_values *v, uint32_t i, float *out)
{
    (void)v;
    out[0] = (float)i;
}

static void object_to_object(const gpu_fused_values *v, uint32_t i, float *out)
{
    bgi_gpu_origin_to_object(v->state, i, out);
}

static void object_normal(const gpu_fused_values *v, uint32_t i, float *out)
{
    column_major3(&v->state->objects[i].normal_to_world[0][0], out);
}

static void object_to_world3(const gpu_fused_values *v, uint32_t i, float *out)
{
    const double(*w)[4] = v->state->objects[i].to_world;
    double l3[3][3];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            l3[r][c] = w[r][c];
    column_major3(&l3[0][0], out);
}

static void object_uv_scale(const gpu_fused_values *v, uint32_t i, float *out)
{
    out[0] = (float)v->state->objects[i].uv_scale[0];
    out[1] = (float)v->state->objects[i].uv_scale[1];
}

static void object_mesh_base(const gpu_fused_values *v, uint32_t i, float *out)
{
    out[0] = v->meshes->base[2 * (size_t)i];
    out[1] = v->meshes->base[2 * (size_t)i + 1];
}

static void material_ior(const gpu_fused_values *v, uint32_t i, float *out)
{
    out[0] = (float)v->state->materials[i].ior;
}

/* A parameter's constant; the scene's ambient light folds into the material's ambient colour. */
static void param_value(const gpu_fused_values *v, int param, uint32_t k, float *out)
{
    bgi_gpu_param_value(v->state, &v->state->materials[k], (gpu_param)param, out);
}

/* ---- the list ---- */

static const row rows[GPU_FUSED_ROW_COUNT] = {
#define FIXED_ROW_(id, scope, name, type, need, value) \
    {GPU_FUSED_##scope, name, MACS_UNIFORM_##type, GPU_FUSED_NEED_##need, value, -1},
    GPU_FUSED_UNIFORMS(FIXED_ROW_)
#undef FIXED_ROW_
#define PARAM_ROW_(id, local, color, unit, need) \
    {GPU_FUSED_MATERIAL, "bg_m%u_" local, color ? MACS_UNIFORM_VEC3 : MACS_UNIFORM_FLOAT, GPU_FUSED_NEED_##need, NULL, \
     GPU_P_##id},
    GPU_PARAMS(PARAM_ROW_)
#undef PARAM_ROW_
};

/* How many objects or materials a row is repeated for (1 for frame and light rows): an object row
 * for the unrolled objects only, so that a frame of the tree variant never visits its tree's
 * thousands of objects here. */
static uint32_t repeats(const gpu_fused_layout *l, const row *w)
{
    return w->scope == GPU_FUSED_OBJECT ? l->unrolled_count : w->scope == GPU_FUSED_MATERIAL ? l->material_count : 1;
}

/* The object or material of a row's k-th repeat. */
static uint32_t repeat_index(const gpu_fused_layout *l, const row *w, uint32_t k)
{
    return w->scope == GPU_FUSED_OBJECT ? l->unrolled[k] : k;
}

/* Array length of a row's uniform: the light rows hold one element per light; 0 = not an array. */
static int array_count(const gpu_fused_layout *l, const row *w)
{
    return w->scope == GPU_FUSED_LIGHTS ? (int)l->light_count : 0;
}

void bgi_gpu_fused_uniform_name(const gpu_fused_layout *l, int r, uint32_t i, char *name, size_t size)
{
    if (rows[r].scope == GPU_FUSED_OBJECT)
        snprintf(name, size, rows[r].name, (unsigned)l->objects[i].slot);
    else if (rows[r].scope == GPU_FUSED_MATERIAL)
        snprintf(name, size, rows[r].name, (unsigned)i);
    else
        snprintf(name, size, "%s", rows[r].name);
}

bool bgi_gpu_fused_uniform_present(const gpu_fused_layout *l, int r, uint32_t i)
{
    const row *w = &rows[r];
    switch (w->scope) {
    case GPU_FUSED_FRAME:
        if (w->need == GPU_FUSED_NEED_MESH)
            return l->mesh;
        if (w->need == GPU_FUSED_NEED_SCRAMBLE)
            return bgi_gpu_fused_layout_samples(l);
        if (w->need == GPU_FUSED_NEED_ENV)
            return l->env;
        if (w->need == GPU_FUSED_NEED_LENS)
            return l->lens;
        return w->need == GPU_FUSED_NEED_BOUNCE ? l->max_depth > 0 : w->need == GPU_FUSED_NEED_TREE ? l->tree : true;
    case GPU_FUSED_LIGHTS:
        return l->light_count > 0 && (w->need != GPU_FUSED_NEED_AREA || l->area) && (w->need != GPU_FUSED_NEED_PATH || l->path);
    case GPU_FUSED_OBJECT:
        if (l->objects[i].in_tree)
            return false;
        /* A mesh's hit needs its linear part for the offset of the rays that leave it. */
        if (l->objects[i].shape == BGI_SHAPE_MESH && (w->need == GPU_FUSED_NEED_MESH || w->need == GPU_FUSED_NEED_TANGENT))
            return true;
        return w->need == GPU_FUSED_NEED_ALWAYS || (w->need == GPU_FUSED_NEED_TANGENT && bgi_gpu_fused_object_tangent(l, i)) ||
               (w->need == GPU_FUSED_NEED_UV && bgi_gpu_fused_object_uv(l, i));
    case GPU_FUSED_MATERIAL:
        return bgi_gpu_fused_material_has(&l->materials[i], w->need);
    }
    return false;
}

/* Calls fn for every uniform the layout has; stops at the first false. */
typedef bool (*visit_fn)(void *user, int r, uint32_t i);

static bool each_uniform(const gpu_fused_layout *l, visit_fn fn, void *user)
{
    for (int r = 0; r < GPU_FUSED_ROW_COUNT; r++)
        for (uint32_t k = 0; k < repeats(l, &rows[r]); k++) {
            uint32_t i = repeat_index(l, &rows[r], k);
            if (bgi_gpu_fused_uniform_present(l, r, i) && !fn(user, r, i))
                return false;
        }
    return true;
}

typedef struct budget {
    const gpu_fused_layout *l;
    int components;
} budget;

static bool add_components(void *user, int r, uint32_t i)
{
    (void)i;
    budget *b = user;
    int n = array_count(b->l, &rows[r]);
    b->components += bgi_gpu_uniform_type_components(rows[r].type) * (n > 0 ? n : 1);
    return true;
}

int bgi_gpu_fused_uniform_components(const gpu_fused_layout *l)
{
    budget b = {l, 0};
    each_uniform(l, add_components, &b);
    return b.components;
}

static bool count_one(void *user, int r, uint32_t i)
{
    (void)r;
    (void)i;
    (*(int *)user)++;
    return true;
}

typedef struct declaring {
    const gpu_fused_layout *l;
    macs_uniform_desc *desc;
    char *names;
    int n;
} declaring;

static bool declare_one(void *user, int r, uint32_t i)
{
    declaring *d = user;
    char *name = d->names + (size_t)d->n * NAME_SIZE;
    bgi_gpu_fused_uniform_name(d->l, r, i, name, NAME_SIZE);
    d->desc[d->n++] = (macs_uniform_desc){name, rows[r].type, array_count(d->l, &rows[r])};
    return true;
}

bool bgi_gpu_fused_uniforms_declare(const bg_allocator *a, const gpu_fused_layout *l, macs_uniform_desc **out, int *count,
                                char **names)
{
    int n = 0;
    each_uniform(l, count_one, &n);
    size_t slots = n ? (size_t)n : 1;
    declaring d = {l, bgi_alloc(a, slots * sizeof *d.desc), bgi_alloc(a, slots * NAME_SIZE), 0};
    if (!d.desc || !d.names) {
        bgi_gpu_fused_uniforms_free(a, d.desc, d.names);
        return false;
    }
    each_uniform(l, declare_one, &d);
    *out = d.desc;
    *count = d.n;
    *names = d.names;
    return true;
}

void bgi_gpu_fused_uniforms_free(const bg_allocator *a, macs_uniform_desc *desc, char *names)
{
    bgi_free(a, desc);
    bgi_free(a, names);
}

typedef struct setting {
    macs_pass *pass;
    const gpu_fused_layout *l;
    const gpu_fused_values *v;
    float *scratch; /* room for the largest value: every light's vec4 */
    macs_status ms;
} setting;

static bool set_one(void *user, int r, uint32_t i)
{
    setting *s = user;
    const row *w = &rows[r];
    if (w->value)
        w->value(s->v, i, s->scratch);
    else
        param_value(s->v, w->param, i, s->scratch);
    char name[NAME_SIZE];
    bgi_gpu_fused_uniform_name(s->l, r, i, name, sizeof name);
    s->ms = macs_pass_set_uniform(s->pass, name, s->scratch);
    return s->ms == MACS_OK;
}

bg_status bgi_gpu_fused_uniforms_set(bg_renderer *r, macs_pass *pass, const gpu_fused_layout *l, const gpu_fused_values *v)
{
    size_t n = 16 + 4 * (size_t)l->light_count;
    setting s = {pass, l, v, bgi_alloc(&r->allocator, n * sizeof(float)), MACS_OK};
    if (!s.scratch)
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory setting the fused pass's uniforms");
    memset(s.scratch, 0, n * sizeof(float));
    each_uniform(l, set_one, &s);
    bgi_free(&r->allocator, s.scratch);
    return s.ms ? bgi_gpu_fail_macs(r, s.ms, "fused pass uniforms") : BG_OK;
}
