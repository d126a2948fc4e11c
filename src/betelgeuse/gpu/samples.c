/* Several samples per pixel on the GPU (docs/shading.md 1.1): each sample is a whole frame pass of
 * whichever plan runs, its camera rays shifted by the sample's offset from the pixel centre, into a
 * float texture, summed on the GPU in the order the samples are taken (bgi_sample_order,
 * accumulate.c), so the sum is deterministic and the plans need no accumulation of their own, and
 * read back once. A pixel whose walks ran out of steps in any sample is the CPU reference's for all
 * of them (shared/fallback.c): the sum's alpha marks it, the resolve writes that mark into what it
 * reads back (alpha 0), and the host renders it there, so the marks cost no read-back of their own;
 * into an RGBA8 texture one read of the packed marks finds them. The caller's image or texture is
 * written only after the last pass, so a cancelled or failed frame leaves it untouched. */
#include <string.h>

#include "../common/alloc.h"
#include "../common/encoding.h"
#include "driver.h"

void bgi_gpu_view_for_sample(const bgi_render_view *view, int k, gpu_view *out)
{
    /* The k-th sample taken is sample s of the pattern (docs/shading.md 1.1); the pass's view keeps
     * k, as the CPU's does, and its uniforms and the tree plan's CPU pixels take s from it. */
    double px, py;
    bgi_sample_position(view->samples, bgi_sample_order(view->samples, k), &px, &py);
    out->pixels = *view;
    out->pixels.sample_first = k;
    out->pixels.sample_count = 1;
    /* gl_FragCoord is the window pixel's centre, GL rows bottom-up: the frame's GL row of window row
     * 0 is frame_height - y0 - height, and the doc's y + py is GL's row + (1 - py). Every term is a
     * multiple of 2^-BGI_SAMPLE_BITS below 2^14: exact in float. */
    out->shift[0] = (float)((double)view->x0 + (px - 0.5));
    out->shift[1] = (float)((double)(view->frame_height - view->y0 - view->height) + (0.5 - py));
}

bg_status bgi_gpu_samples_write(bg_renderer *r, const bg_render_settings *settings, const gpu_frame_out *out,
                                const float *sum, int samples, const bg_scene_state *state,
                                const bgi_render_view *view, uint64_t *fallback)
{
    int w = out->width, h = out->height;
    bool as_float = out->as_float;
    size_t texel = as_float ? 16 : 4;
    void *scratch = NULL;
    if (!out->image) {
        scratch = bgi_alloc(&r->allocator, (size_t)w * (size_t)h * texel);
        if (!scratch)
            return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for the averaged samples (%zu bytes)",
                                (size_t)w * (size_t)h * texel);
    }
    float whole = (float)samples - 0.5f;
    for (int y = 0; y < h; y++) {
        /* sum holds the frame's rows top-down, as the image read back has them. */
        const float *src = sum + (size_t)y * (size_t)w * 4;
        unsigned char *dst = out->image ? (unsigned char *)out->image->pixels + (size_t)y * out->stride
                                        : (unsigned char *)scratch + (size_t)(h - 1 - y) * (size_t)w * texel;
        for (int x = 0; x < w; x++) {
            const float *px = src + (size_t)x * 4;
            float cpu[4];
            if (state && px[3] < whole) {
                bgi_gpu_fallback_sum(state, settings, view, x, y, view->sample_first, view->sample_count, cpu);
                px = cpu;
                ++*fallback;
            }
            bgi_gpu_mean_texel(px, samples, as_float, settings->encoding, dst + (size_t)x * texel);
        }
    }
    if (out->image)
        return BG_OK;
    macs_status ms = macs_texture_upload(out->texture, scratch, 0);
    bgi_free(&r->allocator, scratch);
    return ms ? bgi_gpu_fail_macs(r, ms, "uploading the averaged samples") : BG_OK;
}

bg_status bgi_gpu_samples_render(bg_renderer *r, const bg_scene *scene, const bg_scene_state *state,
                                 const bg_render_settings *settings, const gpu_frame_out *out,
                                 const bgi_render_view *view)
{
    int w = out->width, h = out->height, n = view->samples;
    /* A sum of another size (the last tile of a tiled image is smaller) goes once the new one has
     * made its add pass, which then takes the old one's program from MACS's cache. */
    bg_accumulation *old = NULL;
    if (r->frame_sum && !bgi_gpu_accumulation_fits(r->frame_sum, w, h)) {
        old = r->frame_sum;
        r->frame_sum = NULL;
    }
    if (!r->frame_sum)
        r->frame_sum = bgi_gpu_accumulation_new(r, w, h);
    bg_accumulation *a = r->frame_sum;
    /* RGBA8 takes the exact bytes on the GPU: no float sum comes back. */
    float *sum = out->as_float ? bgi_alloc(&r->allocator, (size_t)w * (size_t)h * 16) : NULL;
    if (!a || (out->as_float && !sum)) {
        bg_accumulation_destroy(old);
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for %d samples (%zu bytes of host buffer)", n,
                            (size_t)w * (size_t)h * 16);
    }
    bg_status st = bgi_gpu_accumulate_samples(r, scene, state, settings, view, a, 0, n,
                                              out->image ? "image" : "texture", true);
    /* Whether a pass could leave marks in the sum: only then are they looked for. */
    bool marks = r->marks_left;
    uint64_t fallback = 0;
    if (st == BG_OK && !out->as_float && out->image) {
        st = bgi_gpu_accumulation_read_bytes(r, a, settings->encoding, out->image->pixels, out->stride, !marks);
        if (st == BG_OK && marks)
            fallback = bgi_gpu_fallback_image(state, settings, view, out->image, out->stride);
    } else if (st == BG_OK && !out->as_float) {
        st = bgi_gpu_accumulation_bytes(r, a, settings->encoding, out->texture);
        if (st == BG_OK && marks)
            st = bgi_gpu_fallback_texture(r, &r->frame_marks, state, settings, view, out->texture, &fallback);
    } else if (st == BG_OK) {
        st = bgi_gpu_accumulation_read(r, a, sum);
    }
    if (st == BG_OK && out->as_float)
        st = bgi_gpu_samples_write(r, settings, out, sum, n, marks ? state : NULL, view, &fallback);
    if (st == BG_OK)
        r->stats.fallback_pixels = fallback;
    if (st == BG_OK)
        bgi_render_progress(settings, 1.0);
    bg_accumulation_destroy(old);
    bgi_free(&r->allocator, sum);
    return st;
}
