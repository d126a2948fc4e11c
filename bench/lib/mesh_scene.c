/* The mesh benchmarks' scene (mesh_scene.h). */
#include "mesh_scene.h"

bg_status bench_mesh_scene(bg_scene *scene, const mesh *m, const bg_camera *camera)
{
    uint32_t mat = 0, obj = 0, light = 0;
    bg_material material = bg_material_init();
    bg_status st = bg_scene_add_material(scene, &material, &mat);
    bg_mesh_desc d = bg_mesh_desc_init(mat);
    d.positions = m->positions;
    d.vertex_count = m->vertex_count;
    d.indices = m->indices;
    d.triangle_count = m->triangle_count;
    if (st == BG_OK)
        st = bg_scene_add_mesh(scene, &d, &obj);
    bg_light l = bg_light_init();
    l.position = bg_vec3_make(1.5, 2.0, 1.0);
    l.intensity = 0.7;
    if (st == BG_OK)
        st = bg_scene_add_light(scene, &l, &light);
    l.position = bg_vec3_make(-2.0, 1.5, 0.5);
    l.intensity = 0.5;
    if (st == BG_OK)
        st = bg_scene_add_light(scene, &l, &light);
    if (st == BG_OK)
        st = bg_scene_set_camera(scene, camera);
    return st;
}
