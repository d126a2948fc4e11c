/* The CPU reference for the pixels whose walks (the object tree's or a mesh's, in either plan) ran
 * out of steps: the shaders mark them with alpha 0 (bg_tree_short); they must still come from the
 * CPU reference, never stay black, while the rest of the frame stays on the GPU.
 * bgi_gpu_fallback_image renders them into a read-back image; the rest of this file does it for a
 * frame that ends in a texture (bg_render_gpu_to_texture, the accumulation).
 *
 * With several samples a marked pixel is the CPU reference's for all of them, whichever sample ran
 * out: the float sum of its one-sample texels in the order taken, as the accumulation's add pass
 * sums them (bgi_gpu_fallback_sum), then the mean and encoding of samples.c. So the marks of the
 * sample passes need not come back one by one: the sum's alpha counts the samples that finished, and
 * the frame's end finds the pixels below the count, once (docs/gpu_pipeline.md, "GL work per frame").
 *
 * One pass packs the marks into an RGBA8 texture of one bit per pixel (bg_tree_marks.glsl: 32
 * pixels of a row to a texel), which is all that is read back: ceil(width / 32) x height x 4 bytes,
 * 1/32 of an RGBA8 frame, 1/128 of an RGBA32F one. The CPU reference then renders each marked pixel
 * as bg_render_gpu's read-back path does, in the target's format, and each run of marked pixels in a
 * row goes up with one glTexSubImage2D (macs_texture_upload_region). Rows are the texture's, bottom
 * first; the image row of texture row y is height - 1 - y. */
#include <string.h>

#include "../../common/encoding.h"
#include "../../cpu/cpu_internal.h"
#include "shared.h"

enum { PIXELS_PER_TEXEL = 32 };

static bg_status mark_pass_create(bg_renderer *r, macs_texture *marks, macs_pass **out)
{
    macs_input_desc in[1] = {{"bg_frame"}};
    macs_uniform_desc u[2] = {{"bg_size", MACS_UNIFORM_VEC2, 0}, {"bg_whole", MACS_UNIFORM_FLOAT, 0}};
    macs_output_desc o[1] = {{"marks", "bg_mark_texel(bg_frame, bg_size, bg_whole, floor(gl_FragCoord.x), macs_uv.y)"}};
    macs_texture *outs[1] = {marks};
    macs_pass_desc d;
    bgi_gpu_pass_desc_init(&d, NULL, in, NULL, 1, u, 2, o, outs, 1);
    const char *files[] = {"bg_tree_marks.glsl", NULL};
    return bgi_gpu_pass_create(r, "tree marks pass", files, NULL, &d, out);
}

/* Makes the marks texture and its pass fit a width x height frame. The new pass is made before the
 * old one goes, so that MACS's program cache hands the program over instead of compiling it again. */
static bg_status marks_prepare(bg_renderer *r, gpu_marks *m, int width, int height)
{
    int mw = (width + PIXELS_PER_TEXEL - 1) / PIXELS_PER_TEXEL, have_w = 0, have_h = 0;
    macs_texture_size(m->texture, &have_w, &have_h);
    if (m->texture && m->pass && have_w == mw && have_h == height)
        return BG_OK;
    macs_texture *marks = NULL;
    macs_pass *pass = NULL;
    bg_status st = bgi_gpu_texture_ensure(r, mw, height, MACS_FORMAT_RGBA8, &marks, "tree marks texture");
    if (st == BG_OK)
        st = mark_pass_create(r, marks, &pass);
    if (st != BG_OK) {
        macs_texture_destroy(marks);
        return st;
    }
    bgi_gpu_marks_release(m);
    m->texture = marks;
    m->pass = pass;
    return BG_OK;
}

bg_status bgi_gpu_marks_read(bg_renderer *r, gpu_marks *m, macs_texture *target, float whole, size_t spare,
                             const unsigned char **marks, unsigned char **room)
{
    int width = 0, height = 0;
    macs_texture_size(target, &width, &height);
    bg_status st = marks_prepare(r, m, width, height);
    if (st != BG_OK)
        return st;
    size_t mark_bytes = bgi_gpu_marks_row_bytes(width) * (size_t)height;
    unsigned char *buffer = bgi_gpu_read_back_buffer(r, mark_bytes + spare);
    if (!buffer)
        return BG_ERR_OUT_OF_MEMORY;
    float size[2] = {(float)width, (float)height};
    macs_status ms = macs_pass_set_input(m->pass, 0, target);
    if (!ms)
        ms = macs_pass_set_uniform(m->pass, "bg_size", size);
    if (!ms)
        ms = macs_pass_set_uniform(m->pass, "bg_whole", &whole);
    if (!ms)
        ms = macs_pass_run(m->pass, NULL);
    /* The pass keeps no hold on the caller's texture between frames. */
    if (!ms)
        ms = macs_pass_set_input(m->pass, 0, NULL);
    if (!ms)
        ms = macs_texture_read(m->texture, buffer, 0);
    if (ms)
        return bgi_gpu_fail_macs(r, ms, "finding the pixels the tree walks left");
    *marks = buffer;
    *room = buffer + mark_bytes;
    return BG_OK;
}

size_t bgi_gpu_marks_row_bytes(int width)
{
    return (size_t)((width + PIXELS_PER_TEXEL - 1) / PIXELS_PER_TEXEL) * 4;
}

