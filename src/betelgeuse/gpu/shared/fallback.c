/* The CPU reference for the pixels whose walks (the object tree's or a mesh's, in either plan) ran
 * out of steps: the shaders mark them with alpha 0 (bg_tree_short); they must still come from the
 * CPU reference, never stay black, while the rest of the frame stays on the GPU.
 * bgi_gpu_fallback_image renders them into a read-back image; the rest of this file does it for a
 * frame that ends in the caller's texture (bg_render_gpu_to_texture).
 *
 * One pass packs the marks into an RGBA8 texture of one bit per pixel (bg_tree_marks.glsl: 32
 * pixels of a row to a texel), which is all that is read back: ceil(width / 32) x height x 4 bytes,
 * 1/32 of an RGBA8 frame, 1/128 of an RGBA32F one. The CPU reference then renders each marked pixel
 * as bg_render_gpu's read-back path does, in the target's format, and each run of marked pixels in a
 * row goes up with one glTexSubImage2D (macs_texture_upload_region). Rows are the texture's, bottom
 * first; the image row of texture row y is height - 1 - y. */
#include <string.h>

#include "../../cpu/cpu_internal.h"
#include "shared.h"

enum { PIXELS_PER_TEXEL = 32 };

static bg_status mark_pass_create(bg_renderer *r, macs_texture *marks, macs_pass **out)
{
    macs_input_desc in[1] = {{"bg_frame"}};
    macs_uniform_desc u[1] = {{"bg_size", MACS_UNIFORM_VEC2, 0}};
    macs_output_desc o[1] = {{"marks", "bg_mark_texel(bg_frame, bg_size, floor(gl_FragCoord.x), macs_uv.y)"}};
    macs_texture *outs[1] = {marks};
    macs_pass_desc d;
    bgi_gpu_pass_desc_init(&d, NULL, in, NULL, 1, u, 1, o, outs, 1);
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

/* Runs the mark pass over target and reads the marks into the read-back buffer, followed by room
 * for one row of target texels; *marks and *row point into it. */
static bg_status marks_read(bg_renderer *r, gpu_marks *m, macs_texture *target, int width, int height,
                            const unsigned char **marks, unsigned char **row)
{
    bg_status st = marks_prepare(r, m, width, height);
    if (st != BG_OK)
        return st;
    int mw = 0;
    macs_texture_size(m->texture, &mw, NULL);
    size_t mark_bytes = (size_t)mw * (size_t)height * 4;
    unsigned char *buffer = bgi_gpu_read_back_buffer(r, mark_bytes + (size_t)width * 16);
    if (!buffer)
        return BG_ERR_OUT_OF_MEMORY;
    float size[2] = {(float)width, (float)height};
    macs_status ms = macs_pass_set_input(m->pass, 0, target);
    if (!ms)
        ms = macs_pass_set_uniform(m->pass, "bg_size", size);
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
    *row = buffer + mark_bytes;
    return BG_OK;
}

static bool marked(const unsigned char *mark_row, int x)
{
    return (mark_row[x / 8] >> (x % 8)) & 1u;
}

bg_status bgi_gpu_fallback_texture(bg_renderer *r, gpu_marks *m, const bg_scene_state *state,
                                          const bg_render_settings *settings, macs_texture *target, uint64_t *count)
{
    *count = 0;
    int width = 0, height = 0;
    macs_texture_size(target, &width, &height);
    const unsigned char *marks = NULL;
    unsigned char *row = NULL;
    bg_status st = marks_read(r, m, target, width, height, &marks, &row);
    if (st != BG_OK)
        return st;
    bg_pixel_format format = macs_texture_format(target) == MACS_FORMAT_RGBA8 ? BG_PIXEL_RGBA8 : BG_PIXEL_RGBA32F;
    size_t texel = format == BG_PIXEL_RGBA8 ? 4 : 16;
    /* A texel's four bytes are consecutive: byte k of a marks row holds pixels 8k .. 8k + 7. */
    size_t mark_row_bytes = (size_t)((width + PIXELS_PER_TEXEL - 1) / PIXELS_PER_TEXEL) * 4;
    for (int y = 0; y < height; y++) {
        const unsigned char *mark_row = marks + (size_t)y * mark_row_bytes;
        for (int x = 0; x < width;) {
            if (!marked(mark_row, x)) {
                x++;
                continue;
            }
            int first = x;
            for (; x < width && marked(mark_row, x); x++)
                bgi_cpu_render_texel(state, settings, &r->view.pixels, x, height - 1 - y, format,
                                    row + (size_t)(x - first) * texel);
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
                bgi_cpu_render_pixel(state, settings, view, image, stride, x, y);
                count++;
            }
        }
    }
    return count;
}
