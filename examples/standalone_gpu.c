/* standalone_gpu: a mirror sphere and a turned blue box on a checkered floor, ray traced on the GPU
 * through a headless OpenGL 2.1 context and written as a PNG. Every call from the GL context to the
 * saved image is in this file; it needs only <betelgeuse.h> (which includes <macs.h>) and libc, so it
 * builds against an installed library alone:
 *
 *     cc -std=c99 standalone_gpu.c $(pkg-config --cflags --libs betelgeuse) -o standalone_gpu
 *
 * A program with its own GL context (GLFW, SDL, a toolkit) makes it current and passes its own
 * get_proc_address instead of the headless one.
 *
 * Usage: standalone_gpu [out.png [size]]   (-h, --help: the usage)
 *   out.png     default standalone_gpu.png in the current folder
 *   size        image width and height in pixels, 1..16384, default 512
 */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <betelgeuse.h>

#define NAME "standalone_gpu"
/* MAX_SIZE: the renderers' limit per side; a GL with a smaller texture size makes the render fail,
 * saying so. */
enum { DEFAULT_SIZE = 512, MAX_SIZE = 16384 };

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
                   "Ray traces a mirror sphere and a blue box on a checkered floor on the GPU (headless OpenGL).\n"
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

/* Everything the program creates; NULL until created. release() frees it in reverse order. */
typedef struct program {
    macs_headless *gl;
    macs_context *context;
    bg_renderer *renderer;
    bg_scene *scene;
    unsigned char *pixels;
} program;

static void release(program *p)
{
    free(p->pixels);
    bg_scene_destroy(p->scene);
    bg_renderer_destroy(p->renderer); /* before the MACS context that holds its GPU objects */
    macs_context_destroy(p->context);
    macs_headless_destroy(p->gl);
}

/* ---- 2. GL context, MACS context, renderer ------------------------------------------------- */

/* A headless GL context (the library's default order: an EGL device, EGL surfaceless, OSMesa), the
 * MACS context over it, and the renderer on that; false after printing why one failed. */
static bool create_gpu(program *p)
{
    char message[1024];
    macs_status ms = macs_headless_create(NULL, &p->gl, message, sizeof message);
    if (ms != MACS_OK) {
        fprintf(stderr, NAME ": headless OpenGL context: %s: %s\n", macs_status_string(ms), message);
        return false;
    }
    macs_context_desc cd = {0};
    cd.get_proc_address = macs_headless_get_proc_address(p->gl);
    cd.get_proc_address_user = macs_headless_proc_user(p->gl);
    ms = macs_context_create(&cd, &p->context, message, sizeof message);
    if (ms != MACS_OK) {
        fprintf(stderr, NAME ": MACS context: %s: %s\n", macs_status_string(ms), message);
        return false;
    }
    bg_renderer_desc rd = {0};
    rd.context = p->context;
    bg_status st = bg_renderer_create(&rd, &p->renderer, message, sizeof message);
    if (st != BG_OK) {
        fprintf(stderr, NAME ": renderer: %s: %s\n", bg_status_string(st), message);
        return false;
    }
    return true;
}

/* ---- 3. The scene -------------------------------------------------------------------------- */

/* A 64x64 checkerboard of 8-texel cells made in memory; the scene copies it, so it can live on the
 * stack. Nearest filtering keeps the cell edges sharp. */
static bg_status add_checker_texture(bg_scene *scene, uint32_t *out)
{
    enum { N = 64, CELL = 8 };
    unsigned char texels[N * N * 4];
    for (int y = 0; y < N; y++)
        for (int x = 0; x < N; x++) {
            unsigned char v = (x / CELL + y / CELL) % 2 ? 40 : 230;
            unsigned char *t = texels + (y * N + x) * 4;
            t[0] = t[1] = t[2] = v;
            t[3] = 255;
        }
    bg_image image = {N, N, BG_PIXEL_RGBA8, 0, texels};
    bg_texture_desc desc = {BG_WRAP_REPEAT, BG_TEXTURE_SRGB, BG_FILTER_NEAREST};
    return bg_scene_add_texture(scene, &image, &desc, out);
}

static bg_status add_objects(bg_scene *scene, uint32_t floor, uint32_t blue, uint32_t chrome)
{
    uint32_t id;
    /* The plane y = 0 moved down to y = -1; planar u = (x + 1) / 2 * uv_scale, so 0.25 gives one
     * checker cell (an eighth of the texture) per unit. */
    bg_object_desc d = bg_object_desc_init(BG_SHAPE_PLANE, floor);
    d.transform = bg_mat4_translate(0, -1, 0);
    d.uv_scale[0] = d.uv_scale[1] = 0.25;
    bg_status st = bg_scene_add_object(scene, &d, &id);
    /* The cube [-1, 1]^3 scaled to 0.6 (applied first), turned 30 degrees about y, set on the floor. */
    d = bg_object_desc_init(BG_SHAPE_BOX, blue);
    d.transform = bg_mat4_mul(bg_mat4_translate(-1.2, -0.4, 0.6),
                              bg_mat4_mul(bg_mat4_rotate(bg_vec3_make(0, 1, 0), 30), bg_mat4_scale(0.6, 0.6, 0.6)));
    if (st == BG_OK)
        st = bg_scene_add_object(scene, &d, &id);
    if (st == BG_OK)
        st = bg_scene_add_sphere(scene, bg_vec3_make(1.0, 0.0, -0.5), 1.0, chrome, &id);
    return st;
}

