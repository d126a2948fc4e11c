/* GPU memory of the multipass: size-dependent targets (G-buffer, accumulation, visibility, encoded
 * output, depth/stencil, ray-set pool) and the white texel of untextured parameters (the scene's
 * textures are the plans' one copy, shared/scene_textures.c). Everything is made on demand and kept
 * while the size stays the same. */
#include <stdio.h>
#include <string.h>

#include "../../common/alloc.h"
#include "multipass.h"

macs_format bgi_gpu_slot_format(const bg_renderer *r, gpu_slot slot)
{
    if (!r->half_gbuffer)
        return MACS_FORMAT_RGBA32F;
    switch (slot) {
    case GPU_SLOT_HIT:
        /* Shadow segments and bounce rays start at this position: 11 bits would move their origins
         * by up to |p| 2^-11, a defect (acne, light leaks) rather than a trade-off. The w lane is
         * the hit code, object index + 1 (+ 0.5), which half holds exactly only below 1024 objects. */
        return MACS_FORMAT_RGBA32F;
    case GPU_SLOT_MESH:
        /* The offset is a few float ulps of the point's magnitude, below half's normal range. */
        return MACS_FORMAT_RGBA32F;
    case GPU_SLOT_ONCE:
        /* rgb is weight x (emission + opaque x ambient), which the API does not bound: above 65504
         * half gives Inf, which the renderer never lets reach a target. w is the index of refraction, which
         * Snell's law and total internal reflection use at every level of a refracted path. */
        return MACS_FORMAT_RGBA32F;
    default:
        /* The rest are unit vectors and values clamped to [0, 1] (path weight x opaque is at most
         * 1), plus two flags half holds exactly: coat roughness -1 (no coat) and isotropy 1. A
         * relative error of 2^-11 there bends reflections and shading slightly, which is the
         * measured trade-off (docs/gpu_pipeline.md). */
        return MACS_FORMAT_RGBA16F;
    }
}

bool bgi_gpu_half_probe(bg_renderer *r, char *why, size_t why_size)
{
    /* Exact in half and float, not in 8 bits: an implementation that quietly stores RGBA16F with
     * fewer bits fails the comparison. Values stay in [0, 1] so that missing ARB_color_buffer_float
     * (clamped outputs, which would break RGBA32F as well) does not count against RGBA16F. */
    static const float want[4] = {0.25f, 0.50048828125f, 0.75f, 0.0009765625f};
    static const char *const value = "vec4(0.25, 0.50048828125, 0.75, 0.0009765625)";
    enum { SIZE = 2 };
    macs_status before = macs_context_error(r->ctx);
    macs_texture *tex[2] = {NULL, NULL};
    macs_pass *pass = NULL;
    float texels[SIZE * SIZE * 4];
    bool ok = true;
    macs_status ms = MACS_OK;
    why[0] = '\0';
    for (int i = 0; i < 2 && !ms; i++) {
        macs_texture_desc d;
        memset(&d, 0, sizeof d);
        d.width = d.height = SIZE;
        d.format = i == 0 ? MACS_FORMAT_RGBA32F : MACS_FORMAT_RGBA16F;
        ms = macs_texture_create(r->ctx, &d, &tex[i]);
    }
    if (!ms) {
        /* Both formats in one pass, as the intersection pass writes them: EXT_framebuffer_object
         * (MACS's fallback) wants every colour attachment of a framebuffer in one format. */
        macs_output_desc outputs[2] = {{"full", value}, {"half", value}};
        macs_pass_desc desc;
        bgi_gpu_pass_desc_init(&desc, NULL, NULL, NULL, 0, NULL, 0, outputs, tex, 2);
        ms = macs_pass_create(r->ctx, &desc, &pass);
    }
    if (!ms)
        ms = macs_pass_run(pass, NULL);
    for (int i = 0; i < 2 && !ms && ok; i++) {
        ms = macs_texture_read(tex[i], texels, 0);
        for (int k = 0; k < SIZE * SIZE * 4 && !ms && ok; k++)
            if (texels[k] != want[k % 4]) {
                snprintf(why, why_size, "an RGBA%s target read back %.9g instead of %.9g", i ? "16F" : "32F",
                         (double)texels[k], (double)want[k % 4]);
                ok = false;
            }
    }
    if (ms) {
        const char *detail = macs_context_error_message(r->ctx);
        snprintf(why, why_size, "%s", detail && *detail ? detail : macs_status_string(ms));
        ok = false;
        /* The probe's failure is an answer, not an error of the caller's. */
        if (before == MACS_OK)
            macs_context_clear_error(r->ctx);
    }
    macs_pass_destroy(pass);
    macs_texture_destroy(tex[0]);
    macs_texture_destroy(tex[1]);
    return ok;
}

void bgi_gpu_targets_release(bg_renderer *r)
{
    for (int s = 0; s < GPU_SLOT_COUNT; s++) {
        macs_texture_destroy(r->multipass->gbuffer[s]);
        r->multipass->gbuffer[s] = NULL;
    }
    macs_texture_destroy(r->multipass->accum);
    macs_texture_destroy(r->multipass->vis);
    macs_texture_destroy(r->multipass->encoded);
    macs_depth_stencil_destroy(r->multipass->depth);
    r->multipass->accum = r->multipass->vis = r->multipass->encoded = NULL;
    r->multipass->depth = NULL;
    for (int i = 0; i < r->multipass->set_count; i++) {
        macs_texture_destroy(r->multipass->sets[i].origin);
        macs_texture_destroy(r->multipass->sets[i].dir);
        macs_texture_destroy(r->multipass->sets[i].weight);
    }
    bgi_free(&r->allocator, r->multipass->sets);
    r->multipass->sets = NULL;
    r->multipass->set_count = 0;
    r->multipass->width = r->multipass->height = 0;
}

