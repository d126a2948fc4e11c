/* bg_window: the smallest program that shows Betelgeuse in a window of its own. GLFW opens the window
 * with an OpenGL 2.1 context; MACS is made from glfwGetProcAddress, as from any program's own context;
 * a scene is built in code (a sphere over a plane, one light); then a progressive loop renders the
 * frame into a texture on the GPU, draws that texture on a quad and swaps, until the window closes.
 * Every call is in this file; it needs <betelgeuse.h> (with <macs.h>), GLFW 3, the system's GL for the
 * quad, and libc:
 *
 *     cc -std=c99 bg_window.c $(pkg-config --cflags --libs betelgeuse glfw3) -lGL -o bg_window
 *
 * Usage: bg_window [--frames N] [out.png [size]]   (-h, --help: the usage)
 *   --frames N  draw N frames, then save out.png (when given) and exit 0; default: until closed
 *   out.png     where --frames saves the last frame
 *   size        the window's width and height in pixels, 1..4096, default 256
 *
 * Progressive: each frame adds one sample per pixel to a running sum on the GPU (bg_accumulation) and
 * draws its mean, so the picture appears at once and then sharpens; at 16 samples the frame is
 * bg_render_gpu's at samples = 16, bit for bit, and the loop stops rendering and only waits for events.
 */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define GLFW_INCLUDE_NONE
#include <GL/gl.h>
#include <GLFW/glfw3.h>

#include <betelgeuse.h>

#define NAME "bg_window"
enum { DEFAULT_SIZE = 256, MAX_SIZE = 4096, MAX_SAMPLES = 16 };

/* ---- 1. The command line ------------------------------------------------------------------- */

/* A whole number in [lo, hi], or -1. */
static long whole(const char *text, long lo, long hi)
{
    char *end = NULL;
    long v = strtol(text, &end, 10);
    return text[0] >= '0' && text[0] <= '9' && *end == '\0' && v >= lo && v <= hi ? v : -1;
}

/* Reads "[--frames N] [out.png [size]]". Returns -1 to go on, else the exit status: 0 after --help,
 * 2 after naming an unknown option, a bad number or a third argument. */
static int parse_command_line(int argc, char **argv, int *frames, const char **path, int *size)
{
    int positional = 0;
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        if (strcmp(arg, "-h") == 0 || strcmp(arg, "--help") == 0) {
            printf("usage: " NAME " [--frames N] [out.png [size]]\n"
                   "Ray traces a sphere over a plane into a GPU texture and shows it in a window, one more sample\n"
                   "per pixel each frame, up to %d.\n"
                   "\n"
                   "  --frames N  draw N frames, save out.png when given, and exit\n"
                   "  out.png     where --frames saves the last frame\n"
                   "  size        the window's width and height in pixels, 1..%d (default %d)\n"
                   "  -h, --help  print this help and exit\n",
                   MAX_SAMPLES, MAX_SIZE, DEFAULT_SIZE);
            return 0;
        }
        if (strcmp(arg, "--frames") == 0) {
            long n = i + 1 < argc ? whole(argv[i + 1], 1, 1000000) : -1;
            if (n < 0) {
                fprintf(stderr, NAME ": --frames '%s' is not a whole number 1..1000000\n", i + 1 < argc ? argv[i + 1] : "");
                return 2;
            }
            *frames = (int)n;
            i++;
        } else if (arg[0] == '-') {
            fprintf(stderr, NAME ": unknown option '%s' (try --help)\n", arg);
            return 2;
        } else if (positional == 0) {
            *path = arg;
            positional++;
        } else if (positional == 1) {
            long v = whole(arg, 1, MAX_SIZE);
            if (v < 0) {
                fprintf(stderr, NAME ": size '%s' is not an integer in 1..%d\n", arg, MAX_SIZE);
                return 2;
            }
            *size = (int)v;
            positional++;
        } else {
            fprintf(stderr, NAME ": too many arguments ('%s'): at most out.png and size (try --help)\n", arg);
            return 2;
        }
    }
    return -1;
}

