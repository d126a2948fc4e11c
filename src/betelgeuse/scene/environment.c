/* The environment (docs/shading.md 7.1): an equirectangular texture seen by rays that meet nothing
 * and, optionally, a distant light drawn in proportion to its texels' luminance times solid angle.
 * The tables are built when the environment is set, not at commit, so that a commit of moved
 * objects or edited values stays cheap. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "../common/alloc.h"
#include "scene_private.h"

#define PI 3.14159265358979323846

bg_environment bg_environment_init(void)
{
    bg_environment e;
    memset(&e, 0, sizeof e);
    e.texture = 0;
    e.intensity = 1.0;
    e.lights = false;
    e.sampling = BG_ENVIRONMENT_IMPORTANCE;
    return e;
}

static void tables_free(bg_scene *scene, bgi_environment_tables *t)
{
    if (!t)
        return;
    bgi_free(&scene->allocator, t->marginal);
    bgi_free(&scene->allocator, t->conditional);
    bgi_free(&scene->allocator, t);
}

/* The cumulative tables of a texture's weights; NULL tables inside when the image is black. */
static bg_status tables_build(bg_scene *scene, uint32_t handle, const bg_texture_data *t, bgi_environment_tables **out)
{
    static const char where[] = "bg_scene_set_environment";
    int w = t->width, h = t->height;
    bgi_environment_tables *tb = bgi_alloc(&scene->allocator, sizeof *tb);
    double *marginal = bgi_alloc(&scene->allocator, (size_t)h * sizeof *marginal);
    double *conditional = bgi_alloc(&scene->allocator, (size_t)w * (size_t)h * sizeof *conditional);
    if (!tb || !marginal || !conditional) {
        bgi_free(&scene->allocator, tb);
        bgi_free(&scene->allocator, marginal);
        bgi_free(&scene->allocator, conditional);
        return bgi_scene_fail(scene, BG_ERR_OUT_OF_MEMORY, "%s: out of memory for the importance tables of a %d x %d "
                              "texture", where, w, h);
    }
    double total = 0.0;
    for (int j = 0; j < h; j++) {
        /* Row j (v = (j + 1/2) / h) spans the polar angle theta = pi (1 - v); its texels' solid
         * angles go as sin(theta). */
        double sin_t = sin(PI * (j + 0.5) / h), row = 0.0;
        for (int i = 0; i < w; i++) {
            double px[4];
            bgi_texture_texel(t, (size_t)j * (size_t)w + (size_t)i, px);
            row += (0.2126 * px[0] + 0.7152 * px[1] + 0.0722 * px[2]) * sin_t;
            conditional[(size_t)j * (size_t)w + (size_t)i] = row;
        }
        for (int i = 0; i < w; i++)
            conditional[(size_t)j * (size_t)w + (size_t)i] = row > 0.0 ? conditional[(size_t)j * (size_t)w + (size_t)i] / row : 0.0;
        if (row > 0.0)
            conditional[(size_t)j * (size_t)w + (size_t)(w - 1)] = 1.0;
        total += row;
        marginal[j] = total;
    }
    tb->texture = handle;
    tb->id = bgi_scene_next_serial();
    if (!(total > 0.0) || !isfinite(total)) {
        /* A black image (or one whose sum overflows): uniform sampling. */
        bgi_free(&scene->allocator, marginal);
        bgi_free(&scene->allocator, conditional);
        tb->marginal = tb->conditional = NULL;
    } else {
        for (int j = 0; j < h; j++)
            marginal[j] /= total;
        marginal[h - 1] = 1.0;
        tb->marginal = marginal;
        tb->conditional = conditional;
    }
    *out = tb;
    return BG_OK;
}

bg_status bg_scene_set_environment(bg_scene *scene, const bg_environment *environment)
{
    static const char where[] = "bg_scene_set_environment";
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    if (!environment)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: environment is NULL", where);
    const bg_environment *e = environment;
    if (!isfinite(e->intensity) || e->intensity < 0.0)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: intensity = %g must be finite and >= 0", where,
                              e->intensity);
    if ((int)e->sampling < 0 || e->sampling >= BG_ENVIRONMENT_SAMPLING_COUNT_)
        return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: sampling = %d is not a bg_environment_sampling",
                              where, (int)e->sampling);
    bgi_environment_tables *tables = scene->env_pending;
    if (e->texture != 0) {
        uint32_t slot;
        bg_status st = bgi_pool_lookup(scene, &scene->textures, where, "texture", e->texture, &slot);
        if (st != BG_OK)
            return st;
        if (!tables || tables->texture != e->texture) {
            st = tables_build(scene, e->texture, bgi_pool_item(&scene->textures, slot), &tables);
            if (st != BG_OK)
                return st;
        }
    } else {
        tables = NULL;
    }
    if (scene->env_pending != tables && scene->env_pending != scene->env_committed)
        tables_free(scene, scene->env_pending);
    scene->env_pending = tables;
    scene->environment = *e;
    return BG_OK;
}

bool bgi_environment_uses(const bg_scene *scene, uint32_t texture)
{
    return scene->environment.texture != 0 && scene->environment.texture == texture;
}

void bgi_environment_commit(bg_scene *scene, const uint32_t *texture_map, bg_environment_data *out)
{
    const bg_environment *e = &scene->environment;
    if (scene->env_committed != scene->env_pending) {
        tables_free(scene, scene->env_committed);
        scene->env_committed = scene->env_pending;
    }
    memset(out, 0, sizeof *out);
    out->on = e->texture != 0;
    if (!out->on)
        return;
    out->texture = texture_map[bgi_handle_slot(e->texture)] + 1;
    out->intensity = e->intensity;
    out->lights = e->lights;
    out->sampling = e->sampling;
    const bgi_environment_tables *t = scene->env_committed;
    bool importance = e->sampling == BG_ENVIRONMENT_IMPORTANCE && t->marginal;
    out->marginal = importance ? t->marginal : NULL;
    out->conditional = importance ? t->conditional : NULL;
    out->tables_id = t->id;
}

void bgi_environment_release(bg_scene *scene)
{
    if (scene->env_pending != scene->env_committed)
        tables_free(scene, scene->env_pending);
    tables_free(scene, scene->env_committed);
    scene->env_pending = scene->env_committed = NULL;
}
