/* Meshes: checking and copying a bg_mesh_desc into immutable shared geometry with its own tree,
 * mesh objects and instances over it, and the geometry's lifetime.
 *
 * Invariant: a bg_mesh_data is either shown by live pending objects (refs of them, each holding one
 * reference) or on the scene's retired list (refs 0), never both; a retired mesh may still be shown
 * by the committed state, which is why it is freed only after the next successful commit. The tree
 * is built at add, not at commit: the geometry never changes afterwards, so the one build belongs
 * to the call that brought the triangles, which also reports its failures (memory, limits), and
 * commit keeps its promise that an accepted object never makes it fail. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "../common/alloc.h"
#include "scene_private.h"

static const char where_add[] = "bg_scene_add_mesh";
static const char where_instance[] = "bg_scene_add_mesh_instance";

#define FAIL(status, ...) bgi_scene_fail(scene, status, __VA_ARGS__)

bg_mesh_desc bg_mesh_desc_init(uint32_t material)
{
    bg_mesh_desc d;
    memset(&d, 0, sizeof d);
    d.transform = bg_mat4_identity();
    d.material = material;
    d.casts_shadows = true;
    return d;
}

static void mesh_free(bg_scene *scene, bg_mesh_data *mesh)
{
    if (!mesh)
        return;
    bgi_bvh_destroy(&mesh->tree);
    bgi_free(&scene->allocator, mesh->positions);
    bgi_free(&scene->allocator, mesh->indices);
    bgi_free(&scene->allocator, mesh->normals);
    bgi_free(&scene->allocator, mesh->uvs);
    bgi_free(&scene->allocator, mesh);
}

void bgi_mesh_unref(bg_scene *scene, bg_mesh_data *mesh)
{
    if (!mesh || --mesh->refs > 0)
        return;
    mesh->next_retired = scene->retired_meshes;
    scene->retired_meshes = mesh;
}

void bgi_mesh_free_retired(bg_scene *scene)
{
    while (scene->retired_meshes) {
        bg_mesh_data *next = scene->retired_meshes->next_retired;
        mesh_free(scene, scene->retired_meshes);
        scene->retired_meshes = next;
    }
}

/* The counts: at least one triangle, byte sizes within size_t, within the tree's and the indices'
 * ranges. */
static bg_status check_counts(bg_scene *scene, const bg_mesh_desc *d)
{
    if (d->triangle_count == 0)
        return FAIL(BG_ERR_INVALID_ARGUMENT, "%s: desc.triangle_count is 0 (a mesh needs a triangle)", where_add);
    size_t bytes;
    if (!bgi_size_mul(d->triangle_count, 3 * sizeof(uint32_t), &bytes) ||
        !bgi_size_mul(d->triangle_count, sizeof(bg_bvh_box), &bytes))
        return FAIL(BG_ERR_LIMIT, "%s: desc.triangle_count = %zu overflows the size of its arrays", where_add,
                    d->triangle_count);
    if (d->triangle_count > BG_BVH_MAX_PRIMS)
        return FAIL(BG_ERR_LIMIT, "%s: desc.triangle_count = %zu exceeds the %u triangles a mesh's tree takes",
                    where_add, d->triangle_count, (unsigned)BG_BVH_MAX_PRIMS);
    if (!bgi_size_mul(d->vertex_count, 3 * sizeof(float), &bytes))
        return FAIL(BG_ERR_LIMIT, "%s: desc.vertex_count = %zu overflows the size of its arrays", where_add,
                    d->vertex_count);
    if (d->vertex_count > UINT32_MAX)
        return FAIL(BG_ERR_LIMIT, "%s: desc.vertex_count = %zu exceeds the %u vertices 32-bit indices reach",
                    where_add, d->vertex_count, (unsigned)UINT32_MAX);
    if (!d->positions)
        return FAIL(BG_ERR_INVALID_ARGUMENT, "%s: desc.positions is NULL (vertex_count = %zu)", where_add,
                    d->vertex_count);
    if (!d->indices)
        return FAIL(BG_ERR_INVALID_ARGUMENT, "%s: desc.indices is NULL (triangle_count = %zu)", where_add,
                    d->triangle_count);
    return BG_OK;
}

