/* Textures at their image's precision (docs/shading.md 5.2):
 *   - the sRGB decode table is the EOTF of k / 255 for every byte k;
 *   - an RGBA8 image keeps 4 bytes a texel on the host (a float image 16), from bg_scene_add_texture
 *     and from an 8-bit PNG alike;
 *   - the CPU reference decodes every byte exactly as the table says (linear textures as k / 255);
 *   - the GPU shader decodes every byte to the table's float, exactly, through the production lookup
 *     (bg_texture_srgb.glsl), with NEAREST and with the shader's GL_LINEAR at texel centres, and
 *     filters between texels as the CPU reference does to float rounding;
 *   - the renderer reports 4 bytes a texel of GPU memory for an 8-bit texture (plus the 4096 bytes of
 *     the table) in every plan, and 16 on a context with too few texture units for the table, where
 *     the image is the same. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "betelgeuse.h"
#include "betelgeuse/common/srgb.h"
#include "betelgeuse/cpu/cpu_internal.h"
#include "betelgeuse/gpu/shared/shared.h"
#include "betelgeuse/scene/scene_internal.h"
#include "util_gl.h"
#include "util_gpu.h"

/* Byte k of channel c in texel k of the 256 x 1 test image: every value in every channel, in a
 * different order per channel. */
static unsigned char byte_of(int k, int c)
{
    switch (c) {
    case 0:
        return (unsigned char)k;
    case 1:
        return (unsigned char)(255 - k);
    case 2:
        return (unsigned char)((k * 101 + 7) & 255); /* 101 is odd: a permutation of 0..255 */
    default:
        return (unsigned char)((k * 37 + 11) & 255);
    }
}

