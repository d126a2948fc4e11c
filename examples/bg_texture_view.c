/* bg_texture_view: a frame that stays on the GPU, as an interactive viewer wants it. The ray tracer
 * renders into a MACS texture (bg_render_gpu_to_texture) instead of host memory; a MACS pass then
 * post-processes it the way a viewer's display step would (a 2x bilinear upscale, a vignette and
 * the sRGB encoding) into a texture the viewer made with its own GL calls and lent to MACS
 * (macs_texture_wrap); finally the viewer's own GL code binds that texture by its GL name, where
 * a real viewer would draw it, and here reads it back to save a PNG. Nothing but the final PNG
 * crosses to the host. Every call is in this file; it needs <betelgeuse.h> (with <macs.h>), the
 * system's <GL/gl.h> for the viewer's own GL calls, and libc:
 *
 *     cc -std=c99 bg_texture_view.c $(pkg-config --cflags --libs betelgeuse) -o bg_texture_view
 *
 * A program with a window (GLFW, SDL, a toolkit) makes its context current, passes its own
 * get_proc_address to MACS, and calls its GL directly instead of through the pointers below.
 *
 * Usage: bg_texture_view [out.png [size]]   (-h, --help: the usage)
 *   out.png     default bg_texture_view.png in the current folder
 *   size        the rendered frame's width and height in pixels, 1..8192, default 256; the PNG is
 *               twice that
 */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <GL/gl.h>

#include <betelgeuse.h>

#define NAME "bg_texture_view"
/* The PNG is twice the frame, which keeps it within the renderers' 16384 per side. */
enum { DEFAULT_SIZE = 256, MAX_SIZE = 8192, UPSCALE = 2 };

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
                   "Ray traces a frame into a GPU texture, post-processes it on the GPU (2x upscale, vignette)\n"
                   "into a texture of the viewer's own, and saves that as a PNG.\n"
                   "\n"
                   "  out.png     where to write the PNG (default " NAME ".png in the current folder)\n"
                   "  size        the frame's width and height in pixels, 1..%d (default %d); the PNG is %dx\n"
                   "  -h, --help  print this help and exit\n",
                   MAX_SIZE, DEFAULT_SIZE, UPSCALE);
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

/* ---- 2. The viewer's own GL ---------------------------------------------------------------- */

/* The GL calls this program makes itself, as a viewer does to draw. They come from the same loader
 * MACS was given, so they reach the same context (the headless one here, a window's in a viewer). */
typedef void (GLAPIENTRY *gen_textures_fn)(GLsizei n, GLuint *textures);
typedef void (GLAPIENTRY *delete_textures_fn)(GLsizei n, const GLuint *textures);
typedef void (GLAPIENTRY *bind_texture_fn)(GLenum target, GLuint texture);
typedef void (GLAPIENTRY *tex_image_2d_fn)(GLenum target, GLint level, GLint internalformat, GLsizei width,
                                           GLsizei height, GLint border, GLenum format, GLenum type,
                                           const void *pixels);
typedef void (GLAPIENTRY *get_tex_image_fn)(GLenum target, GLint level, GLenum format, GLenum type, void *pixels);
typedef GLenum (GLAPIENTRY *get_error_fn)(void);

typedef struct viewer_gl {
    gen_textures_fn GenTextures;
    delete_textures_fn DeleteTextures;
    bind_texture_fn BindTexture;
    tex_image_2d_fn TexImage2D;
    get_tex_image_fn GetTexImage;
    get_error_fn GetError;
} viewer_gl;

/* Looks one function up. The loader returns a generic function pointer (macs_gl_proc); the cast to
 * the function's own type is one ISO C defines. */
static bool found(macs_gl_proc p, const char *name)
{
    if (!p)
        fprintf(stderr, NAME ": the GL has no %s\n", name);
    return p != NULL;
}

