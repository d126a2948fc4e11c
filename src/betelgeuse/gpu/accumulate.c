/* Progressive accumulation on the GPU (docs/gpu_pipeline.md, "Accumulation"): a frame's running sum
 * of samples in RGBA32F textures, each sample one pass of whichever plan runs into a float texture
 * and then added by a MACS pass, sum_new = sum_old + sample, ping-ponging between textures (a pass
 * may not read its own output, and float blending is not in GL 2.1). The adds are the same float
 * additions in the same order as the host's sum of bg_render_gpu before it, so the sum is bit for bit
 * that sum (IEEE single precision, round to nearest, on every GL that honours GLSL's float; llvmpipe
 * does). samples.c renders bg_render_gpu's multi-sample frames through this too, with one read-back
 * at the end instead of one per sample.
 *
 * A call that fails or is cancelled leaves the sum and its count as they were: the samples of a call
 * go into the two textures that do not hold the sum, and only a finished call makes its last one the
 * sum.
 *
 * Pixels whose walks run out of steps (shared/fallback.c): a sample pass leaves them marked (alpha 0)
 * in its float output, so the sum's alpha counts the samples that finished, and nothing is read back
 * per sample. Such a pixel is the CPU reference's for every sample of the sum, whichever ran out: its
 * sum is the float sum of the CPU's samples in the order taken (bgi_gpu_fallback_sum), what the add
 * pass would have summed, so the image does not depend on how the samples were split among calls.
 * bg_render_gpu's frame (samples.c) finds those pixels once at its end, in the resolve it reads back.
 * An accumulation is resolved later, without the scene, so each call of bg_render_gpu_accumulate ends
 * by reading the marks once and writing the CPU's sums into the sum; the accumulation keeps the CPU's
 * pixels and their sums (owned), so that a later call adds its samples to them (and renders the
 * earlier samples of a pixel that runs out first in it). */
#include <string.h>

#include "../common/alloc.h"
#include "../common/render_settings.h"
#include "driver.h"

#define FN_ACCUMULATE "bg_render_gpu_accumulate"

struct bg_accumulation {
    bg_renderer *renderer;
    bg_allocator allocator; /* the renderer's, kept for destroy */
    int width, height;
    int pattern;            /* settings.samples of the samples in the sum: the pattern they belong to */
    int samples;            /* samples in the sum */
    int current;            /* sum[current] is the sum when samples > 0 */
    macs_texture *sum[3];   /* the third only once samples are added to an existing sum */
    macs_texture *sample;   /* one sample's radiance */
    macs_pass *add;
    macs_pass *resolve;     /* into a texture of resolve_format */
    macs_format resolve_format;
    gpu_exact_bytes *exact; /* the RGBA8 resolve, bit for bit the host's (exact_bytes.c) */
    macs_texture *bytes;    /* its target when the bytes go to a host image */
    gpu_marks marks;        /* of the sum's run-out pixels (shared/fallback.c) */
    size_t owned;           /* pixels the CPU reference renders, in texel order (y * width + x,
                             * rows bottom first), with their sums */
    uint32_t *owned_index;
    float *owned_sum;
};

bool bgi_gpu_accumulation_fits(const bg_accumulation *a, int width, int height)
{
    return a->width == width && a->height == height;
}

bg_accumulation *bgi_gpu_accumulation_new(bg_renderer *r, int width, int height)
{
    bg_accumulation *a = bgi_alloc(&r->allocator, sizeof *a);
    if (!a)
        return NULL;
    memset(a, 0, sizeof *a);
    a->renderer = r;
    a->allocator = r->allocator;
    a->width = width;
    a->height = height;
    return a;
}

