/* macs_hello: compute a Mandelbrot image with one MACS pass on a headless context and save it as PNG.
 * Usage: macs_hello [out.png]   (default: macs_hello.png in the current folder; -h, --help: the usage)
 * It needs only macs.h, libpng and libc. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <png.h>

#include "macs.h"

enum { WIDTH = 512, HEIGHT = 384 };

/* Reads "[out.png]" into *path. Returns -1 to go on, else the exit status: 0 after --help, 2 after
 * naming an unknown option or a second argument. */
static int parse_command_line(int argc, char **argv, const char **path)
{
    int positional = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0) {
            printf("usage: macs_hello [out.png]\n"
                   "Computes a Mandelbrot image (%dx%d) with one MACS pass on a headless OpenGL context.\n"
                   "\n"
                   "  out.png     where to write the PNG (default macs_hello.png in the current folder)\n"
                   "  -h, --help  print this help and exit\n",
                   WIDTH, HEIGHT);
            return 0;
        }
        if (argv[i][0] == '-') {
            fprintf(stderr, "macs_hello: unknown option '%s' (try --help)\n", argv[i]);
            return 2;
        }
        if (positional++ > 0) {
            fprintf(stderr, "macs_hello: too many arguments ('%s'): at most out.png (try --help)\n", argv[i]);
            return 2;
        }
        *path = argv[i];
    }
    return -1;
}

int main(int argc, char **argv)
{
    const char *path = "macs_hello.png";
    int exit_now = parse_command_line(argc, argv, &path);
    if (exit_now >= 0)
        return exit_now;

    char message[1024];

    /* 1. An OpenGL context without a window (a GLFW or SDL user passes its own loader instead). */
    macs_headless *gl = NULL;
    if (macs_headless_create(NULL, &gl, message, sizeof message) != MACS_OK) {
        fprintf(stderr, "macs_hello: %s\n", message);
        return 1;
    }
    macs_context_desc cd = {0};
    cd.get_proc_address = macs_headless_get_proc_address(gl);
    cd.get_proc_address_user = macs_headless_proc_user(gl);
    macs_context *ctx = NULL;
    if (macs_context_create(&cd, &ctx, message, sizeof message) != MACS_OK) {
        fprintf(stderr, "macs_hello: %s\n", message);
        macs_headless_destroy(gl);
        return 1;
    }
    /* The limits that decide how passes are split (caps in the descriptor can only lower them). */
    macs_limits real, effective;
    macs_context_get_limits(ctx, &real, &effective);
    macs_gl_info info;
    macs_context_get_gl_info(ctx, &info);
    printf("macs_hello: %s, GL %s: %d draw buffers, %d colour attachments, %d texture units, "
           "texture size %d (effective %d / %d / %d / %d)\n",
           info.renderer ? info.renderer : "?", info.version ? info.version : "?", real.max_draw_buffers,
           real.max_color_attachments, real.max_texture_units, real.max_texture_size,
           effective.max_draw_buffers, effective.max_color_attachments, effective.max_texture_units,
           effective.max_texture_size);

    /* 2. An 8-bit output texture and a pass: GLSL 1.10 code run once per output pixel. */
    macs_texture_desc td = {0};
    td.width = WIDTH;
    td.height = HEIGHT;
    td.format = MACS_FORMAT_RGBA8;
    macs_texture *image = NULL;
    macs_status st = macs_texture_create(ctx, &td, &image);

    macs_uniform_desc uniforms[] = {{"center", MACS_UNIFORM_VEC2, 0}, {"scale", MACS_UNIFORM_VEC2, 0}};
    macs_output_desc output = {"color", "vec4(inside ? vec3(0.0) : palette(t), 1.0)"};
    macs_pass_desc pd = {0};
    pd.functions = "vec3 palette(float t)\n"
                   "{\n"
                   "    return 0.5 + 0.5 * cos(6.28318 * (vec3(0.0, 0.1, 0.2) + t * 1.5 + 0.5));\n"
                   "}\n";
    /* GLSL 1.10 loops need a constant bound; the escape is a break. */
    pd.main = "vec2 c = center + (macs_uv - 0.5) * scale;\n"
              "vec2 z = vec2(0.0);\n"
              "float n = 0.0;\n"
              "for (int i = 0; i < 200; i++) {\n"
              "    z = vec2(z.x * z.x - z.y * z.y, 2.0 * z.x * z.y) + c;\n"
              "    if (dot(z, z) > 16.0) break;\n"
              "    n += 1.0;\n"
              "}\n"
              "bool inside = n >= 200.0;\n"
              "float t = sqrt(n / 200.0);\n";
    pd.uniforms = uniforms;
    pd.uniform_count = 2;
    pd.outputs = &output;
    pd.output_count = 1;
    pd.output_textures = &image;
    macs_pass *pass = NULL;
    if (st == MACS_OK)
        st = macs_pass_create(ctx, &pd, &pass);

    /* 3. Uniforms, one run, and the pixels back into our own buffer. */
    const float center[2] = {-0.65f, 0.0f};
    const float scale[2] = {2.6f * WIDTH / HEIGHT, 2.6f};
    unsigned char *pixels = malloc((size_t)WIDTH * HEIGHT * 4);
    if (st == MACS_OK && !pixels)
        st = MACS_ERR_OUT_OF_MEMORY;
    if (st == MACS_OK)
        st = macs_pass_set_uniform(pass, "center", center);
    if (st == MACS_OK)
        st = macs_pass_set_uniform(pass, "scale", scale);
    if (st == MACS_OK)
        st = macs_pass_run(pass, NULL);
    if (st == MACS_OK)
        st = macs_texture_read(image, pixels, 0);
    if (st != MACS_OK)
        fprintf(stderr, "macs_hello: %s\n", macs_context_error_message(ctx));

    /* 4. PNG through libpng's simplified API; texture rows run bottom-up, so the stride is negative. */
    int ok = st == MACS_OK;
    if (ok) {
        png_image png = {0};
        png.version = PNG_IMAGE_VERSION;
        png.width = WIDTH;
        png.height = HEIGHT;
        png.format = PNG_FORMAT_RGBA;
        ok = png_image_write_to_file(&png, path, 0, pixels, -(png_int_32)(WIDTH * 4), NULL);
        if (!ok)
            fprintf(stderr, "macs_hello: %s: %s\n", path, png.message);
        else
            printf("macs_hello: wrote %s (%dx%d)\n", path, WIDTH, HEIGHT);
    }
    free(pixels);
    macs_context_destroy(ctx); /* also destroys the pass and the texture */
    macs_headless_destroy(gl);
    return ok ? 0 : 1;
}
