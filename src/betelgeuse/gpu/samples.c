/* Several samples per pixel on the GPU (docs/shading.md 1.1): each sample is a whole frame pass of
 * whichever plan runs, its camera rays shifted by the sample's offset from the pixel centre, read
 * back as linear float and summed on the host in sample order, so the sum is deterministic and the
 * plans need no accumulation of their own. The tree plan's CPU pixels of a pass are that sample's
 * (bgi_cpu_render_texel renders r->view's one sample). The caller's image or texture is written
 * only after the last pass, so a cancelled or failed frame leaves it untouched. */
#include <string.h>

#include "../common/alloc.h"
#include "../common/encoding.h"
#include "driver.h"

void bgi_gpu_view_for_sample(const bgi_render_view *view, int s, gpu_view *out)
{
    double px, py;
    bgi_sample_position(view->samples, s, &px, &py);
    out->pixels = *view;
    out->pixels.sample_first = s;
    out->pixels.sample_count = 1;
    /* gl_FragCoord is the window pixel's centre, GL rows bottom-up: the frame's GL row of window row
     * 0 is frame_height - y0 - height, and the doc's y + py is GL's row + (1 - py). Every term is a
     * multiple of 2^-BGI_SAMPLE_BITS below 2^14: exact in float. */
    out->shift[0] = (float)((double)view->x0 + (px - 0.5));
    out->shift[1] = (float)((double)(view->frame_height - view->y0 - view->height) + (0.5 - py));
}

/* The average into the caller's image (rows top-down) or texture (rows bottom-up). */
static bg_status write_out(bg_renderer *r, const bg_render_settings *settings, const gpu_frame_out *out,
                           const float *sum, int samples, void *scratch)
{
    int w = out->width, h = out->height;
    bool as_float = out->as_float;
    size_t texel = as_float ? 16 : 4;
    for (int y = 0; y < h; y++) {
        /* sum holds the frame's rows top-down, as the image read back has them. */
        const float *src = sum + (size_t)y * (size_t)w * 4;
        unsigned char *dst = out->image ? (unsigned char *)out->image->pixels + (size_t)y * out->stride
                                        : (unsigned char *)scratch + (size_t)(h - 1 - y) * (size_t)w * texel;
        for (int x = 0; x < w; x++) {
            float rgb[3];
            for (int i = 0; i < 3; i++)
                rgb[i] = src[(size_t)x * 4 + (size_t)i] / (float)samples;
            if (as_float) {
                float px[4] = {rgb[0], rgb[1], rgb[2], 1.0f};
                memcpy(dst + (size_t)x * 16, px, sizeof px);
            } else {
                for (int i = 0; i < 3; i++)
                    dst[(size_t)x * 4 + (size_t)i] = bgi_encode_channel(rgb[i], settings->encoding);
                dst[(size_t)x * 4 + 3] = 255;
            }
        }
    }
    if (out->image)
        return BG_OK;
    macs_status ms = macs_texture_upload(out->texture, scratch, 0);
    return ms ? bgi_gpu_fail_macs(r, ms, "uploading the averaged samples") : BG_OK;
}

bg_status bgi_gpu_samples_render(bg_renderer *r, const bg_scene *scene, const bg_scene_state *state,
                                 const bg_render_settings *settings, const gpu_frame_out *out,
                                 const bgi_render_view *view)
{
    int w = out->width, h = out->height, n = view->samples;
    size_t bytes = (size_t)w * (size_t)h * 16;
    /* One pass's float image and the running sum; the sum's buffer later holds a texture's texels. */
    float *pass = bgi_alloc(&r->allocator, bytes), *sum = bgi_alloc(&r->allocator, bytes);
    void *scratch = out->texture ? bgi_alloc(&r->allocator, bytes) : NULL;
    if (!pass || !sum || (out->texture && !scratch)) {
        bgi_free(&r->allocator, pass);
        bgi_free(&r->allocator, sum);
        bgi_free(&r->allocator, scratch);
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for %d samples (%zu bytes of host buffers)",
                            n, 3 * bytes);
    }
    bg_image image = {w, h, BG_PIXEL_RGBA32F, (size_t)w * 16, pass};
    gpu_frame_out one = {&image, image.stride, NULL, w, h, true};
    bg_status st = BG_OK;
    uint64_t fallback = 0;
    int compiled = 0;
    size_t floats = (size_t)w * (size_t)h * 4;
    for (int s = 0; s < n && st == BG_OK; s++) {
        bgi_gpu_view_for_sample(view, s, &r->view);
        st = bgi_gpu_plan_render(r, scene, state, settings, &one);
        if (st != BG_OK)
            break;
        fallback += r->stats.fallback_pixels;
        compiled += r->stats.programs_compiled;
        for (size_t i = 0; i < floats; i++)
            sum[i] = s == 0 ? pass[i] : sum[i] + pass[i];
        if (s + 1 < n && !bgi_render_progress(settings, (double)(s + 1) / n))
            st = bgi_gpu_fail(r, BG_ERR_CANCELLED, "cancelled by settings.progress after %d of %d sample passes; "
                              "the pixels of this %s (of this tile, when tiled) are untouched", s + 1, n,
                              out->image ? "image" : "texture");
    }
    if (st == BG_OK) {
        r->stats.fallback_pixels = fallback;
        r->stats.programs_compiled = compiled;
        st = write_out(r, settings, out, sum, n, scratch);
    }
    if (st == BG_OK)
        bgi_render_progress(settings, 1.0);
    bgi_free(&r->allocator, pass);
    bgi_free(&r->allocator, sum);
    bgi_free(&r->allocator, scratch);
    return st;
}