void bg_accumulation_destroy(bg_accumulation *a)
{
    if (!a)
        return;
    for (int i = 0; i < 3; i++)
        macs_texture_destroy(a->sum[i]);
    macs_texture_destroy(a->sample);
    macs_pass_destroy(a->add);
    macs_pass_destroy(a->resolve);
    macs_texture_destroy(a->bytes);
    bgi_gpu_exact_bytes_destroy(a->exact, &a->allocator);
    bgi_gpu_marks_release(&a->marks);
    bgi_free(&a->allocator, a->owned_index);
    bgi_free(&a->allocator, a->owned_sum);
    bg_allocator allocator = a->allocator;
    bgi_free(&allocator, a);
}

bg_status bg_accumulation_create(bg_renderer *renderer, int width, int height, bg_accumulation **out)
{
    bg_renderer *r = renderer;
    if (!r)
        return BG_ERR_INVALID_ARGUMENT;
    r->entry = "bg_accumulation_create";
    if (!out)
        return bgi_gpu_fail(r, BG_ERR_INVALID_ARGUMENT, "out is NULL");
    *out = NULL;
    if (width < 1 || height < 1 || width > BG_MAX_IMAGE_SIDE || height > BG_MAX_IMAGE_SIDE)
        return bgi_gpu_fail(r, BG_ERR_INVALID_ARGUMENT, "size %dx%d is outside [1, %d] per side", width, height,
                            BG_MAX_IMAGE_SIDE);
    int max = r->limits.max_texture_size;
    if (width > max || height > max)
        return bgi_gpu_fail(r, BG_ERR_LIMIT, "size %dx%d exceeds the GL texture size limit %d", width, height, max);
    *out = bgi_gpu_accumulation_new(r, width, height);
    return *out ? BG_OK : bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for the accumulation");
}

int bg_accumulation_samples(const bg_accumulation *a)
{
    return a ? a->samples : 0;
}

/* The add pass: sum_new = sum_old + sample, or the sample alone for the first one (bg_first), as the
 * host sum began. Its inputs and output are bound at each run. */
static bg_status add_prepare(bg_renderer *r, bg_accumulation *a, int out_index)
{
    if (a->add)
        return BG_OK;
    macs_input_desc in[2] = {{"bg_sum"}, {"bg_sample"}};
    macs_uniform_desc u[1] = {{"bg_first", MACS_UNIFORM_BOOL, 0}};
    macs_output_desc o[1] = {{"sum", "bg_first ? texture2D(bg_sample, macs_uv) : "
                                     "texture2D(bg_sum, macs_uv) + texture2D(bg_sample, macs_uv)"}};
    macs_texture *outs[1] = {a->sum[out_index]};
    macs_pass_desc d;
    bgi_gpu_pass_desc_init(&d, NULL, in, NULL, 2, u, 1, o, outs, 1);
    return bgi_gpu_pass_create(r, "accumulation add pass", NULL, NULL, &d, &a->add);
}

static bg_status add_run(bg_renderer *r, bg_accumulation *a, int from, int to)
{
    int first = from < 0;
    /* The last run's input may be this run's output: unbind it first, as MACS refuses a texture as both. */
    macs_status ms = macs_pass_set_input(a->add, 0, NULL);
    if (!ms)
        ms = macs_pass_set_output(a->add, 0, a->sum[to]);
    if (!ms)
        ms = macs_pass_set_input(a->add, 0, a->sum[first ? (to == 0 ? 1 : 0) : from]);
    if (!ms)
        ms = macs_pass_set_input(a->add, 1, a->sample);
    if (!ms)
        ms = macs_pass_set_uniform(a->add, "bg_first", &first);
    if (!ms)
        ms = macs_pass_run(a->add, NULL);
    return ms ? bgi_gpu_fail_macs(r, ms, "the accumulation's add pass") : BG_OK;
}

/* The end of a call of bg_render_gpu_accumulate that added samples [first, first + count) into sum:
 * the pixels the CPU reference renders are those the accumulation owned already and those whose
 * sample ran out in this call (alpha below first + count); each gets the CPU's sum, uploaded into
 * sum with one upload per run of a row. The new list replaces the old one only when all went up. */