/* ---- 2. MACS on the window's context -------------------------------------------------------- */

/* GLFW's loader in MACS's shape: glfwGetProcAddress already returns a function pointer. */
static macs_gl_proc glfw_proc(const char *name, void *user)
{
    (void)user;
    return (macs_gl_proc)glfwGetProcAddress(name);
}

/* ---- 3. The scene -------------------------------------------------------------------------- */

/* A red sphere on a grey plane under one light. */
static bg_status build_scene(bg_scene *s)
{
    uint32_t red, grey, id;
    bg_material m = bg_material_init();
    m.base.reflectance.r = 0.85;
    m.base.reflectance.g = 0.2;
    m.base.reflectance.b = 0.15;
    bg_status st = bg_scene_add_material(s, &m, &red);
    m = bg_material_init();
    if (st == BG_OK)
        st = bg_scene_add_material(s, &m, &grey);
    if (st == BG_OK)
        st = bg_scene_add_sphere(s, bg_vec3_make(0, 0, 0), 1.0, red, &id);
    if (st == BG_OK)
        st = bg_scene_add_plane(s, bg_vec3_make(0, -1, 0), bg_vec3_make(0, 1, 0), grey, &id);
    bg_light light = bg_light_init();
    light.position = bg_vec3_make(3, 5, 4);
    if (st == BG_OK)
        st = bg_scene_add_light(s, &light, &id);
    bg_camera camera = bg_camera_init();
    camera.position = bg_vec3_make(0, 1.5, 5);
    camera.look_at = bg_vec3_make(0, -0.2, 0);
    if (st == BG_OK)
        st = bg_scene_set_camera(s, &camera);
    if (st == BG_OK)
        st = bg_scene_commit(s);
    return st;
}

/* ---- 4. Drawing the frame's texture -------------------------------------------------------- */

/* A quad over the whole window with the texture on it, GL 2.1's fixed function. MACS leaves its own
 * GL state changed (viewport, scissor, blending, textures; macs.h), so the state the quad needs is set
 * here every time. Texture row 0 is the frame's bottom row: (0, 0) at the bottom-left shows it upright. */
static void draw_texture(const macs_texture *frame, int width, int height)
{
    glViewport(0, 0, width, height);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_BLEND);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glEnable(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, macs_texture_gl_name(frame));
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
    glBegin(GL_QUADS);
    glTexCoord2f(0, 0);
    glVertex2f(-1, -1);
    glTexCoord2f(1, 0);
    glVertex2f(1, -1);
    glTexCoord2f(1, 1);
    glVertex2f(1, 1);
    glTexCoord2f(0, 1);
    glVertex2f(-1, 1);
    glEnd();
    glBindTexture(GL_TEXTURE_2D, 0);
    glDisable(GL_TEXTURE_2D);
}

/* ---- 5. The program ------------------------------------------------------------------------ */

