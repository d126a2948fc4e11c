/* "objects": an array, each element one shape key ({"sphere": {...}}, "plane", "box", "cylinder",
 * "rectangle", "mesh") beside the optional "transform", "material", "uv" and "casts_shadows".
 * A shape's own keys (a sphere's centre and radius, a plane's point and normal) place its
 * prototype as bg_scene_add_sphere and bg_scene_add_plane do; the transform then applies to that. */
#include "scenefile_internal.h"

#include <string.h>

static const char *const shape_keys[] = {"sphere", "plane", "box", "cylinder", "rectangle", "mesh", NULL};

/* The placement a shape's own keys give; false when it has none (the prototype as it is). */
static bg_status shape_local(bgi_sf_ctx *ctx, bg_shape shape, const cJSON *v, bg_mat4 *local, bool *has_local)
{
    static const char *const sphere_keys[] = {"center", "radius", NULL};
    static const char *const plane_keys[] = {"point", "normal", NULL};
    static const char *const no_keys[] = {NULL};
    *has_local = false;
    if (shape == BG_SHAPE_SPHERE) {
        BGI_SF_TRY(bgi_sf_check_object(ctx, v, sphere_keys));
        bg_vec3 c = bg_vec3_make(0, 0, 0);
        double r = 1.0;
        BGI_SF_TRY(bgi_sf_field_vec3(ctx, v, "center", &c));
        BGI_SF_TRY(bgi_sf_field_number(ctx, v, "radius", bgi_sf_positive, &r));
        if (v->child) {
            *local = bg_mat4_mul(bg_mat4_translate(c.x, c.y, c.z), bg_mat4_scale(r, r, r));
            *has_local = true;
        }
        return BG_OK;
    }
    if (shape == BG_SHAPE_PLANE) {
        BGI_SF_TRY(bgi_sf_check_object(ctx, v, plane_keys));
        bg_vec3 p = bg_vec3_make(0, 0, 0), n = bg_vec3_make(0, 1, 0);
        BGI_SF_TRY(bgi_sf_field_vec3(ctx, v, "point", &p));
        BGI_SF_TRY(bgi_sf_field_vec3(ctx, v, "normal", &n));
        if (n.x == 0 && n.y == 0 && n.z == 0) {
            size_t at = bgi_sf_push_key(ctx, "normal");
            bg_status st = bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must not be zero");
            bgi_sf_pop(ctx, at);
            return st;
        }
        if (v->child) {
            *local = bg_mat4_mul(bg_mat4_translate(p.x, p.y, p.z), bgi_sf_plane_frame(bgi_sf_normalize(n)));
            *has_local = true;
        }
        return BG_OK;
    }
    return bgi_sf_check_object(ctx, v, no_keys);
}

static bg_status read_uv(bgi_sf_ctx *ctx, const cJSON *v, bg_object_desc *d)
{
    static const char *const keys[] = {"mapping", "scale", NULL};
    static const char *const mappings[] = {"default", "spherical", "planar", "box", "cylindrical", NULL};
    BGI_SF_TRY(bgi_sf_check_object(ctx, v, keys));
    int mapping = (int)d->uv_mapping;
    BGI_SF_TRY(bgi_sf_field_enum(ctx, v, "mapping", mappings, &mapping));
    d->uv_mapping = (bg_uv_mapping)mapping;
    const cJSON *s = bgi_sf_member(v, "scale");
    if (!s)
        return BG_OK;
    size_t at = bgi_sf_push_key(ctx, "scale");
    bg_status st;
    if (cJSON_IsNumber(s)) {
        st = bgi_sf_number(ctx, s, bgi_sf_positive, &d->uv_scale[0]);
        d->uv_scale[1] = d->uv_scale[0];
    } else {
        st = bgi_sf_numbers(ctx, s, 2, bgi_sf_positive, d->uv_scale);
    }
    bgi_sf_pop(ctx, at);
    return st;
}

static bg_status material_ref(bgi_sf_ctx *ctx, const cJSON *v, uint32_t *out)
{
    size_t at = bgi_sf_push_key(ctx, "material");
    const char *name = NULL;
    bg_status st = bgi_sf_string(ctx, v, &name);
    if (st == BG_OK && !(*out = bgi_sf_names_find(&ctx->materials, name)))
        st = bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "no material is named \"%s\" in \"materials\"", name);
    bgi_sf_pop(ctx, at);
    return st;
}

static bg_status read_mesh(bgi_sf_ctx *ctx, const cJSON *v, bgi_sf_model_desc *m)
{
    static const char *const keys[] = {"file", "normals", NULL};
    static const char *const normals[] = {"file", "smooth", "flat", NULL};
    BGI_SF_TRY(bgi_sf_check_object(ctx, v, keys));
    const cJSON *f = bgi_sf_member(v, "file");
    if (!f)
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "\"file\" is required");
    int n = BGI_SF_NORMALS_FILE;
    BGI_SF_TRY(bgi_sf_field_enum(ctx, v, "normals", normals, &n));
    m->normals = (bgi_sf_normals)n;
    size_t at = bgi_sf_push_key(ctx, "file");
    const char *file = NULL;
    bg_status st = bgi_sf_string(ctx, f, &file);
    bgi_sf_pop(ctx, at);
    BGI_SF_TRY(st);
    m->path = file;
    return BG_OK;
}

