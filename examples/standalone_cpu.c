/* standalone_cpu: a red sphere and a mirror sphere on a grey floor under two point lights, built with
 * the scene API, ray traced by the double-precision CPU reference renderer and written as a PNG.
 * Everything it needs is in this file, <betelgeuse.h> and libc, so it builds against an installed
 * library alone:
 *
 *     cc -std=c99 standalone_cpu.c $(pkg-config --cflags --libs betelgeuse) -o standalone_cpu
 *
 * Usage: standalone_cpu [out.png [size]]   (-h, --help: the usage)
 *   out.png     default standalone_cpu.png in the current folder
 *   size        image width and height in pixels, 1..16384, default 512
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <betelgeuse.h>

#define NAME "standalone_cpu"
enum { DEFAULT_SIZE = 512, MAX_SIZE = 16384 }; /* MAX_SIZE: bg_render_cpu's limit per side */

/* ---- 1. The command line ------------------------------------------------------------------- */

/* Reads "[out.png [size]]". Returns -1 to go on, else the exit status: 0 after --help, 2 after naming
 * an unknown option, a bad size or a third argument. */
static int parse_command_line(int argc, char **argv, const char **path, int *size)
{
    int positional = 0;
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        char *end = NULL;
        if (strcmp(arg, "-h") == 0 || strcmp(arg, "--help") == 0) {
            printf("usage: " NAME " [out.png [size]]\n"
                   "Ray traces a red sphere and a mirror sphere on a grey floor with the CPU reference renderer.\n"
                   "\n"
                   "  out.png     where to write the PNG (default " NAME ".png in the current folder)\n"
                   "  size        width and height in pixels, 1..%d (default %d)\n"
                   "  -h, --help  print this help and exit\n",
                   MAX_SIZE, DEFAULT_SIZE);
            return 0;
        }
        if (arg[0] == '-') {
            fprintf(stderr, NAME ": unknown option '%s' (try --help)\n", arg);
            return 2;
        }
        if (positional == 0) {
            *path = arg;
        } else if (positional == 1) {
            long v = strtol(arg, &end, 10);
            if (arg[0] < '0' || arg[0] > '9' || *end != '\0' || v < 1 || v > MAX_SIZE) {
                fprintf(stderr, NAME ": size '%s' is not an integer in 1..%d\n", arg, MAX_SIZE);
                return 2;
            }
            *size = (int)v;
        } else {
            fprintf(stderr, NAME ": too many arguments ('%s'): at most out.png and size (try --help)\n", arg);
            return 2;
        }
        positional++;
    }
    return -1;
}

/* ---- 2. The scene -------------------------------------------------------------------------- */

/* Adds a one-layer material: roughness 1 is Lambertian, 0 a perfect mirror. */
static bg_status add_material(bg_scene *scene, double r, double g, double b, double roughness, uint32_t *out)
{
    bg_material m = bg_material_init();
    m.base.reflectance.r = r;
    m.base.reflectance.g = g;
    m.base.reflectance.b = b;
    m.base.roughness.value = roughness;
    return bg_scene_add_material(scene, &m, out);
}

static bg_status add_point_light(bg_scene *scene, double x, double y, double z, double intensity)
{
    bg_light light = bg_light_init();
    light.position = bg_vec3_make(x, y, z);
    light.intensity = intensity;
    uint32_t id;
    return bg_scene_add_light(scene, &light, &id);
}

/* Materials first, then the objects and lights that use them, the camera, and a commit that
 * validates it all. The scene keeps the first failure's message, so the calls simply chain. */
static bg_status build_scene(bg_scene *scene)
{
    uint32_t grey, red, chrome, id;
    bg_status st = add_material(scene, 0.7, 0.7, 0.7, 1.0, &grey);
    if (st == BG_OK)
        st = add_material(scene, 0.8, 0.15, 0.1, 1.0, &red);
    if (st == BG_OK)
        st = add_material(scene, 0.9, 0.9, 0.9, 0.0, &chrome);
    if (st == BG_OK)
        st = bg_scene_add_plane(scene, bg_vec3_make(0, -1, 0), bg_vec3_make(0, 1, 0), grey, &id);
    if (st == BG_OK)
        st = bg_scene_add_sphere(scene, bg_vec3_make(-1.1, -0.3, 0.5), 0.7, red, &id);
    if (st == BG_OK)
        st = bg_scene_add_sphere(scene, bg_vec3_make(0.9, 0.0, -0.4), 1.0, chrome, &id);
    if (st == BG_OK)
        st = add_point_light(scene, 4, 6, 5, 0.8);
    if (st == BG_OK)
        st = add_point_light(scene, -5, 4, 2, 0.4);
    bg_camera camera = bg_camera_init();
    camera.position = bg_vec3_make(0, 1.5, 6);
    camera.look_at = bg_vec3_make(0, -0.2, 0);
    if (st == BG_OK)
        st = bg_scene_set_camera(scene, &camera);
    if (st == BG_OK)
        st = bg_scene_commit(scene);
    return st;
}

/* ---- 3. Render and save -------------------------------------------------------------------- */

int main(int argc, char **argv)
{
    const char *path = NAME ".png";
    int size = DEFAULT_SIZE;
    int exit_now = parse_command_line(argc, argv, &path, &size);
    if (exit_now >= 0)
        return exit_now;

    bg_scene *scene = NULL;
    bg_status st = bg_scene_create(NULL, &scene);
    if (st != BG_OK) {
        fprintf(stderr, NAME ": creating the scene: %s\n", bg_status_string(st));
        return 1;
    }
    st = build_scene(scene);
    if (st != BG_OK)
        fprintf(stderr, NAME ": building the scene: %s: %s\n", bg_status_string(st), bg_scene_error_message(scene));

    /* The image is ours: the library writes into it and never allocates it. */
    unsigned char *pixels = NULL;
    if (st == BG_OK) {
        pixels = malloc((size_t)size * (size_t)size * 4);
        if (!pixels) {
            fprintf(stderr, NAME ": out of memory for a %dx%d image\n", size, size);
            st = BG_ERR_OUT_OF_MEMORY;
        }
    }
    bg_image image = {size, size, BG_PIXEL_RGBA8, 0, pixels};
    if (st == BG_OK) {
        bg_render_settings settings = bg_render_settings_init(); /* sRGB output, 5 bounce levels */
        st = bg_render_cpu(scene, &settings, &image);
        if (st != BG_OK)
            fprintf(stderr, NAME ": rendering: %s: %s\n", bg_status_string(st), bg_scene_error_message(scene));
    }
    if (st == BG_OK) {
        char message[512];
        st = bg_png_save(path, &image, message, sizeof message);
        if (st != BG_OK)
            fprintf(stderr, NAME ": writing %s: %s\n", path, message);
    }

    free(pixels);
    bg_scene_destroy(scene);
    if (st != BG_OK)
        return 1;
    printf(NAME ": wrote %s (%dx%d)\n", path, size, size);
    return 0;
}
