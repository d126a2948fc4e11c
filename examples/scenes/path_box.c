/* Closed boxes for the path integrator (path_box.h). */
#include <math.h>

#include "path_box.h"

bg_status path_box_wall(bg_scene *s, bg_vec3 c, bg_vec3 u, bg_vec3 v, uint32_t mat)
{
    /* The prototype square [-1, 1]^2 of y = 0: x along u / 2, z along v / 2, y along the unit normal. */
    bg_vec3 n = bg_vec3_make(u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x);
    double len = sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    const double cols[3][3] = {{0.5 * u.x, 0.5 * u.y, 0.5 * u.z}, {n.x / len, n.y / len, n.z / len},
                               {0.5 * v.x, 0.5 * v.y, 0.5 * v.z}};
    const double centre[3] = {c.x + 0.5 * (u.x + v.x), c.y + 0.5 * (u.y + v.y), c.z + 0.5 * (u.z + v.z)};
    bg_object_desc o = bg_object_desc_init(BG_SHAPE_RECTANGLE, mat);
    o.transform = bg_mat4_identity();
    for (int r = 0; r < 3; r++) {
        for (int j = 0; j < 3; j++)
            o.transform.m[r][j] = cols[j][r];
        o.transform.m[r][3] = centre[r];
    }
    uint32_t id;
    return bg_scene_add_object(s, &o, &id);
}

bg_status path_box_walls(bg_scene *s, uint32_t left, uint32_t right, uint32_t rest)
{
    const double a = -1.05, b = 2.1;
    const struct {
        bg_vec3 c, u, v;
        uint32_t mat;
    } walls[6] = {
        {{-1, a, a}, {0, b, 0}, {0, 0, b}, left}, {{1, a, a}, {0, b, 0}, {0, 0, b}, right},
        {{a, -1, a}, {b, 0, 0}, {0, 0, b}, rest}, {{a, 1, a}, {b, 0, 0}, {0, 0, b}, rest},
        {{a, a, -1}, {b, 0, 0}, {0, b, 0}, rest}, {{a, a, 1}, {b, 0, 0}, {0, b, 0}, rest},
    };
    bg_status st = BG_OK;
    for (int k = 0; k < 6 && st == BG_OK; k++)
        st = path_box_wall(s, walls[k].c, walls[k].u, walls[k].v, walls[k].mat);
    return st;
}

static bg_status lambertian(bg_scene *s, double r, double g, double b, double e, uint32_t *id)
{
    bg_material m = bg_material_init();
    m.base.reflectance = (bg_color_param){r, g, b, 0};
    m.base.roughness.value = 1.0;
    m.emission = (bg_color_param){e, e, e, 0};
    return bg_scene_add_material(s, &m, id);
}

static bg_status camera_and_commit(bg_scene *s, bg_vec3 eye, bg_vec3 at, double fov)
{
    const double none[3] = {0, 0, 0};
    bg_camera c = bg_camera_init();
    c.position = eye;
    c.look_at = at;
    c.fov_y_degrees = fov;
    bg_status st = bg_scene_set_ambient(s, none);
    if (st == BG_OK)
        st = bg_scene_set_camera(s, &c);
    return st == BG_OK ? bg_scene_commit(s) : st;
}

bg_status path_box_cornell(bg_scene *s)
{
    uint32_t red, green, white, id;
    bg_status st = lambertian(s, 0.75, 0.1, 0.1, 0.0, &red);
    if (st == BG_OK)
        st = lambertian(s, 0.1, 0.7, 0.15, 0.0, &green);
    if (st == BG_OK)
        st = lambertian(s, 0.75, 0.75, 0.75, 0.0, &white);
    if (st == BG_OK)
        st = path_box_walls(s, red, green, white);
    bg_light l = bg_light_init();
    l.type = BG_LIGHT_RECTANGLE;
    l.visible = true;
    l.position = bg_vec3_make(-0.3, 0.98, -0.3);
    l.edge_u = bg_vec3_make(0.6, 0, 0);
    l.edge_v = bg_vec3_make(0, 0, 0.6); /* u x v = -y: it shines down */
    l.intensity = 0.5;
    if (st == BG_OK)
        st = bg_scene_add_light(s, &l, &id);
    if (st == BG_OK)
        st = bg_scene_add_sphere(s, bg_vec3_make(-0.4, -0.65, -0.3), 0.35, white, &id);
    return st == BG_OK ? camera_and_commit(s, bg_vec3_make(0, -0.1, 0.95), bg_vec3_make(0, 0.25, -1), 75.0) : st;
}

bg_status path_box_white(bg_scene *s, double e)
{
    uint32_t white;
    bg_status st = lambertian(s, 1.0, 1.0, 1.0, e, &white);
    if (st == BG_OK)
        st = path_box_walls(s, white, white, white);
    return st == BG_OK ? camera_and_commit(s, bg_vec3_make(0.2, -0.1, 0.6), bg_vec3_make(-0.3, 0.2, -1), 60.0) : st;
}