/* A texel's four bytes are consecutive: byte k of a marks row holds pixels 8k .. 8k + 7. */
bool bgi_gpu_marked(const unsigned char *mark_row, int x)
{
    return (mark_row[x / 8] >> (x % 8)) & 1u;
}

void bgi_gpu_fallback_sum(const bg_scene_state *state, const bg_render_settings *settings,
                          const bgi_render_view *view, int x, int y, int first, int count, float sum[4])
{
    bgi_render_view one = *view;
    one.sample_count = 1;
    for (int k = first; k < first + count; k++) {
        float texel[4];
        one.sample_first = k;
        bgi_cpu_render_texel(state, settings, &one, x, y, BG_PIXEL_RGBA32F, texel);
        /* The add pass's float additions, in its order: the first sample of a sum is kept as it is. */
        for (int i = 0; i < 4; i++)
            sum[i] = k == 0 ? texel[i] : sum[i] + texel[i];
    }
}

void bgi_gpu_mean_texel(const float sum[4], int samples, bool as_float, bg_output_encoding encoding, void *texel)
{
    float rgb[3];
    for (int i = 0; i < 3; i++)
        rgb[i] = sum[i] / (float)samples;
    if (as_float) {
        float px[4] = {rgb[0], rgb[1], rgb[2], 1.0f};
        memcpy(texel, px, sizeof px);
    } else {
        unsigned char *px = texel;
        for (int i = 0; i < 3; i++)
            px[i] = bgi_encode_channel(rgb[i], encoding);
        px[3] = 255;
    }
}

/* Pixel (x, y) (image rows, top first) of the view's frame as the CPU reference gives it in format:
 * one sample as bg_render_cpu renders it, several as the GPU's sum of the CPU's samples. */
static void cpu_texel(const bg_scene_state *state, const bg_render_settings *settings, const bgi_render_view *view,
                      int x, int y, bg_pixel_format format, void *texel)
{
    if (view->sample_count == 1) {
        bgi_cpu_render_texel(state, settings, view, x, y, format, texel);
        return;
    }
    float sum[4];
    bgi_gpu_fallback_sum(state, settings, view, x, y, view->sample_first, view->sample_count, sum);
    bgi_gpu_mean_texel(sum, view->sample_count, format == BG_PIXEL_RGBA32F, settings->encoding, texel);
}

bg_status bgi_gpu_fallback_texture(bg_renderer *r, gpu_marks *m, const bg_scene_state *state,
                                   const bg_render_settings *settings, const bgi_render_view *view,
                                   macs_texture *target, uint64_t *count)
{
    *count = 0;
    int width = 0, height = 0;
    macs_texture_size(target, &width, &height);
    const unsigned char *marks = NULL;
    unsigned char *row = NULL;
    bg_status st = bgi_gpu_marks_read(r, m, target, 1.0f, (size_t)width * 16, &marks, &row);
    if (st != BG_OK)
        return st;
    bg_pixel_format format = macs_texture_format(target) == MACS_FORMAT_RGBA8 ? BG_PIXEL_RGBA8 : BG_PIXEL_RGBA32F;
    size_t texel = format == BG_PIXEL_RGBA8 ? 4 : 16;
    size_t mark_row_bytes = bgi_gpu_marks_row_bytes(width);
    for (int y = 0; y < height; y++) {
        const unsigned char *mark_row = marks + (size_t)y * mark_row_bytes;
        for (int x = 0; x < width;) {
            if (!bgi_gpu_marked(mark_row, x)) {
                x++;
                continue;
            }
            int first = x;
            for (; x < width && bgi_gpu_marked(mark_row, x); x++)
                cpu_texel(state, settings, view, x, height - 1 - y, format, row + (size_t)(x - first) * texel);
            macs_status ms = macs_texture_upload_region(target, first, y, x - first, 1, row, 0);
            if (ms)
                return bgi_gpu_fail_macs(r, ms, "uploading the CPU reference's pixels");
            *count += (uint64_t)(x - first);
        }
    }
    return BG_OK;
}

void bgi_gpu_marks_release(gpu_marks *m)
{
    macs_pass_destroy(m->pass);
    macs_texture_destroy(m->texture);
    m->pass = NULL;
    m->texture = NULL;
}

uint64_t bgi_gpu_fallback_image(const bg_scene_state *state, const bg_render_settings *settings,
                                 const bgi_render_view *view, const bg_image *image, size_t stride)
{
    uint64_t count = 0;
    bool as_float = image->format == BG_PIXEL_RGBA32F;
    for (int y = 0; y < image->height; y++) {
        const unsigned char *row = (const unsigned char *)image->pixels + (size_t)y * stride;
        for (int x = 0; x < image->width; x++) {
            bool marked;
            if (as_float) {
                float alpha, one = 1.0f;
                memcpy(&alpha, row + (size_t)x * 16 + 12, sizeof alpha);
                marked = alpha < 0.5f;
                memcpy((unsigned char *)row + (size_t)x * 16 + 12, &one, sizeof one);
            } else {
                marked = row[(size_t)x * 4 + 3] == 0;
            }
            if (marked) {
                cpu_texel(state, settings, view, x, y, image->format, (unsigned char *)row + (size_t)x * (as_float ? 16 : 4));
                count++;
            }
        }
    }
    return count;
}