/* Every value finite: positions, and normals and uvs where given. */
static bg_status check_values(bg_scene *scene, const bg_mesh_desc *d)
{
    struct {
        const float *values;
        int per_vertex;
        const char *field;
    } arrays[] = {{d->positions, 3, "positions"}, {d->normals, 3, "normals"}, {d->uvs, 2, "uvs"}};
    for (int a = 0; a < 3; a++) {
        if (!arrays[a].values)
            continue;
        for (size_t v = 0; v < d->vertex_count; v++)
            for (int k = 0; k < arrays[a].per_vertex; k++)
                if (!isfinite(arrays[a].values[v * arrays[a].per_vertex + k]))
                    return FAIL(BG_ERR_INVALID_ARGUMENT, "%s: desc.%s of vertex %zu is not finite (component %d = %g)",
                                where_add, arrays[a].field, v, k, (double)arrays[a].values[v * arrays[a].per_vertex + k]);
    }
    return BG_OK;
}

/* Every index in range; writes the object-space box of the vertices the triangles use. */
static bg_status check_indices(bg_scene *scene, const bg_mesh_desc *d, double lo[3], double hi[3])
{
    for (int i = 0; i < 3; i++) {
        lo[i] = DBL_MAX;
        hi[i] = -DBL_MAX;
    }
    for (size_t t = 0; t < d->triangle_count; t++)
        for (int c = 0; c < 3; c++) {
            uint32_t index = d->indices[3 * t + c];
            if (index >= d->vertex_count)
                return FAIL(BG_ERR_INVALID_ARGUMENT,
                            "%s: desc.indices: triangle %zu corner %d has index %u, out of range (vertex_count = %zu)",
                            where_add, t, c, (unsigned)index, d->vertex_count);
            const float *p = &d->positions[3 * (size_t)index];
            for (int i = 0; i < 3; i++) {
                lo[i] = p[i] < lo[i] ? p[i] : lo[i];
                hi[i] = p[i] > hi[i] ? p[i] : hi[i];
            }
        }
    return BG_OK;
}

static void *copy_array(bg_scene *scene, const void *src, size_t count, size_t elem, bool *failed)
{
    if (!src || *failed)
        return NULL;
    void *dst = bgi_alloc(&scene->allocator, count * elem); /* products checked by check_counts */
    if (!dst)
        *failed = true;
    else
        memcpy(dst, src, count * elem);
    return dst;
}

/* The mesh's tree over its triangles' boxes; a float vertex is exact in double, so each box is its
 * triangle's exact box. */
static bg_status build_tree(bg_scene *scene, bg_mesh_data *m)
{
    bg_bvh_box *boxes = bgi_alloc(&scene->allocator, (size_t)m->triangle_count * sizeof *boxes);
    if (!boxes)
        return FAIL(BG_ERR_OUT_OF_MEMORY, "%s: out of memory for the boxes of %u triangles", where_add,
                    (unsigned)m->triangle_count);
    for (uint32_t t = 0; t < m->triangle_count; t++) {
        for (int i = 0; i < 3; i++) {
            boxes[t].min[i] = DBL_MAX;
            boxes[t].max[i] = -DBL_MAX;
        }
        for (int c = 0; c < 3; c++) {
            const float *p = &m->positions[3 * (size_t)m->indices[3 * (size_t)t + c]];
            for (int i = 0; i < 3; i++) {
                boxes[t].min[i] = p[i] < boxes[t].min[i] ? p[i] : boxes[t].min[i];
                boxes[t].max[i] = p[i] > boxes[t].max[i] ? p[i] : boxes[t].max[i];
            }
        }
    }
    bg_status st = bgi_bvh_build(&scene->allocator, boxes, m->triangle_count, &m->tree);
    bgi_free(&scene->allocator, boxes);
    if (st != BG_OK)
        return FAIL(st, "%s: building the tree of %u triangles failed (%s)", where_add, (unsigned)m->triangle_count,
                    bg_status_string(st));
    return BG_OK;
}

/* The pending item of a mesh object: an object description whose shape says mesh. */
static bg_object_item mesh_item(bg_mesh_data *mesh, const bg_mat4 *transform, uint32_t material, bool casts_shadows)
{
    bg_object_item item;
    item.desc = bg_object_desc_init(BG_SHAPE_SPHERE, material);
    item.desc.shape = BGI_SHAPE_MESH;
    item.desc.transform = *transform;
    item.desc.casts_shadows = casts_shadows;
    item.mesh = mesh;
    return item;
}