static bg_status own_cpu_pixels(bg_renderer *r, bg_accumulation *a, const bg_scene_state *state,
                                const bg_render_settings *settings, const bgi_render_view *view, int first, int count,
                                macs_texture *sum, uint64_t *pixels)
{
    int w = a->width, h = a->height, total = first + count;
    size_t old = first > 0 ? a->owned : 0;
    const unsigned char *marks = NULL;
    unsigned char *room = NULL;
    bg_status st = bgi_gpu_marks_read(r, &a->marks, sum, (float)total, 0, &marks, &room);
    if (st != BG_OK)
        return st;
    size_t n = old, row_bytes = bgi_gpu_marks_row_bytes(w);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            n += bgi_gpu_marked(marks + (size_t)y * row_bytes, x);
    uint32_t *index = bgi_alloc(&r->allocator, (n ? n : 1) * sizeof *index);
    float *sums = bgi_alloc(&r->allocator, (n ? n : 1) * 16);
    if (!index || !sums) {
        bgi_free(&r->allocator, index);
        bgi_free(&r->allocator, sums);
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for the CPU reference's pixels (%zu)", n);
    }
    /* Merge the old list with this call's marks, both in texel order; a pixel in both counts once. */
    size_t k = 0, j = 0;
    for (int y = 0; y < h; y++) {
        const unsigned char *mark_row = marks + (size_t)y * row_bytes;
        for (int x = 0; x < w; x++) {
            uint32_t i = (uint32_t)y * (uint32_t)w + (uint32_t)x;
            bool had = j < old && a->owned_index[j] == i;
            if (!had && !bgi_gpu_marked(mark_row, x))
                continue;
            float *s = sums + k * 4;
            if (had)
                memcpy(s, a->owned_sum + j++ * 4, 16);
            /* An owned pixel adds this call's samples; a new one takes all of its samples. */
            bgi_gpu_fallback_sum(state, settings, view, x, h - 1 - y, had ? first : 0, had ? count : total, s);
            index[k++] = i;
        }
    }
    macs_status ms = MACS_OK;
    for (size_t b = 0; b < k && !ms;) {
        size_t e = b + 1;
        while (e < k && index[e] == index[e - 1] + 1 && index[e] % (uint32_t)w != 0)
            e++;
        ms = macs_texture_upload_region(sum, (int)(index[b] % (uint32_t)w), (int)(index[b] / (uint32_t)w), (int)(e - b),
                                        1, sums + b * 4, 0);
        b = e;
    }
    if (ms) {
        bgi_free(&r->allocator, index);
        bgi_free(&r->allocator, sums);
        return bgi_gpu_fail_macs(r, ms, "uploading the CPU reference's sums");
    }
    bgi_free(&r->allocator, a->owned_index);
    bgi_free(&r->allocator, a->owned_sum);
    a->owned_index = index;
    a->owned_sum = sums;
    a->owned = k;
    *pixels = k;
    return BG_OK;
}