/* A scene holding the 256 x 1 image as texture 1 with the encoding and filter. */
static bg_scene *byte_scene(bg_texture_encoding encoding, bg_texture_filter filter)
{
    unsigned char px[256 * 4];
    for (int k = 0; k < 256; k++)
        for (int c = 0; c < 4; c++)
            px[4 * k + c] = byte_of(k, c);
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_image img = {256, 1, BG_PIXEL_RGBA8, 0, px};
    bg_texture_desc d = {BG_WRAP_CLAMP, encoding, filter};
    uint32_t t = 0;
    assert_int_equal(bg_scene_add_texture(s, &img, &d, &t), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    return s;
}

/* What byte b of channel c decodes to: the table for sRGB colour, else b / 255. */
static double decoded(unsigned char b, int c, bool srgb)
{
    return srgb && c < 3 ? bgi_srgb_table[b] : b / 255.0;
}

/* ---- the host ---- */

static void srgb_table_is_the_eotf(void **state)
{
    (void)state;
    assert_true(bgi_srgb_table[0] == 0.0 && bgi_srgb_table[255] == 1.0);
    for (int k = 0; k < 256; k++) {
        double want = bgi_srgb_to_linear(k / 255.0);
        /* Written out with one libm, checked here with whichever: equal to within one double step. */
        if (fabs(bgi_srgb_table[k] - want) > nextafter(want, 2.0) - want)
            fail_msg("bgi_srgb_table[%d] = %.17g, the EOTF of %d/255 is %.17g", k, bgi_srgb_table[k], k, want);
        if (k > 0 && !(bgi_srgb_table[k] > bgi_srgb_table[k - 1]))
            fail_msg("bgi_srgb_table is not increasing at %d", k);
    }
}

static void rgba8_keeps_bytes_on_the_host(void **state)
{
    (void)state;
    /* From bg_scene_add_texture: the bytes as given, rows flipped, 4 a texel. */
    unsigned char px[3 * 2 * 4];
    for (int i = 0; i < (int)sizeof px; i++)
        px[i] = (unsigned char)(i * 11);
    float fpx[3 * 2 * 4] = {0};
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_image img8 = {3, 2, BG_PIXEL_RGBA8, 0, px}, img32 = {3, 2, BG_PIXEL_RGBA32F, 0, fpx};
    uint32_t a = 0, b = 0, c = 0;
    assert_int_equal(bg_scene_add_texture(s, &img8, NULL, &a), BG_OK);
    assert_int_equal(bg_scene_add_texture(s, &img32, NULL, &b), BG_OK);

    /* From an 8-bit PNG: the same. */
    char path[] = "/tmp/bg_texprec_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    char msg[256];
    assert_int_equal(bg_png_save(path, &img8, msg, sizeof msg), BG_OK);
    bg_texture_desc lin = {BG_WRAP_REPEAT, BG_TEXTURE_LINEAR, BG_FILTER_NEAREST};
    assert_int_equal(bg_scene_load_texture_png(s, path, &lin, &c), BG_OK);
    remove(path);
    assert_int_equal(bg_scene_commit(s), BG_OK);

    const bg_scene_state *st = bgi_scene_committed(s);
    const bg_texture_data *t8 = &st->textures[a - 1], *t32 = &st->textures[b - 1], *tp = &st->textures[c - 1];
    assert_true(t8->bytes && !t8->texels && t8->srgb);
    assert_true(tp->bytes && !tp->texels && !tp->srgb);
    assert_true(t32->texels && !t32->bytes);
    assert_int_equal(bgi_texture_bytes(t8), 3 * 2 * 4);
    assert_int_equal(bgi_texture_bytes(tp), 3 * 2 * 4);
    assert_int_equal(bgi_texture_bytes(t32), 3 * 2 * 16);
    /* Row 0 of the texture is the image's bottom row. */
    assert_memory_equal(t8->bytes, px + 12, 12);
    assert_memory_equal(t8->bytes + 12, px, 12);
    assert_memory_equal(tp->bytes, t8->bytes, 24);
    bg_scene_destroy(s);
}

/* The CPU reference samples every byte of every channel as the table (sRGB) or k / 255 (linear)
 * says, exactly, with NEAREST and with GL_LINEAR at texel centres. */
static void cpu_decodes_every_byte(void **state)
{
    (void)state;
    for (int e = 0; e < 2; e++)
        for (int f = 0; f < 2; f++) {
            bool srgb = e == 0;
            bg_scene *s = byte_scene(srgb ? BG_TEXTURE_SRGB : BG_TEXTURE_LINEAR, f ? BG_FILTER_LINEAR : BG_FILTER_NEAREST);
            const bg_texture_data *t = &bgi_scene_committed(s)->textures[0];
            for (int k = 0; k < 256; k++) {
                double rgba[4];
                bgi_cpu_texture_sample(t, (k + 0.5) / 256.0, 0.5, rgba);
                for (int c = 0; c < 4; c++)
                    if (rgba[c] != decoded(byte_of(k, c), c, srgb))
                        fail_msg("%s %s texel %d channel %d: %.17g, want %.17g", srgb ? "sRGB" : "linear",
                                 f ? "LINEAR" : "NEAREST", k, c, rgba[c], decoded(byte_of(k, c), c, srgb));
            }
            bg_scene_destroy(s);
        }
}

/* ---- the GPU ---- */

enum { POINTS = 1024 }; /* 256 texel centres, then points between texels */

/* Samples texture 1 of s through the production upload and lookup at POINTS points (u, 0.5) into got
 * (RGBA floats); u of point i is (i + 0.5) / 256 for i < 256, pseudo-random in [0, 1) after. */
static void gpu_samples(bg_scene *s, float *u, float *got)
{
    bg_renderer *r = util_fx.renderer;
    macs_context *ctx = util_fx.ctx;
    const bg_texture_data *t = &bgi_scene_committed(s)->textures[0];
    uint32_t seed = 12345u;
    float *uv = malloc(sizeof(float) * 4 * POINTS);
    assert_non_null(uv);
    for (int i = 0; i < POINTS; i++) {
        seed = seed * 1664525u + 1013904223u;
        u[i] = i < 256 ? (float)((i + 0.5) / 256.0) : (float)((seed >> 8) / 16777216.0);
        uv[4 * i] = u[i];
        uv[4 * i + 1] = 0.5f;
        uv[4 * i + 2] = uv[4 * i + 3] = 0.0f;
    }
    macs_texture_desc cd = {POINTS, 1, MACS_FORMAT_RGBA32F, MACS_FILTER_NEAREST, MACS_WRAP_CLAMP_TO_EDGE, uv, 0};
    macs_texture *in[3] = {NULL, NULL, NULL}, *out = util_texture(ctx, POINTS, 1, MACS_FORMAT_RGBA32F);
    assert_int_equal(macs_texture_create(ctx, &cd, &in[0]), MACS_OK);
    uint64_t bytes = 0;
    assert_int_equal(bgi_gpu_scene_texture_upload(r, t, true, &in[1], &bytes), BG_OK);
    assert_int_equal(bytes, 256 * 4);
    assert_int_equal(macs_texture_format(in[1]), MACS_FORMAT_RGBA8);
    assert_int_equal(bgi_gpu_srgb_table_upload(r, &in[2]), BG_OK);

    bg_allocator none = {0};
    gpu_text functions;
    bgi_gpu_text_init(&functions, &none);
    const char *seen[4];
    int seen_count = 0;
    assert_true(bgi_gpu_text_snippet(&functions, "bg_texture_srgb.glsl", seen, &seen_count, 4));
    assert_false(functions.failed);
    gpu_texture_mode mode = bgi_gpu_texture_mode(t, true);
    char lookup[192];
    assert_true(bgi_gpu_texture_lookup(lookup, sizeof lookup, "bg_img", "texture2D(bg_uv, macs_uv).xy", mode));
    assert_true(!t->srgb || strstr(lookup, "bg_srgb_table") != NULL);

    macs_input_desc inputs[3] = {{"bg_uv"}, {"bg_img"}, {"bg_srgb_table"}};
    macs_output_desc output = {"decoded", lookup};
    macs_pass_desc pd = {0};
    pd.functions = functions.s;
    pd.inputs = inputs;
    pd.input_count = 3;
    pd.input_textures = in;
    pd.outputs = &output;
    pd.output_count = 1;
    pd.output_textures = &out;
    macs_pass *pass = NULL;
    if (macs_pass_create(ctx, &pd, &pass) != MACS_OK)
        fail_msg("%s", macs_context_error_message(ctx));
    assert_int_equal(macs_pass_run(pass, NULL), MACS_OK);
    assert_int_equal(macs_texture_read(out, got, 0), MACS_OK);
    macs_pass_destroy(pass);
    bgi_gpu_text_free(&functions);
    for (int i = 0; i < 3; i++)
        macs_texture_destroy(in[i]);
    macs_texture_destroy(out);
    free(uv);
}

static void shader_decodes_every_byte(void **state)
{
    (void)state;
    macs_limits real, effective;
    macs_context_get_limits(util_fx.ctx, &real, &effective);
    int units = effective.max_texture_units;
    if (units < 3) {
        print_message("skipped: the pass samples 3 textures, the context has %d texture units\n", units);
        skip();
    }
    float u[POINTS], *got = malloc(sizeof(float) * 4 * POINTS);
    assert_non_null(got);
    for (int e = 0; e < 2; e++)
        for (int f = 0; f < 2; f++) {
            bool srgb = e == 0, linear = f == 1;
            const char *label = srgb ? (linear ? "sRGB LINEAR" : "sRGB NEAREST") : (linear ? "linear LINEAR" : "linear NEAREST");
            bg_scene *s = byte_scene(srgb ? BG_TEXTURE_SRGB : BG_TEXTURE_LINEAR, linear ? BG_FILTER_LINEAR : BG_FILTER_NEAREST);
            const bg_texture_data *t = &bgi_scene_committed(s)->textures[0];
            gpu_samples(s, u, got);
            double worst = 0.0;
            for (int i = 0; i < POINTS; i++) {
                double want[4];
                bgi_cpu_texture_sample(t, u[i], 0.5, want);
                for (int c = 0; c < 4; c++) {
                    double g = got[4 * i + c];
                    if (i < 256 && srgb && c < 3) {
                        /* The table's float, exactly: no pow, no rounding but the table's own. */
                        if (g != (double)(float)want[c])
                            fail_msg("%s: byte %u of channel %d decodes to %.9g on the GPU, the table's float is "
                                     "%.9g", label, byte_of(i, c), c, g, (double)(float)want[c]);
                    } else if (i < 256 || !linear) {
                        /* k / 255 as GL converts a normalised byte, which GL does not require to be
                         * correctly rounded (llvmpipe's is one float step off for some k): within
                         * two float steps of values below 1, 2^-22. */
                        if (fabs(g - want[c]) > 0x1p-22)
                            fail_msg("%s: texel %d channel %d is %.9g on the GPU, %.9g on the CPU", label, i, c, g,
                                     want[c]);
                    } else {
                        worst = fabs(g - want[c]) > worst ? fabs(g - want[c]) : worst;
                    }
                }
            }
            /* Between texels: the same decoded texels and the same weights (u * 256 - 0.5 is exact
             * in float), float arithmetic against double: a few float steps. */
            printf("%s: largest difference between texels %.3g\n", label, worst);
            if (worst > 1e-6)
                fail_msg("%s: the shader's filter differs from the CPU reference's by %.3g", label, worst);
            bg_scene_destroy(s);
        }
    free(got);
}

/* The earth scene's one texture is 256 x 128 8-bit sRGB. */
enum { EARTH_TEXELS = 256 * 128, W = 64, H = 48 };

/* Renders the earth scene on r with the plan into a float image; returns its texture bytes. */
static uint64_t render_bytes(bg_renderer *r, macs_context *ctx, bg_gpu_plan plan, float *px, const char *label)
{
    bg_scene *s = util_scene(SCENE_PAPER_EARTH);
    bg_render_settings set = plan == BG_PLAN_MULTIPASS ? util_multipass_settings() : bg_render_settings_init();
    set.gpu_plan = plan;
    bg_image img = {W, H, BG_PIXEL_RGBA32F, 0, px};
    util_render_gpu(r, ctx, s, &set, &img, label);
    bg_render_stats stats;
    bg_renderer_get_stats(r, &stats);
    assert_int_equal(stats.plan, plan);
    bg_scene_destroy(s);
    return stats.texture_bytes;
}

static void gpu_keeps_rgba8_at_4_bytes(void **state)
{
    (void)state;
    bg_renderer *r = util_fx.renderer;
    if (!bgi_gpu_srgb_table(r)) {
        print_message("skipped: the context has %d texture units, fewer than the %d the sRGB table needs\n",
                      r->limits.max_texture_units, GPU_SRGB_TABLE_MIN_UNITS);
        skip();
    }
    float *a = malloc(sizeof(float) * 4 * W * H), *b = malloc(sizeof(float) * 4 * W * H);
    assert_non_null(a);
    assert_non_null(b);
    static const bg_gpu_plan plans[] = {BG_PLAN_FUSED, BG_PLAN_MULTIPASS, BG_PLAN_FUSED_TREE};
    static const char *const names[] = {"fused", "multipass", "fused tree"};
    for (int p = 0; p < 3; p++) {
        uint64_t bytes = render_bytes(r, util_fx.ctx, plans[p], a, names[p]);
        if (bytes != (uint64_t)EARTH_TEXELS * 4 + 4096)
            fail_msg("%s: the earth texture takes %llu bytes of GPU memory, want %d (4 a texel and the table)",
                     names[p], (unsigned long long)bytes, EARTH_TEXELS * 4 + 4096);
    }

    /* Too few units for the table: decoded to RGBA32F, 16 bytes a texel, and the same image. */
    render_bytes(r, util_fx.ctx, BG_PLAN_FUSED, a, "fused with the table");
    macs_limits caps = {0};
    caps.max_texture_units = GPU_SRGB_TABLE_MIN_UNITS - 1;
    util_gpu g;
    util_gpu_open(&g, &caps);
    assert_false(bgi_gpu_srgb_table(g.renderer));
    uint64_t bytes = render_bytes(g.renderer, g.ctx, BG_PLAN_FUSED, b, "fused without the table");
    assert_int_equal(bytes, (uint64_t)EARTH_TEXELS * 16);
    double worst = 0.0;
    for (int i = 0; i < 4 * W * H; i++)
        worst = fabs((double)a[i] - b[i]) > worst ? fabs((double)a[i] - b[i]) : worst;
    printf("table against decoded upload: largest difference %.3g\n", worst);
    /* The filter sees the same floats; only the compiler's ordering of two programs may differ. */
    if (worst > 1e-6)
        fail_msg("the image with the table differs from the decoded upload's by %.3g", worst);
    util_gpu_close(&g);
    assert_int_equal(macs_headless_make_current(util_fx.headless), MACS_OK); /* the suite's context again */
    free(a);
    free(b);
}

/* A committed scene: a sphere filling the middle of the default view, emitting a 1 x 1 RGBA8 texture
 * of colour rgb (3 bytes, an odd count of texel bytes per word). */
static bg_scene *one_texel_scene(const unsigned char rgb[3])
{
    unsigned char px[4] = {rgb[0], rgb[1], rgb[2], 255};
    bg_scene *s = NULL;
    assert_int_equal(bg_scene_create(NULL, &s), BG_OK);
    bg_image img = {1, 1, BG_PIXEL_RGBA8, 0, px};
    uint32_t t = 0, m = 0, o = 0;
    assert_int_equal(bg_scene_add_texture(s, &img, NULL, &t), BG_OK);
    bg_material mat = bg_material_init();
    mat.base.reflectance = (bg_color_param){0, 0, 0, 0};
    mat.ambient = (bg_color_param){0, 0, 0, 0};
    mat.emission = (bg_color_param){1, 1, 1, t};
    assert_int_equal(bg_scene_add_material(s, &mat, &m), BG_OK);
    /* The default camera looks at the origin from 5 away. */
    assert_int_equal(bg_scene_add_sphere(s, bg_vec3_make(0, 0, 0), 1.0, m, &o), BG_OK);
    assert_int_equal(bg_scene_commit(s), BG_OK);
    return s;
}

/* The GPU copy of the textures is kept while what they hold is the same (a hash of their bytes): a
 * second scene whose one texture has the same size and modes but another colour is uploaded. */
static void another_texel_of_the_same_size_is_uploaded(void **state)
{
    (void)state;
    static const unsigned char colours[2][3] = {{255, 0, 0}, {0, 0, 255}};
    for (int i = 0; i < 2; i++) {
        bg_scene *s = one_texel_scene(colours[i]);
        unsigned char px[W * H * 4];
        bg_image img = {W, H, BG_PIXEL_RGBA8, 0, px};
        bg_render_settings set = bg_render_settings_init();
        util_render_gpu(util_fx.renderer, util_fx.ctx, s, &set, &img, "one texel");
        const unsigned char *c = px + 4 * ((size_t)(H / 2) * W + W / 2);
        if (c[0] != colours[i][0] || c[1] != colours[i][1] || c[2] != colours[i][2])
            fail_msg("scene %d: the centre is (%d, %d, %d), its texture (%d, %d, %d)", i + 1, c[0], c[1], c[2],
                     colours[i][0], colours[i][1], colours[i][2]);
        bg_scene_destroy(s);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(srgb_table_is_the_eotf),
        cmocka_unit_test(rgba8_keeps_bytes_on_the_host),
        cmocka_unit_test(cpu_decodes_every_byte),
        cmocka_unit_test(shader_decodes_every_byte),
        cmocka_unit_test(gpu_keeps_rgba8_at_4_bytes),
        cmocka_unit_test(another_texel_of_the_same_size_is_uploaded),
    };
    return cmocka_run_group_tests_name("bg_texture_precision", tests, util_gpu_group_setup, util_gpu_group_teardown);
}