bg_status bg_scene_add_mesh(bg_scene *scene, const bg_mesh_desc *desc, uint32_t *out_object)
{
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    if (!desc)
        return FAIL(BG_ERR_INVALID_ARGUMENT, "%s: desc is NULL", where_add);
    if (!out_object)
        return FAIL(BG_ERR_INVALID_ARGUMENT, "%s: out_object is NULL", where_add);
    bg_status st = check_counts(scene, desc);
    if (st == BG_OK)
        st = check_values(scene, desc);
    bg_mesh_data probe;
    memset(&probe, 0, sizeof probe);
    if (st == BG_OK)
        st = check_indices(scene, desc, probe.box_min, probe.box_max);
    /* The transform and material, by the one derivation commit runs, on the mesh's box. */
    bg_object_item item = mesh_item(&probe, &desc->transform, desc->material, desc->casts_shadows);
    bg_object_data derived;
    if (st == BG_OK)
        st = bgi_object_derive(scene, where_add, "desc.transform", &item, &derived);
    if (st == BG_OK)
        st = bgi_pool_reserve(scene, &scene->objects, where_add);
    if (st != BG_OK)
        return st;

    bg_mesh_data *m = bgi_alloc(&scene->allocator, sizeof *m);
    if (!m)
        return FAIL(BG_ERR_OUT_OF_MEMORY, "%s: out of memory", where_add);
    *m = probe;
    m->vertex_count = (uint32_t)desc->vertex_count;
    m->triangle_count = (uint32_t)desc->triangle_count;
    bool failed = false;
    m->positions = copy_array(scene, desc->positions, desc->vertex_count, 3 * sizeof(float), &failed);
    m->indices = copy_array(scene, desc->indices, desc->triangle_count, 3 * sizeof(uint32_t), &failed);
    m->normals = copy_array(scene, desc->normals, desc->vertex_count, 3 * sizeof(float), &failed);
    m->uvs = copy_array(scene, desc->uvs, desc->vertex_count, 2 * sizeof(float), &failed);
    st = failed ? FAIL(BG_ERR_OUT_OF_MEMORY, "%s: out of memory copying %zu vertices and %zu triangles", where_add,
                       desc->vertex_count, desc->triangle_count)
                : build_tree(scene, m);
    if (st != BG_OK) {
        mesh_free(scene, m);
        return st;
    }
    m->refs = 1;
    m->serial = bgi_scene_next_serial();
    item.mesh = m;
    return bgi_pool_add(scene, &scene->objects, where_add, &item, out_object);
}

bg_status bg_scene_add_mesh_instance(bg_scene *scene, uint32_t mesh_object, const bg_mat4 *transform,
                                     uint32_t material, bool casts_shadows, uint32_t *out_object)
{
    if (!scene)
        return BG_ERR_INVALID_ARGUMENT;
    uint32_t slot;
    bg_status st = bgi_pool_lookup(scene, &scene->objects, where_instance, "mesh_object", mesh_object, &slot);
    if (st != BG_OK)
        return st;
    bg_mesh_data *mesh = ((bg_object_item *)bgi_pool_item(&scene->objects, slot))->mesh;
    char text[BG_HANDLE_TEXT_SIZE];
    if (!mesh)
        return FAIL(BG_ERR_INVALID_ARGUMENT,
                    "%s: mesh_object = %s is an analytic shape, not a mesh object (bg_scene_add_mesh)",
                    where_instance, bgi_handle_text(mesh_object, text));
    if (!transform)
        return FAIL(BG_ERR_INVALID_ARGUMENT, "%s: transform is NULL", where_instance);
    if (!out_object)
        return FAIL(BG_ERR_INVALID_ARGUMENT, "%s: out_object is NULL", where_instance);
    bg_object_item item = mesh_item(mesh, transform, material, casts_shadows);
    bg_object_data derived;
    st = bgi_object_derive(scene, where_instance, "transform", &item, &derived);
    if (st == BG_OK)
        st = bgi_pool_reserve(scene, &scene->objects, where_instance);
    if (st != BG_OK)
        return st;
    mesh->refs++;
    return bgi_pool_add(scene, &scene->objects, where_instance, &item, out_object);
}
