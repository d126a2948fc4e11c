/* The bunny examples' scene (bunny_scene.h). */
#include "bunny_scene.h"

#include <stdio.h>
#include <stdlib.h>

#include "ply_mesh.h"

const char *bunny_scene_path(void)
{
    const char *path = getenv("BG_BUNNY");
    return path && *path ? path : "tests/data/bunny.ply";
}

/* The scan has no normals: smooth ones are the area-weighted sums of the faces around each vertex
 * (the cross product of two edges is twice the face's area along its normal). NULL without memory,
 * and the mesh is then shaded with its face normals. */
static float *vertex_normals(const mesh *m)
{
    float *n = calloc((size_t)m->vertex_count * 3, sizeof *n);
    if (!n)
        return NULL;
    for (uint32_t t = 0; t < m->triangle_count; t++) {
        const uint32_t *i = &m->indices[3 * t];
        const float *a = &m->positions[3 * i[0]], *b = &m->positions[3 * i[1]], *c = &m->positions[3 * i[2]];
        double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double f[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < 3; j++)
                n[3 * i[k] + j] += (float)f[j];
    }
    return n; /* the renderer normalises interpolated normals itself */
}

/* The bunny (y up, sitting on y = 0, about 10 units tall) in a clay material on a white floor. */
static bg_status build(bg_scene *scene, const mesh *bunny, const float *normals)
{
    uint32_t clay = 0, white = 0, id = 0;
    bg_material m = bg_material_init();
    m.base.reflectance = (bg_color_param){0.75, 0.45, 0.32, 0};
    bg_status st = bg_scene_add_material(scene, &m, &clay);
    bg_material floor = bg_material_init();
    if (st == BG_OK)
        st = bg_scene_add_material(scene, &floor, &white);

    bg_mesh_desc d = bg_mesh_desc_init(clay);
    d.positions = bunny->positions;
    d.vertex_count = bunny->vertex_count;
    d.indices = bunny->indices;
    d.triangle_count = bunny->triangle_count;
    d.normals = normals;
    if (st == BG_OK)
        st = bg_scene_add_mesh(scene, &d, &id);
    if (st == BG_OK)
        st = bg_scene_add_plane(scene, bg_vec3_make(0, 0, 0), bg_vec3_make(0, 1, 0), white, &id);

    bg_light l = bg_light_init();
    l.position = bg_vec3_make(12, 20, 16);
    l.intensity = 0.8;
    if (st == BG_OK)
        st = bg_scene_add_light(scene, &l, &id);
    l.position = bg_vec3_make(-16, 10, 8);
    l.intensity = 0.35;
    if (st == BG_OK)
        st = bg_scene_add_light(scene, &l, &id);

    bg_camera cam = bg_camera_init();
    cam.position = bg_vec3_make(4, 8, 24);
    cam.look_at = bg_vec3_make(0, 4.2, 0);
    cam.fov_y_degrees = 35;
    if (st == BG_OK)
        st = bg_scene_set_camera(scene, &cam);
    if (st == BG_OK)
        st = bg_scene_commit(scene);
    return st;
}

bg_status bunny_scene_build(bg_scene *scene, const char *name)
{
    mesh bunny = {0};
    char why[512];
    bg_status st = ply_mesh_read(bunny_scene_path(), &bunny, why, sizeof why);
    if (st != BG_OK) {
        fprintf(stderr, "%s: %s (set BG_BUNNY to the file, or run from the source tree's root)\n", name, why);
        return st;
    }
    float *normals = vertex_normals(&bunny);
    st = build(scene, &bunny, normals);
    free(normals);
    mesh_free(&bunny); /* the scene keeps its own copy of everything */
    return st;
}
