/* Which points of a mesh object's triangles are there for rays (docs/shading.md 2.11): a
 * single-sided material drops every point met from the back, a cut-out every point whose coverage is
 * below the cut-off. The filter applies inside the mesh walk, before a hit counts, so a dropped
 * point is simply not there: the walk goes on to what lies behind it, for camera, secondary and
 * shadow rays alike. */
#include "cpu_internal.h"

const bg_cpu_mesh_filter *bgi_cpu_mesh_filter_of(const bg_scene_state *state, const bg_object_data *object,
                                                 bg_cpu_mesh_filter *storage)
{
    const bg_material *m = &state->materials[object->material];
    if (m->sides != BG_SIDES_FRONT && m->coverage_cutoff <= 0.0)
        return NULL;
    storage->front_only = m->sides == BG_SIDES_FRONT;
    storage->cutoff = m->coverage_cutoff;
    storage->coverage = m->coverage.value;
    storage->texture = m->coverage.texture ? &state->textures[m->coverage.texture - 1] : NULL;
    storage->channel = m->coverage.channel;
    storage->uv_scale[0] = object->uv_scale[0];
    storage->uv_scale[1] = object->uv_scale[1];
    return storage;
}

bool bgi_cpu_mesh_filter_keeps(const bg_cpu_mesh_filter *filter, const bg_mesh_data *mesh, uint32_t triangle,
                               const double bary[3], bool front)
{
    if (filter->front_only && !front)
        return false;
    if (filter->cutoff <= 0.0)
        return true;
    double coverage = filter->coverage;
    if (filter->texture) {
        /* The texture coordinates as the hit's attributes compute them (mesh_hit.c); a mesh without
         * them reads the texel at (0, 0), as its shading does. */
        double uv[2] = {0.0, 0.0};
        if (mesh->uvs)
            for (int k = 0; k < 2; k++) {
                double u = 0.0;
                for (int c = 0; c < 3; c++)
                    u += bary[c] * mesh->uvs[2 * (size_t)mesh->indices[3 * (size_t)triangle + c] + k];
                uv[k] = u * filter->uv_scale[k];
            }
        double texel[4];
        bgi_cpu_texture_sample(filter->texture, uv[0], uv[1], texel);
        coverage *= texel[filter->channel];
    }
    return coverage >= filter->cutoff;
}
