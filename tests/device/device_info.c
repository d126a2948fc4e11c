/* What a headless context runs on, for the device check's report (tests/device/run.sh): the EGL
 * device, GL's vendor, renderer and version strings, the limits MACS reads and the ones it passes
 * on after its caps, its optional features, a few more GL 2.1 limits that legacy parts are short of,
 * and the extension string. Exit 0, or 1 with MACS's reason where no context can be made.
 * Usage: device_info [device|egl|osmesa|default]   (default: device, the first EGL device) */
#include <stdio.h>
#include <string.h>

#include "macs.h"

typedef const unsigned char *(*get_string_fn)(unsigned name);
typedef void (*get_integerv_fn)(unsigned name, int *values);

static const char *or_none(const char *s)
{
    return s ? s : "(none)";
}

static void print_limits(const char *what, const macs_limits *l)
{
    printf("MACS limits (%s): draw buffers %d, colour attachments %d, texture units %d, texture size %d, "
           "fragment uniform components %d\n",
           what, l->max_draw_buffers, l->max_color_attachments, l->max_texture_units, l->max_texture_size,
           l->max_uniform_components);
}

/* GL 2.1 limits MACS does not read, by their enum values (GL 2.0's tokens). */
static void print_more_limits(macs_get_proc_address_fn get, void *user)
{
    static const struct { const char *name; unsigned token; } limits[] = {
        {"GL_MAX_VARYING_FLOATS", 0x8B4B},
        {"GL_MAX_VERTEX_UNIFORM_COMPONENTS", 0x8B4A},
        {"GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS", 0x8B4C},
        {"GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS", 0x8B4D},
        {"GL_MAX_RENDERBUFFER_SIZE", 0x84E8},
    };
    macs_gl_proc proc = get("glGetIntegerv", user);
    get_integerv_fn get_integerv = (get_integerv_fn)proc;
    if (!get_integerv)
        return;
    printf("GL limits:");
    for (size_t i = 0; i < sizeof limits / sizeof limits[0]; i++) {
        int v[2] = {0, 0};
        get_integerv(limits[i].token, v);
        printf("%s %s %d", i ? "," : "", limits[i].name, v[0]);
    }
    printf("\n");
    proc = get("glGetString", user);
    get_string_fn get_string = (get_string_fn)proc;
    if (get_string)
        printf("GL_EXTENSIONS: %s\n", or_none((const char *)get_string(0x1F03)));
}

int main(int argc, char **argv)
{
    static const struct { const char *name; macs_headless_backend backend; } names[] = {
        {"device", MACS_HEADLESS_EGL_DEVICE},
        {"egl", MACS_HEADLESS_EGL},
        {"osmesa", MACS_HEADLESS_OSMESA},
        {"default", MACS_HEADLESS_DEFAULT},
    };
    const char *want = argc > 1 ? argv[1] : "device";
    size_t i = 0;
    while (i < sizeof names / sizeof names[0] && strcmp(want, names[i].name) != 0)
        i++;
    if (argc > 2 || i == sizeof names / sizeof names[0]) {
        fprintf(stderr, "usage: device_info [device|egl|osmesa|default]\n");
        return 2;
    }
    macs_headless_desc hd = {0};
    hd.backend = names[i].backend;
    char message[1024] = "";
    macs_headless *h = NULL;
    if (macs_headless_create(&hd, &h, message, sizeof message) != MACS_OK) {
        printf("no %s context: %s\n", want, message);
        return 1;
    }
    macs_headless_info hi;
    macs_headless_get_info(h, &hi);
    static const char *const backends[] = {"default", "OSMesa", "EGL surfaceless", "EGL device"};
    printf("backend: %s", backends[hi.backend]);
    if (hi.backend == MACS_HEADLESS_EGL_DEVICE)
        printf(", device %d of %d (%s)", hi.device_index, hi.device_count, hi.device_name);
    printf("\n");

    macs_context_desc cd = {0};
    cd.get_proc_address = macs_headless_get_proc_address(h);
    cd.get_proc_address_user = macs_headless_proc_user(h);
    macs_context *ctx = NULL;
    int status = 0;
    if (macs_context_create(&cd, &ctx, message, sizeof message) != MACS_OK) {
        printf("no MACS context: %s\n", message);
        status = 1;
    } else {
        macs_gl_info gi;
        macs_context_get_gl_info(ctx, &gi);
        printf("GL_VENDOR: %s\nGL_RENDERER: %s\nGL_VERSION: %s\nGL_SHADING_LANGUAGE_VERSION: %s\n", or_none(gi.vendor),
               or_none(gi.renderer), or_none(gi.version), or_none(gi.shading_language_version));
        macs_limits real, effective;
        macs_context_get_limits(ctx, &real, &effective);
        print_limits("GL", &real);
        print_limits("after caps", &effective);
        macs_features f;
        macs_context_get_features(ctx, &f);
        printf("features: ARB_framebuffer_object %s, ARB_depth_buffer_float %s, ARB_color_buffer_float %s, "
               "ARB_half_float_pixel %s\n",
               f.arb_framebuffer_object ? "yes" : "no", f.depth_buffer_float ? "yes" : "no",
               f.color_buffer_float ? "yes" : "no", f.half_float_pixel ? "yes" : "no");
        print_more_limits(cd.get_proc_address, cd.get_proc_address_user);
        macs_context_destroy(ctx);
    }
    macs_headless_destroy(h);
    return status;
}
