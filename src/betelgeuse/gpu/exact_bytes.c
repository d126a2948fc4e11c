/* The RGBA8 bytes of a mean of samples on the GPU, equal to the host's bit for bit.
 *
 * The host writes a channel of a sum s of n samples as bgi_encode_channel(s / n), the division in
 * float (samples.c). That byte only grows with s: float division by a positive n, the clamp, the sRGB
 * curve and the rounding are each monotonic. So for each byte k in 1 .. 255 there is a least float
 * sum T_k whose byte is at least k, found here by bisecting the ordered bit patterns of the
 * non-negative floats, and the byte of any s is the number of thresholds s reaches: a search of eight
 * float comparisons on the GPU (glsl110/bg_stage_exact_bytes.glsl). No GPU division, pow or rounding
 * takes part, so the bytes are the host's on any GL whose RGBA32F textures hold floats as they are.
 * A sum below T_1 (a negative one included) is 0 and +inf is 255, as on the host; a NaN sum, which
 * no plan writes, would read 0. Alpha is 255, or 0 where the sum's alpha says a sample's walk ran out
 * of steps (the mark the CPU reference's pixels replace, shared/fallback.c).
 *
 * The thresholds go up once per (n, encoding), 4 KB; a frame of the same n and encoding uploads
 * nothing. */
#include <string.h>

#include "../common/alloc.h"
#include "../common/encoding.h"
#include "driver.h"

struct gpu_exact_bytes {
    macs_texture *thresholds; /* 256 x 1 RGBA32F, texel k = T_k in every channel (texel 0: n - 0.5) */
    int samples;              /* the n and encoding the thresholds are of (samples 0: none yet) */
    bg_output_encoding encoding;
    macs_pass *pass;
};

static int host_byte(uint32_t bits, int n, bg_output_encoding encoding)
{
    float s;
    memcpy(&s, &bits, sizeof s);
    /* The host's own expression (bgi_gpu_samples_write): the float quotient, then the encoding. */
    float mean = s / (float)n;
    return bgi_encode_channel(mean, encoding);
}

uint32_t bgi_gpu_exact_threshold(int k, int n, bg_output_encoding encoding)
{
    uint32_t lo = 0, hi = 0x7F800000u;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (host_byte(mid, n, encoding) >= k)
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}

static bg_status thresholds_ensure(bg_renderer *r, gpu_exact_bytes *e, int n, bg_output_encoding encoding)
{
    if (e->thresholds && e->samples == n && e->encoding == encoding)
        return BG_OK;
    float texels[256 * 4];
    for (int k = 0; k < 256; k++) {
        uint32_t bits = k == 0 ? 0u : bgi_gpu_exact_threshold(k, n, encoding);
        float t;
        memcpy(&t, &bits, sizeof t);
        /* Texel 0 is no byte's threshold: it holds n - 0.5, which the sum's alpha (the count of
         * samples whose walks finished) reaches unless some sample's walk ran out; that pixel's alpha
         * is then 0, its mark (shared/fallback.c). */
        if (k == 0)
            t = (float)n - 0.5f;
        for (int c = 0; c < 4; c++)
            texels[k * 4 + c] = t;
    }
    if (!e->thresholds) {
        bg_status st = bgi_gpu_float_texture(r, 256, 1, MACS_FILTER_NEAREST, MACS_WRAP_CLAMP_TO_EDGE, texels,
                                             "exact resolve thresholds", &e->thresholds);
        if (st != BG_OK)
            return st;
    } else {
        macs_status ms = macs_texture_upload(e->thresholds, texels, 0);
        if (ms)
            return bgi_gpu_fail_macs(r, ms, "uploading the exact resolve thresholds");
    }
    e->samples = n;
    e->encoding = encoding;
    return BG_OK;
}

static bg_status pass_ensure(bg_renderer *r, gpu_exact_bytes *e, macs_texture *target)
{
    if (e->pass) {
        macs_status ms = macs_pass_set_output(e->pass, 0, target);
        return ms ? bgi_gpu_fail_macs(r, ms, "binding the exact resolve's target") : BG_OK;
    }
    macs_input_desc in[2] = {{"bg_sum"}, {"bg_thresholds"}};
    macs_output_desc o[1] = {{"bytes", "bg_exact_bytes(bg_thresholds, texture2D(bg_sum, macs_uv))"}};
    macs_texture *outs[1] = {target};
    macs_pass_desc d;
    bgi_gpu_pass_desc_init(&d, NULL, in, NULL, 2, NULL, 0, o, outs, 1);
    const char *files[] = {"bg_stage_exact_bytes.glsl", NULL};
    return bgi_gpu_pass_create(r, "exact resolve pass", files, NULL, &d, &e->pass);
}

bg_status bgi_gpu_exact_bytes_run(bg_renderer *r, gpu_exact_bytes **state, macs_texture *sum, int samples,
                                  bg_output_encoding encoding, macs_texture *target)
{
    if (!*state) {
        *state = bgi_alloc(&r->allocator, sizeof **state);
        if (!*state)
            return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for the exact resolve");
        memset(*state, 0, sizeof **state);
    }
    gpu_exact_bytes *e = *state;
    bg_status st = thresholds_ensure(r, e, samples, encoding);
    if (st == BG_OK)
        st = pass_ensure(r, e, target);
    if (st != BG_OK)
        return st;
    macs_status ms = macs_pass_set_input(e->pass, 0, sum);
    if (!ms)
        ms = macs_pass_set_input(e->pass, 1, e->thresholds);
    if (!ms)
        ms = macs_pass_run(e->pass, NULL);
    return ms ? bgi_gpu_fail_macs(r, ms, "the exact resolve pass") : BG_OK;
}

void bgi_gpu_exact_bytes_destroy(gpu_exact_bytes *e, const bg_allocator *allocator)
{
    if (!e)
        return;
    macs_pass_destroy(e->pass);
    macs_texture_destroy(e->thresholds);
    bgi_free(allocator, e);
}