bg_status bgi_gpu_accumulate_samples(bg_renderer *r, const bg_scene *scene, const bg_scene_state *state,
                                     const bg_render_settings *settings, const bgi_render_view *view,
                                     bg_accumulation *a, int first, int count, const char *untouched,
                                     bool keep_marks)
{
    int n = view->samples;
    /* The call's samples go into the textures that do not hold the sum, so that a failure or a cancel
     * leaves it: two of them when starting afresh, the other two of three when adding to a sum. */
    int keep = first > 0 ? a->current : -1;
    int work[2], k = 0;
    for (int i = 0; i < 3 && k < 2; i++)
        if (i != keep)
            work[k++] = i;
    bg_status st = BG_OK;
    for (int i = 0; i < 2 && st == BG_OK; i++)
        st = bgi_gpu_texture_ensure(r, a->width, a->height, MACS_FORMAT_RGBA32F, &a->sum[work[i]],
                                    "accumulation sum texture");
    if (st == BG_OK)
        st = bgi_gpu_texture_ensure(r, a->width, a->height, MACS_FORMAT_RGBA32F, &a->sample, "accumulation sample texture");
    if (st == BG_OK)
        st = add_prepare(r, a, work[0]);
    gpu_frame_out one = {NULL, 0, a->sample, a->width, a->height, true};
    uint64_t fallback = 0;
    int compiled = 0, from = keep, to = -1;
    r->marks_deferred = true;
    r->marks_left = false;
    for (int i = 0; i < count && st == BG_OK; i++) {
        int s = first + i;
        bgi_gpu_view_for_sample(view, s, &r->view);
        st = bgi_gpu_plan_render(r, scene, state, settings, &one);
        if (st != BG_OK)
            break;
        fallback += r->stats.fallback_pixels;
        compiled += r->stats.programs_compiled;
        to = work[i % 2];
        st = add_run(r, a, from, to);
        from = to;
        if (st == BG_OK && s + 1 < n && !bgi_render_progress(settings, (double)(s + 1) / n))
            st = untouched ? bgi_gpu_fail(r, BG_ERR_CANCELLED, "cancelled by settings.progress after %d of %d sample "
                                          "passes; the pixels of this %s (of this tile, when tiled) are untouched",
                                          s + 1, n, untouched)
                           : bgi_gpu_fail(r, BG_ERR_CANCELLED, "cancelled by settings.progress after %d of the %d "
                                          "samples of this call; the accumulation keeps its %d samples", i + 1,
                                          count, a->samples);
    }
    r->marks_deferred = false;
    /* The owned pixels of the accumulation entry (the marks of bg_render_gpu's frame stay in the sum
     * for samples.c); none where no pass could mark one and none were owned before. */
    bool own = !keep_marks && (r->marks_left || (first > 0 && a->owned > 0));
    if (st == BG_OK && own)
        st = own_cpu_pixels(r, a, state, settings, view, first, count, a->sum[to], &fallback);
    if (st != BG_OK)
        return st;
    if (!keep_marks && !own) {
        bgi_free(&r->allocator, a->owned_index);
        bgi_free(&r->allocator, a->owned_sum);
        a->owned_index = NULL;
        a->owned_sum = NULL;
        a->owned = 0;
    }
    r->stats.fallback_pixels = fallback;
    r->stats.programs_compiled = compiled;
    a->current = to;
    a->samples = first + count;
    a->pattern = n;
    return BG_OK;
}

static bg_status accumulate(bg_renderer *renderer, bg_scene *scene, const bg_render_settings *settings,
                            bg_accumulation *accumulation, int first, int count)
{
    bg_renderer *r = renderer;
    bg_accumulation *a = accumulation;
    if (!r)
        return BG_ERR_INVALID_ARGUMENT;
    r->entry = FN_ACCUMULATE;
    if (!scene || !settings || !a)
        return bgi_gpu_fail(r, BG_ERR_INVALID_ARGUMENT, "%s is NULL",
                            !scene ? "scene" : !settings ? "settings" : "accumulation");
    if (a->renderer != r)
        return bgi_gpu_fail(r, BG_ERR_INVALID_ARGUMENT, "accumulation was made by another renderer");
    char message[256];
    bg_status st = bgi_render_settings_check(settings, FN_ACCUMULATE, message, sizeof message);
    if (st != BG_OK)
        return bgi_gpu_fail_checked(r, st, message);
    bgi_render_view view;
    st = bgi_render_view_make(settings, a->width, a->height, FN_ACCUMULATE, &view, message, sizeof message);
    if (st != BG_OK)
        return bgi_gpu_fail_checked(r, st, message);
    int n = view.samples;
    if (count < 1 || first < 0 || first > n - count)
        /* The end in 64 bits: first + count of two large ints would overflow in the message. */
        return bgi_gpu_fail(r, BG_ERR_INVALID_ARGUMENT, "samples [first, first + count) = [%d, %lld) are not within "
                            "the %d of settings.samples", first, (long long)first + count, n);
    if (first > 0 && first != a->samples)
        return bgi_gpu_fail(r, BG_ERR_INVALID_ARGUMENT, "first = %d, but the accumulation holds %d samples (0 starts "
                            "over)", first, a->samples);
    if (first > 0 && n != a->pattern)
        return bgi_gpu_fail(r, BG_ERR_INVALID_ARGUMENT, "settings.samples = %d, but the accumulation's samples are "
                            "of the pattern of %d (first = 0 starts over)", n, a->pattern);
    const bg_scene_state *state = bgi_scene_committed(scene);
    if (!state)
        return bgi_gpu_fail(r, BG_ERR_NOT_COMMITTED, "the scene was never committed");
    if (!bgi_render_progress(settings, (double)first / n))
        return bgi_gpu_fail(r, BG_ERR_CANCELLED, "cancelled by settings.progress before the first pass; the "
                            "accumulation keeps its %d samples", a->samples);
    st = bgi_gpu_accumulate_samples(r, scene, state, settings, &view, a, first, count, NULL, false);
    if (st == BG_OK)
        bgi_render_progress(settings, (double)(first + count) / n);
    return st;
}