#define LOAD_GL(gl, gpa, user, name, type) \
    (found(gpa("gl" #name, user), "gl" #name) && ((gl)->name = (type)gpa("gl" #name, user)) != NULL)

static bool load_viewer_gl(macs_get_proc_address_fn gpa, void *user, viewer_gl *gl)
{
    return LOAD_GL(gl, gpa, user, GenTextures, gen_textures_fn) &&
           LOAD_GL(gl, gpa, user, DeleteTextures, delete_textures_fn) &&
           LOAD_GL(gl, gpa, user, BindTexture, bind_texture_fn) && LOAD_GL(gl, gpa, user, TexImage2D, tex_image_2d_fn) &&
           LOAD_GL(gl, gpa, user, GetTexImage, get_tex_image_fn) && LOAD_GL(gl, gpa, user, GetError, get_error_fn);
}

/* ---- 3. Everything the program creates ------------------------------------------------------ */

/* NULL (or 0) until created; release() frees it in reverse order. */
typedef struct program {
    macs_headless *headless;
    macs_context *context;
    bg_renderer *renderer;
    bg_scene *scene;
    viewer_gl gl;
    GLuint display_name;   /* the viewer's texture, made and deleted by the viewer's GL */
    macs_texture *frame;   /* the ray tracer's output, a MACS texture */
    macs_texture *display; /* display_name lent to MACS */
    macs_pass *post;       /* frame -> display */
    unsigned char *texels, *pixels;
} program;

static void release(program *p)
{
    free(p->texels);
    free(p->pixels);
    macs_pass_destroy(p->post);
    /* A wrapped texture is only forgotten by MACS: the GL texture stays the viewer's. */
    macs_texture_destroy(p->display);
    macs_texture_destroy(p->frame);
    bg_scene_destroy(p->scene);
    bg_renderer_destroy(p->renderer); /* before the MACS context that holds its GPU objects */
    macs_context_destroy(p->context);
    if (p->display_name)
        p->gl.DeleteTextures(1, &p->display_name); /* the viewer's, so the viewer deletes it */
    macs_headless_destroy(p->headless);
}

/* A headless GL context, the MACS context over it, the renderer on that, and the viewer's GL. */
static bool create_gpu(program *p)
{
    char message[1024];
    macs_status ms = macs_headless_create(NULL, &p->headless, message, sizeof message);
    if (ms != MACS_OK) {
        fprintf(stderr, NAME ": headless OpenGL context: %s: %s\n", macs_status_string(ms), message);
        return false;
    }
    macs_context_desc cd = {0};
    cd.get_proc_address = macs_headless_get_proc_address(p->headless);
    cd.get_proc_address_user = macs_headless_proc_user(p->headless);
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
    return load_viewer_gl(cd.get_proc_address, cd.get_proc_address_user, &p->gl);
}

/* ---- 4. The scene -------------------------------------------------------------------------- */

/* Three spheres, one a mirror, on a grey floor under two lights. */
static bool build_scene(program *p)
{
    bg_status st = bg_scene_create(NULL, &p->scene);
    if (st != BG_OK) {
        fprintf(stderr, NAME ": creating the scene: %s\n", bg_status_string(st));
        return false;
    }
    bg_scene *s = p->scene;
    static const double colours[3][3] = {{0.85, 0.2, 0.15}, {0.9, 0.9, 0.9}, {0.15, 0.35, 0.85}};
    uint32_t materials[3], floor, id;
    for (int i = 0; i < 3 && st == BG_OK; i++) {
        bg_material m = bg_material_init();
        m.base.reflectance.r = colours[i][0];
        m.base.reflectance.g = colours[i][1];
        m.base.reflectance.b = colours[i][2];
        if (i == 1)
            m.base.roughness.value = 0.0; /* the middle sphere is a mirror */
        st = bg_scene_add_material(s, &m, &materials[i]);
    }
    bg_material grey = bg_material_init();
    if (st == BG_OK)
        st = bg_scene_add_material(s, &grey, &floor);
    for (int i = 0; i < 3 && st == BG_OK; i++)
        st = bg_scene_add_sphere(s, bg_vec3_make(-1.3 + 1.3 * i, 0.0, -0.4 * (i % 2)), 0.6, materials[i], &id);
    if (st == BG_OK)
        st = bg_scene_add_plane(s, bg_vec3_make(0, -0.6, 0), bg_vec3_make(0, 1, 0), floor, &id);
    bg_light light = bg_light_init();
    light.position = bg_vec3_make(2, 4, 3);
    if (st == BG_OK)
        st = bg_scene_add_light(s, &light, &id);
    light.position = bg_vec3_make(-3, 3, 1);
    light.intensity = 0.4;
    if (st == BG_OK)
        st = bg_scene_add_light(s, &light, &id);
    bg_camera camera = bg_camera_init();
    camera.position = bg_vec3_make(0, 1.2, 4.5);
    camera.look_at = bg_vec3_make(0, -0.1, 0);
    if (st == BG_OK)
        st = bg_scene_set_camera(s, &camera);
    if (st == BG_OK)
        st = bg_scene_commit(s);
    if (st != BG_OK) {
        fprintf(stderr, NAME ": building the scene: %s: %s\n", bg_status_string(st), bg_scene_error_message(s));
        return false;
    }
    return true;
}

/* ---- 5. The frame, into a texture ---------------------------------------------------------- */

/* An RGBA32F target gets linear, unclamped radiance, so the post-process works in linear light and
 * encodes once at the end (an RGBA8 target would get the settings' sRGB bytes instead). LINEAR
 * filtering makes the 2x upscale bilinear. Texture row 0 is the image's bottom row: a quad drawn
 * with texture coordinate (0, 0) at its bottom-left shows it upright. */
static bool render_frame(program *p, int size)
{
    macs_texture_desc td = {0};
    td.width = td.height = size;
    td.format = MACS_FORMAT_RGBA32F;
    td.filter = MACS_FILTER_LINEAR;
    macs_status ms = macs_texture_create(p->context, &td, &p->frame);
    if (ms != MACS_OK) {
        fprintf(stderr, NAME ": frame texture: %s\n", macs_context_error_message(p->context));
        return false;
    }
    bg_render_settings settings = bg_render_settings_init(); /* automatic plan, 5 bounce levels */
    bg_status st = bg_render_gpu_to_texture(p->renderer, p->scene, &settings, p->frame);
    if (st != BG_OK) {
        fprintf(stderr, NAME ": rendering: %s: %s\n", bg_status_string(st), bg_renderer_error_message(p->renderer));
        return false;
    }
    /* A viewer showing the frame as it is would now call, with its own GL,
     *     glBindTexture(GL_TEXTURE_2D, macs_texture_gl_name(p->frame));
     * and draw a textured quad; here a MACS pass draws it into the viewer's texture instead. */
    return true;
}

/* ---- 6. The viewer's texture and the post-process ------------------------------------------ */

/* The viewer makes its display texture with its own GL, as it would for any texture it draws, and
 * lends it to MACS. The wrap checks the name, size and format against GL and sets the texture's
 * filter and wrap (GL's default minification filter wants mipmaps, which a pass cannot sample). */
static bool make_display(program *p, int size)
{
    int big = size * UPSCALE;
    viewer_gl *gl = &p->gl;
    gl->GenTextures(1, &p->display_name);
    gl->BindTexture(GL_TEXTURE_2D, p->display_name);
    gl->TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, big, big, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    gl->BindTexture(GL_TEXTURE_2D, 0);
    GLenum e = gl->GetError();
    if (e != GL_NO_ERROR) {
        fprintf(stderr, NAME ": the display texture (%dx%d): GL error 0x%04x\n", big, big, (unsigned)e);
        return false;
    }
    macs_texture_wrap_desc wd = {0};
    wd.gl_name = p->display_name;
    wd.width = wd.height = big;
    wd.format = MACS_FORMAT_RGBA8;
    if (macs_texture_wrap(p->context, &wd, &p->display) != MACS_OK) {
        fprintf(stderr, NAME ": wrapping the display texture: %s\n", macs_context_error_message(p->context));
        return false;
    }
    return true;
}

/* One pass over the display's pixels: the frame sampled bilinearly at the same place (macs_uv runs
 * 0..1 over the output whatever its size, so a larger output is an upscale), darkened towards the
 * corners, clamped and sRGB-encoded for the RGBA8 display. */
static bool post_process(program *p)
{
    macs_input_desc input = {"frame"};
    macs_output_desc output = {"shown", "vec4(srgb(clamp(linear * vignette, 0.0, 1.0)), 1.0)"};
    macs_pass_desc pd = {0};
    pd.functions = "vec3 srgb(vec3 x)\n"
                   "{\n"
                   "    vec3 lo = 12.92 * x;\n"
                   "    vec3 hi = 1.055 * pow(max(x, vec3(0.0031308)), vec3(1.0 / 2.4)) - 0.055;\n"
                   "    return mix(lo, hi, step(vec3(0.0031308), x));\n"
                   "}\n";
    pd.main = "vec3 linear = texture2D(frame, macs_uv).rgb;\n"
              "vec2 d = macs_uv - 0.5;\n"
              "float vignette = 1.0 - 1.2 * dot(d, d);\n";
    pd.inputs = &input;
    pd.input_count = 1;
    pd.outputs = &output;
    pd.output_count = 1;
    pd.input_textures = &p->frame;
    pd.output_textures = &p->display;
    macs_status ms = macs_pass_create(p->context, &pd, &p->post);
    if (ms == MACS_OK)
        ms = macs_pass_run(p->post, NULL);
    if (ms != MACS_OK) {
        fprintf(stderr, NAME ": post-process pass: %s\n", macs_context_error_message(p->context));
        return false;
    }
    return true;
}

/* ---- 7. Showing it ------------------------------------------------------------------------- */

/* Where a viewer binds the display texture and draws it, this program binds it and reads it with
 * its own GL (GL's rows come bottom first; the PNG's top first), then saves the PNG. */
static bool show(program *p, int size, const char *path)
{
    int big = size * UPSCALE;
    size_t row = (size_t)big * 4;
    p->texels = malloc(row * (size_t)big);
    p->pixels = malloc(row * (size_t)big);
    if (!p->texels || !p->pixels) {
        fprintf(stderr, NAME ": out of memory for a %dx%d image\n", big, big);
        return false;
    }
    viewer_gl *gl = &p->gl;
    /* The same name the viewer made; macs_texture_gl_name gives any MACS texture's, wrapped or not. */
    gl->BindTexture(GL_TEXTURE_2D, macs_texture_gl_name(p->display));
    gl->GetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, p->texels);
    gl->BindTexture(GL_TEXTURE_2D, 0);
    GLenum e = gl->GetError();
    if (e != GL_NO_ERROR) {
        fprintf(stderr, NAME ": reading the display texture: GL error 0x%04x\n", (unsigned)e);
        return false;
    }
    for (int y = 0; y < big; y++)
        memcpy(p->pixels + (size_t)y * row, p->texels + (size_t)(big - 1 - y) * row, row);
    bg_image image = {big, big, BG_PIXEL_RGBA8, 0, p->pixels};
    char message[512];
    if (bg_png_save(path, &image, message, sizeof message) != BG_OK) {
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

    program p;
    memset(&p, 0, sizeof p);
    bool ok = create_gpu(&p) && build_scene(&p) && render_frame(&p, size) && make_display(&p, size) &&
              post_process(&p) && show(&p, size, path);
    if (ok) {
        bg_render_stats stats;
        bg_renderer_get_stats(p.renderer, &stats);
        printf(NAME ": wrote %s (%dx%d from a %dx%d frame in GL texture %u, plan %d; shown from GL texture %u)\n",
               path, size * UPSCALE, size * UPSCALE, size, size, macs_texture_gl_name(p.frame), (int)stats.plan,
               (unsigned)p.display_name);
    }
    release(&p);
    return ok ? 0 : 1;
}