static bg_status add_lights_and_camera(bg_scene *scene)
{
    uint32_t id;
    bg_light light = bg_light_init();
    light.position = bg_vec3_make(3, 6, 4);
    light.intensity = 0.9;
    bg_status st = bg_scene_add_light(scene, &light, &id);
    light.position = bg_vec3_make(-4, 5, -2);
    light.intensity = 0.3;
    if (st == BG_OK)
        st = bg_scene_add_light(scene, &light, &id);
    bg_camera camera = bg_camera_init();
    camera.position = bg_vec3_make(0, 1.4, 5.5);
    camera.look_at = bg_vec3_make(0, -0.2, 0);
    if (st == BG_OK)
        st = bg_scene_set_camera(scene, &camera);
    return st;
}

/* Texture and materials first, then what uses them; the commit validates it all. false after
 * printing the scene's message (it keeps the first failure's). */
static bool build_scene(program *p)
{
    bg_status st = bg_scene_create(NULL, &p->scene);
    if (st != BG_OK) {
        fprintf(stderr, NAME ": creating the scene: %s\n", bg_status_string(st));
        return false;
    }
    uint32_t checker, floor, blue, chrome;
    st = add_checker_texture(p->scene, &checker);
    bg_material m = bg_material_init(); /* white Lambertian: the texture gives the floor its colour */
    m.base.reflectance.r = m.base.reflectance.g = m.base.reflectance.b = 1.0;
    m.base.reflectance.texture = checker;
    if (st == BG_OK)
        st = bg_scene_add_material(p->scene, &m, &floor);
    m = bg_material_init();
    m.base.reflectance.r = 0.1;
    m.base.reflectance.g = 0.25;
    m.base.reflectance.b = 0.85;
    if (st == BG_OK)
        st = bg_scene_add_material(p->scene, &m, &blue);
    m = bg_material_init(); /* roughness 0: a perfect mirror, traced as a reflected ray */
    m.base.reflectance.r = m.base.reflectance.g = m.base.reflectance.b = 0.85;
    m.base.roughness.value = 0.0;
    if (st == BG_OK)
        st = bg_scene_add_material(p->scene, &m, &chrome);
    if (st == BG_OK)
        st = add_objects(p->scene, floor, blue, chrome);
    if (st == BG_OK)
        st = add_lights_and_camera(p->scene);
    if (st == BG_OK)
        st = bg_scene_commit(p->scene);
    if (st != BG_OK) {
        fprintf(stderr, NAME ": building the scene: %s: %s\n", bg_status_string(st),
                bg_scene_error_message(p->scene));
        return false;
    }
    return true;
}

/* ---- 4. Render and save -------------------------------------------------------------------- */

/* Renders into a buffer of ours (the library never allocates the image) and writes the PNG. */
static bool render_and_save(program *p, int size, const char *path)
{
    p->pixels = malloc((size_t)size * (size_t)size * 4);
    if (!p->pixels) {
        fprintf(stderr, NAME ": out of memory for a %dx%d image\n", size, size);
        return false;
    }
    bg_image image = {size, size, BG_PIXEL_RGBA8, 0, p->pixels};
    bg_render_settings settings = bg_render_settings_init(); /* sRGB output, 5 bounce levels */
    bg_status st = bg_render_gpu(p->renderer, p->scene, &settings, &image);
    if (st != BG_OK) {
        /* GL failures carry MACS's message (a shader log, a limit, the GL error). */
        fprintf(stderr, NAME ": rendering: %s: %s\n", bg_status_string(st), bg_renderer_error_message(p->renderer));
        return false;
    }
    char message[512];
    st = bg_png_save(path, &image, message, sizeof message);
    if (st != BG_OK) {
        fprintf(stderr, NAME ": writing %s: %s\n", path, message);
        return false;
    }
    return true;
}

int main(int argc, char **argv)
{
    const char *path = NAME ".png";
    int size = DEFAULT_SIZE;
    int exit_now = parse_command_line(argc, argv, &path, &size);
    if (exit_now >= 0)
        return exit_now;

    program p = {NULL, NULL, NULL, NULL, NULL};
    bool ok = create_gpu(&p) && build_scene(&p) && render_and_save(&p, size, path);
    if (ok) {
        macs_gl_info info;
        macs_context_get_gl_info(p.context, &info);
        printf(NAME ": wrote %s (%dx%d) on %s\n", path, size, size, info.renderer ? info.renderer : "an unnamed GL");
    }
    release(&p);
    return ok ? 0 : 1;
}