/* The accumulation takes the light passes' additive blending: RGBA32F where the hardware blends it,
 * RGBA16F on parts that blend only 16-bit floats (GeForce 6/7, Radeon X1000: the context's
 * features say so, since GL 2.1 cannot). Each add then rounds to 11 significant bits, at most 2^-11
 * per add, far below one step of the 8-bit output for the handful of adds a pixel takes. A part
 * that blends no float target cannot run the multipass at all. */
static bg_status accumulation_format(bg_renderer *r, macs_format *out)
{
    macs_features f;
    macs_context_get_features(r->ctx, &f);
    if (f.float32_blend)
        *out = MACS_FORMAT_RGBA32F;
    else if (f.float16_blend)
        *out = MACS_FORMAT_RGBA16F;
    else
        return bgi_gpu_fail(r, BG_ERR_LIMIT, "the multipass plan adds its light passes by blending into a float "
                            "target, and this GL context blends neither RGBA32F nor RGBA16F targets (a fused plan "
                            "needs no blending)");
    return BG_OK;
}

bg_status bgi_gpu_targets_prepare(bg_renderer *r, int w, int h)
{
    if (r->multipass->width != w || r->multipass->height != h)
        bgi_gpu_targets_release(r);
    r->multipass->width = w;
    r->multipass->height = h;
    bg_status st = BG_OK;
    for (int s = 0; s < GPU_SLOT_COUNT && st == BG_OK; s++)
        if (r->multipass->features.slot[s])
            st = bgi_gpu_texture_ensure(r, w, h, bgi_gpu_slot_format(r, (gpu_slot)s), &r->multipass->gbuffer[s], "G-buffer texture");
    macs_format accumulation = MACS_FORMAT_RGBA32F;
    if (st == BG_OK)
        st = accumulation_format(r, &accumulation);
    if (st == BG_OK)
        st = bgi_gpu_texture_ensure(r, w, h, accumulation, &r->multipass->accum, "accumulation texture");
    /* Visibility is 0 or 1 per channel: 8 bits hold it exactly. */
    if (st == BG_OK)
        st = bgi_gpu_texture_ensure(r, w, h, MACS_FORMAT_RGBA8, &r->multipass->vis, "visibility texture");
    if (st == BG_OK)
        st = bgi_gpu_texture_ensure(r, w, h, MACS_FORMAT_RGBA8, &r->multipass->encoded, "output texture");
    if (st == BG_OK && !r->multipass->depth) {
        macs_depth_stencil_desc d = {w, h, r->float_depth ? MACS_DEPTH32F_STENCIL8 : MACS_DEPTH24_STENCIL8};
        macs_status ms = macs_depth_stencil_create(r->ctx, &d, &r->multipass->depth);
        if (ms)
            st = bgi_gpu_fail_macs(r, ms, "depth/stencil buffer");
    }
    return st;
}

bg_status bgi_gpu_ray_set_get(bg_renderer *r, int index, gpu_ray_set **out)
{
    if (index >= r->multipass->set_count) {
        size_t old = (size_t)r->multipass->set_count * sizeof *r->multipass->sets, need = (size_t)(index + 1) * sizeof *r->multipass->sets;
        gpu_ray_set *grown = bgi_realloc(&r->allocator, r->multipass->sets, old, need);
        if (!grown)
            return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for ray set %d", index);
        memset((char *)grown + old, 0, need - old);
        r->multipass->sets = grown;
        r->multipass->set_count = index + 1;
    }
    gpu_ray_set *s = &r->multipass->sets[index];
    bg_status st = bgi_gpu_texture_ensure(r, r->multipass->width, r->multipass->height, MACS_FORMAT_RGBA32F, &s->origin, "ray origin map");
    if (st == BG_OK)
        st = bgi_gpu_texture_ensure(r, r->multipass->width, r->multipass->height, MACS_FORMAT_RGBA32F, &s->dir, "ray direction map");
    if (st == BG_OK)
        st = bgi_gpu_texture_ensure(r, r->multipass->width, r->multipass->height, MACS_FORMAT_RGBA32F, &s->weight, "ray weight map");
    *out = s;
    return st;
}

bg_status bgi_gpu_white_prepare(bg_renderer *r)
{
    if (r->multipass->white)
        return BG_OK;
    static const float white[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    macs_texture_desc d;
    memset(&d, 0, sizeof d);
    d.width = d.height = 1;
    d.format = MACS_FORMAT_RGBA32F;
    d.filter = MACS_FILTER_NEAREST; /* exactly 1.0, so constant x white is the constant */
    d.data = white;
    macs_status ms = macs_texture_create(r->ctx, &d, &r->multipass->white);
    return ms ? bgi_gpu_fail_macs(r, ms, "white texture") : BG_OK;
}