bg_status bgi_gpu_accumulation_bytes(bg_renderer *r, bg_accumulation *a, bg_output_encoding encoding,
                                     macs_texture *target)
{
    return bgi_gpu_exact_bytes_run(r, &a->exact, a->sum[a->current], a->samples, encoding, target);
}

bg_status bgi_gpu_accumulation_read_bytes(bg_renderer *r, bg_accumulation *a, bg_output_encoding encoding,
                                          unsigned char *pixels, size_t stride, bool may_park)
{
    bg_status st = bgi_gpu_texture_ensure(r, a->width, a->height, MACS_FORMAT_RGBA8, &a->bytes,
                                          "accumulation bytes texture");
    if (st == BG_OK)
        st = bgi_gpu_accumulation_bytes(r, a, encoding, a->bytes);
    if (st != BG_OK)
        return st;
    /* Where nothing writes the image after these bytes, a tile's read may wait for the next tile
     * (tiles.c); where the CPU's pixels follow (marks), they need the bytes now. */
    if (may_park && bgi_gpu_read_park(r, a->bytes, true))
        return BG_OK;
    macs_status ms = macs_texture_read(a->bytes, pixels, stride);
    if (ms)
        return bgi_gpu_fail_macs(r, ms, "reading the resolved bytes back");
    /* The texture's rows come bottom first: turn them over in place. */
    size_t row = (size_t)a->width * 4;
    for (int y = 0; y < a->height / 2; y++) {
        unsigned char *p = pixels + (size_t)y * stride, *q = pixels + (size_t)(a->height - 1 - y) * stride;
        for (size_t i = 0; i < row; i++) {
            unsigned char t = p[i];
            p[i] = q[i];
            q[i] = t;
        }
    }
    return BG_OK;
}

bg_status bgi_gpu_accumulation_read(bg_renderer *r, const bg_accumulation *a, float *top_down)
{
    size_t row = (size_t)a->width * 4;
    macs_status ms = macs_texture_read(a->sum[a->current], top_down, 0);
    if (ms)
        return bgi_gpu_fail_macs(r, ms, "reading the accumulation back");
    /* The texture's rows come bottom first: turn them over in place. */
    for (int y = 0; y < a->height / 2; y++) {
        float *p = top_down + (size_t)y * row, *q = top_down + (size_t)(a->height - 1 - y) * row;
        for (size_t i = 0; i < row; i++) {
            float t = p[i];
            p[i] = q[i];
            q[i] = t;
        }
    }
    return BG_OK;
}