static bg_status read_object(bgi_sf_ctx *ctx, const cJSON *v)
{
    static const char *const keys[] = {"sphere", "plane", "box", "cylinder", "rectangle", "mesh",
                                       "transform", "material", "uv", "casts_shadows", NULL};
    BGI_SF_TRY(bgi_sf_check_object(ctx, v, keys));
    int shape = -1;
    const cJSON *sv = NULL;
    for (int i = 0; shape_keys[i]; i++) {
        const cJSON *c = bgi_sf_member(v, shape_keys[i]);
        if (!c)
            continue;
        if (sv)
            return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "has two shapes, \"%s\" and \"%s\" (one per object)",
                               shape_keys[shape], shape_keys[i]);
        sv = c;
        shape = i;
    }
    if (!sv)
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT,
                           "has no shape (one of \"sphere\", \"plane\", \"box\", \"cylinder\", \"rectangle\", \"mesh\")");
    bool is_mesh = strcmp(shape_keys[shape], "mesh") == 0;

    bg_mat4 transform = bg_mat4_identity(), local = bg_mat4_identity();
    bool has_transform = false, has_local = false;
    const cJSON *t = bgi_sf_member(v, "transform");
    if (t) {
        size_t at = bgi_sf_push_key(ctx, "transform");
        bg_status st = bgi_sf_read_transform(ctx, t, &transform);
        bgi_sf_pop(ctx, at);
        BGI_SF_TRY(st);
        has_transform = true;
    }
    uint32_t material = 0;
    const cJSON *mv = bgi_sf_member(v, "material");
    if (mv)
        BGI_SF_TRY(material_ref(ctx, mv, &material));
    bool casts_shadows = true;
    BGI_SF_TRY(bgi_sf_field_bool(ctx, v, "casts_shadows", &casts_shadows));

    if (is_mesh) {
        if (bgi_sf_member(v, "uv")) {
            size_t at = bgi_sf_push_key(ctx, "uv");
            bg_status st = bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT,
                                       "applies to analytic shapes only (a mesh has the file's texture coordinates)");
            bgi_sf_pop(ctx, at);
            return st;
        }
        bgi_sf_model_desc m;
        memset(&m, 0, sizeof m);
        size_t at = bgi_sf_push_key(ctx, "mesh");
        bg_status st = read_mesh(ctx, sv, &m);
        char path[BGI_SF_PATH_MAX];
        if (st == BG_OK) {
            size_t at_file = bgi_sf_push_key(ctx, "file");
            st = bgi_sf_resolve(ctx, m.path, path);
            m.path = path;
            m.transform = transform;
            m.material = material;
            m.casts_shadows = casts_shadows;
            if (st == BG_OK)
                st = bgi_sf_load_model(ctx, &m);
            bgi_sf_pop(ctx, at_file);
        }
        bgi_sf_pop(ctx, at);
        return st;
    }

    size_t at = bgi_sf_push_key(ctx, shape_keys[shape]);
    bg_status st = shape_local(ctx, (bg_shape)shape, sv, &local, &has_local);
    bgi_sf_pop(ctx, at);
    BGI_SF_TRY(st);
    if (!material)
        BGI_SF_TRY(bgi_sf_default_material(ctx, &material));
    bg_object_desc d = bg_object_desc_init((bg_shape)shape, material);
    d.casts_shadows = casts_shadows;
    d.transform = has_transform && has_local ? bg_mat4_mul(transform, local) : has_local ? local : transform;
    const cJSON *uv = bgi_sf_member(v, "uv");
    if (uv) {
        size_t at_uv = bgi_sf_push_key(ctx, "uv");
        st = read_uv(ctx, uv, &d);
        bgi_sf_pop(ctx, at_uv);
        BGI_SF_TRY(st);
    }
    uint32_t id;
    st = bg_scene_add_object(ctx->scene, &d, &id);
    if (st != BG_OK)
        return bgi_sf_scene_fail(ctx, st, "the object");
    ctx->out->summary.objects++;
    bgi_sf_summary_shape(&ctx->out->summary, (bg_shape)shape, d.transform);
    return BG_OK;
}

bg_status bgi_sf_read_objects(bgi_sf_ctx *ctx, const cJSON *v)
{
    if (!cJSON_IsArray(v))
        return bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "must be an array of objects (got %s)", bgi_sf_type_name(v));
    size_t i = 0;
    for (const cJSON *o = v->child; o; o = o->next, i++) {
        size_t at = bgi_sf_push_index(ctx, i);
        bg_status st = read_object(ctx, o);
        bgi_sf_pop(ctx, at);
        BGI_SF_TRY(st);
    }
    return BG_OK;
}