int main(int argc, char **argv)
{
    int frames = 0, size = DEFAULT_SIZE;
    const char *path = NULL;
    int parsed = parse_command_line(argc, argv, &frames, &path, &size);
    if (parsed >= 0)
        return parsed;

    /* The window, with an OpenGL 2.1 context current on this thread. */
    if (!glfwInit()) {
        const char *why = NULL;
        glfwGetError(&why);
        fprintf(stderr, NAME ": GLFW: %s\n", why ? why : "cannot start (no display?)");
        return 1;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 2);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    GLFWwindow *window = glfwCreateWindow(size, size, NAME, NULL, NULL);
    if (!window) {
        const char *why = NULL;
        glfwGetError(&why);
        fprintf(stderr, NAME ": no window with OpenGL 2.1: %s\n", why ? why : "?");
        glfwTerminate();
        return 1;
    }
    glfwMakeContextCurrent(window);

    /* MACS from the window's loader, the renderer on it, the scene, and the frame's texture. */
    int status = 1;
    char message[1024];
    macs_context *context = NULL;
    bg_renderer *renderer = NULL;
    bg_scene *scene = NULL;
    macs_texture *frame = NULL;
    bg_accumulation *sum = NULL;
    macs_context_desc cd = {0};
    cd.get_proc_address = glfw_proc;
    bg_renderer_desc rd = {0};
    macs_texture_desc td = {0};
    td.width = td.height = size;
    td.format = MACS_FORMAT_RGBA8; /* the sRGB bytes a window shows */
    bg_status st;
    if (macs_context_create(&cd, &context, message, sizeof message) != MACS_OK) {
        fprintf(stderr, NAME ": MACS context: %s\n", message);
    } else if ((rd.context = context), bg_renderer_create(&rd, &renderer, message, sizeof message) != BG_OK) {
        fprintf(stderr, NAME ": renderer: %s\n", message);
    } else if ((st = bg_scene_create(NULL, &scene)) != BG_OK || (st = build_scene(scene)) != BG_OK) {
        fprintf(stderr, NAME ": building the scene: %s: %s\n", bg_status_string(st),
                scene ? bg_scene_error_message(scene) : "");
    } else if (macs_texture_create(context, &td, &frame) != MACS_OK) {
        fprintf(stderr, NAME ": the frame's texture: %s\n", macs_context_error_message(context));
    } else if (bg_accumulation_create(renderer, size, size, &sum) != BG_OK) {
        fprintf(stderr, NAME ": the accumulation: %s\n", bg_renderer_error_message(renderer));
    } else {
        /* The loop: add a sample of the 16-sample pattern while there are more to take, draw the mean,
         * swap; once the sum has them all, sleep until an event instead of drawing the same picture. */
        bg_render_settings settings = bg_render_settings_init();
        settings.frame_width = settings.frame_height = size;
        settings.samples = MAX_SAMPLES;
        status = 0;
        for (int drawn = 0; !glfwWindowShouldClose(window) && (frames == 0 || drawn < frames); drawn++) {
            int done = bg_accumulation_samples(sum);
            if (done < MAX_SAMPLES) {
                st = bg_render_gpu_accumulate(renderer, scene, &settings, sum, done, 1);
                if (st == BG_OK)
                    st = bg_accumulation_resolve_to_texture(renderer, sum, &settings, frame);
                if (st != BG_OK) {
                    fprintf(stderr, NAME ": render: %s\n", bg_renderer_error_message(renderer));
                    status = 1;
                    break;
                }
                int w, h;
                glfwGetFramebufferSize(window, &w, &h);
                draw_texture(frame, w, h);
                glfwSwapBuffers(window);
                glfwPollEvents();
            } else if (frames == 0) {
                glfwWaitEvents();
            }
        }
        /* --frames with out.png: the last frame, read back from the GPU (rows bottom first), saved. */
        if (status == 0 && frames > 0 && path) {
            bg_image image = {size, size, BG_PIXEL_RGBA8, 0, malloc((size_t)size * size * 4)};
            unsigned char *rows = malloc((size_t)size * size * 4);
            if (!image.pixels || !rows || macs_texture_read(frame, rows, 0) != MACS_OK) {
                fprintf(stderr, NAME ": reading the frame back failed\n");
                status = 1;
            } else {
                for (int y = 0; y < size; y++)
                    memcpy((unsigned char *)image.pixels + (size_t)y * size * 4,
                           rows + (size_t)(size - 1 - y) * size * 4, (size_t)size * 4);
                if (bg_png_save(path, &image, message, sizeof message) != BG_OK) {
                    fprintf(stderr, NAME ": %s\n", message);
                    status = 1;
                } else {
                    printf(NAME ": %d samples per pixel, saved to %s\n", bg_accumulation_samples(sum), path);
                }
            }
            free(rows);
            free(image.pixels);
        }
    }

    /* Released in reverse order; the renderer before the MACS context that holds its GPU objects. */
    bg_accumulation_destroy(sum);
    macs_texture_destroy(frame);
    bg_scene_destroy(scene);
    bg_renderer_destroy(renderer);
    macs_context_destroy(context);
    glfwDestroyWindow(window);
    glfwTerminate();
    return status;
}