/* The checks both resolves share. */
static bg_status resolve_check(bg_renderer *r, const bg_accumulation *a, const bg_render_settings *settings, int w,
                               int h, const char *what)
{
    if (!settings || !a)
        return bgi_gpu_fail(r, BG_ERR_INVALID_ARGUMENT, "%s is NULL", !a ? "accumulation" : "settings");
    if (a->renderer != r)
        return bgi_gpu_fail(r, BG_ERR_INVALID_ARGUMENT, "accumulation was made by another renderer");
    if (a->samples == 0)
        return bgi_gpu_fail(r, BG_ERR_INVALID_ARGUMENT, "the accumulation holds no samples yet");
    if (w != a->width || h != a->height)
        return bgi_gpu_fail(r, BG_ERR_INVALID_ARGUMENT, "%s is %dx%d, the accumulation %dx%d", what, w, h, a->width,
                            a->height);
    char message[256];
    bg_status st = bgi_render_settings_check(settings, r->entry, message, sizeof message);
    return st != BG_OK ? bgi_gpu_fail_checked(r, st, message) : BG_OK;
}

static bg_status resolve(bg_renderer *renderer, const bg_accumulation *accumulation,
                         const bg_render_settings *settings, bg_image *image)
{
    bg_renderer *r = renderer;
    const bg_accumulation *a = accumulation;
    if (!r)
        return BG_ERR_INVALID_ARGUMENT;
    r->entry = "bg_accumulation_resolve";
    if (!image || !image->pixels)
        return bgi_gpu_fail(r, BG_ERR_INVALID_ARGUMENT, "image%s is NULL", image ? "->pixels" : "");
    if (image->format != BG_PIXEL_RGBA8 && image->format != BG_PIXEL_RGBA32F)
        return bgi_gpu_fail(r, BG_ERR_INVALID_ARGUMENT, "image->format = %d is not BG_PIXEL_RGBA8 or BG_PIXEL_RGBA32F",
                            (int)image->format);
    bg_status st = resolve_check(r, a, settings, image->width, image->height, "image");
    if (st != BG_OK)
        return st;
    bool as_float = image->format == BG_PIXEL_RGBA32F;
    size_t min_stride = (size_t)image->width * (as_float ? 16 : 4);
    size_t stride = image->stride ? image->stride : min_stride;
    if (stride < min_stride)
        return bgi_gpu_fail(r, BG_ERR_INVALID_ARGUMENT, "image->stride = %zu is below a row's %zu bytes", stride,
                            min_stride);
    if (!as_float)
        return bgi_gpu_accumulation_read_bytes(r, (bg_accumulation *)a, settings->encoding, image->pixels, stride,
                                                false);
    float *sum = bgi_alloc(&r->allocator, (size_t)a->width * a->height * 16);
    if (!sum)
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory reading the accumulation back");
    st = bgi_gpu_accumulation_read(r, a, sum);
    gpu_frame_out out = {image, stride, NULL, image->width, image->height, as_float};
    if (st == BG_OK)
        st = bgi_gpu_samples_write(r, settings, &out, sum, a->samples, NULL, NULL, NULL);
    bgi_free(&r->allocator, sum);
    return st;
}

/* The resolve pass into a float target (RGBA32F or RGBA16F): the mean, linear. An RGBA8 target takes
 * the exact bytes instead (exact_bytes.c). */
static bg_status resolve_prepare(bg_renderer *r, bg_accumulation *a, macs_texture *target)
{
    macs_format format = macs_texture_format(target);
    if (a->resolve && a->resolve_format == format) {
        macs_status ms = macs_pass_set_output(a->resolve, 0, target);
        return ms ? bgi_gpu_fail_macs(r, ms, "binding the accumulation's resolve target") : BG_OK;
    }
    macs_pass_destroy(a->resolve);
    a->resolve = NULL;
    macs_input_desc in[1] = {{"bg_sum"}};
    macs_uniform_desc u[1] = {{"bg_count", MACS_UNIFORM_FLOAT, 0}};
    macs_output_desc o[1] = {{"resolved", "vec4(texture2D(bg_sum, macs_uv).rgb / bg_count, 1.0)"}};
    macs_texture *outs[1] = {target};
    macs_pass_desc d;
    bgi_gpu_pass_desc_init(&d, NULL, in, NULL, 1, u, 1, o, outs, 1);
    bg_status st = bgi_gpu_pass_create(r, "accumulation resolve pass", NULL, NULL, &d, &a->resolve);
    if (st == BG_OK)
        a->resolve_format = format;
    return st;
}

static bg_status resolve_to_texture(bg_renderer *renderer, const bg_accumulation *accumulation,
                                    const bg_render_settings *settings, macs_texture *target)
{
    bg_renderer *r = renderer;
    if (!r)
        return BG_ERR_INVALID_ARGUMENT;
    r->entry = "bg_accumulation_resolve_to_texture";
    if (!target)
        return bgi_gpu_fail(r, BG_ERR_INVALID_ARGUMENT, "target is NULL");
    if (macs_texture_context(target) != r->ctx)
        return bgi_gpu_fail(r, BG_ERR_INVALID_ARGUMENT,
                            "target belongs to another macs_context than the renderer's (bg_renderer_desc.context)");
    int w = 0, h = 0;
    macs_texture_size(target, &w, &h);
    bg_status st = resolve_check(r, accumulation, settings, w, h, "target");
    if (st != BG_OK)
        return st;
    /* The resolve pass is the accumulation's own GPU object, not part of its value. */
    bg_accumulation *a = (bg_accumulation *)accumulation;
    if (macs_texture_format(target) == MACS_FORMAT_RGBA8)
        return bgi_gpu_accumulation_bytes(r, a, settings->encoding, target);
    st = resolve_prepare(r, a, target);
    if (st != BG_OK)
        return st;
    float count = (float)a->samples;
    macs_status ms = macs_pass_set_input(a->resolve, 0, a->sum[a->current]);
    if (!ms)
        ms = macs_pass_set_uniform(a->resolve, "bg_count", &count);
    if (!ms)
        ms = macs_pass_run(a->resolve, NULL);
    return ms ? bgi_gpu_fail_macs(r, ms, "the accumulation's resolve pass") : BG_OK;
}

/* The entry points: each is its body above with the GL work it issued in stats.gl_work (and, adding
 * samples, its phases timed); a resolve has no phases. */
bg_status bg_render_gpu_accumulate(bg_renderer *renderer, bg_scene *scene, const bg_render_settings *settings,
                                   bg_accumulation *accumulation, int first, int count)
{
    if (!renderer)
        return BG_ERR_INVALID_ARGUMENT;
    gpu_entry e;
    bgi_gpu_entry_begin(renderer, settings, &e);
    return bgi_gpu_entry_end(renderer, &e, accumulate(renderer, scene, settings, accumulation, first, count));
}

bg_status bg_accumulation_resolve(bg_renderer *renderer, const bg_accumulation *accumulation,
                                  const bg_render_settings *settings, bg_image *image)
{
    if (!renderer)
        return BG_ERR_INVALID_ARGUMENT;
    gpu_entry e;
    bgi_gpu_entry_begin(renderer, NULL, &e);
    return bgi_gpu_entry_end(renderer, &e, resolve(renderer, accumulation, settings, image));
}

bg_status bg_accumulation_resolve_to_texture(bg_renderer *renderer, const bg_accumulation *accumulation,
                                             const bg_render_settings *settings, macs_texture *target)
{
    if (!renderer)
        return BG_ERR_INVALID_ARGUMENT;
    gpu_entry e;
    bgi_gpu_entry_begin(renderer, NULL, &e);
    return bgi_gpu_entry_end(renderer, &e, resolve_to_texture(renderer, accumulation, settings, target));
}
