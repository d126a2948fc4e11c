/* Textures both plans make: a target created on first use, and a scene texture as the samplers
 * read it (GL_NEAREST, filtered in the shader where the scene asks for GL_LINEAR). */
#include <string.h>

#include "../../common/alloc.h"
#include "../../common/srgb.h"
#include "shared.h"

bg_status bgi_gpu_texture_ensure(bg_renderer *r, int w, int h, macs_format format, macs_texture **out, const char *what)
{
    if (*out)
        return BG_OK;
    macs_texture_desc d;
    memset(&d, 0, sizeof d);
    d.width = w;
    d.height = h;
    d.format = format;
    macs_status ms = macs_texture_create(r->ctx, &d, out);
    return ms ? bgi_gpu_fail_macs(r, ms, what) : BG_OK;
}

bg_status bgi_gpu_float_texture(bg_renderer *r, int w, int h, macs_filter filter, macs_wrap wrap, const float *texels,
                                const char *what, macs_texture **out)
{
    macs_texture_desc d;
    memset(&d, 0, sizeof d);
    d.width = w;
    d.height = h;
    d.format = MACS_FORMAT_RGBA32F;
    d.filter = filter;
    d.wrap = wrap;
    d.data = texels;
    macs_status ms = macs_texture_create(r->ctx, &d, out);
    return ms ? bgi_gpu_fail_macs(r, ms, what) : BG_OK;
}

bool bgi_gpu_srgb_table(const bg_renderer *r)
{
    return r->limits.max_texture_units >= GPU_SRGB_TABLE_MIN_UNITS;
}

bg_status bgi_gpu_srgb_table_upload(bg_renderer *r, macs_texture **out)
{
    float texels[256 * 4];
    for (int k = 0; k < 256; k++)
        for (int c = 0; c < 4; c++)
            texels[4 * k + c] = (float)bgi_srgb_table[k];
    return bgi_gpu_float_texture(r, 256, 1, MACS_FILTER_NEAREST, MACS_WRAP_CLAMP_TO_EDGE, texels, "sRGB decode table",
                                 out);
}

/* An 8-bit sRGB texture as linear floats, for a context without a unit for the table. */
static bg_status decoded_upload(bg_renderer *r, const bg_texture_data *t, macs_wrap wrap, macs_texture **out)
{
    size_t n = (size_t)t->width * (size_t)t->height;
    float *decoded = bgi_alloc(&r->allocator, n * 4 * sizeof *decoded);
    if (!decoded)
        return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory decoding a %d x %d scene texture", t->width,
                            t->height);
    for (size_t k = 0; k < n; k++)
        for (int c = 0; c < 4; c++)
            decoded[4 * k + (size_t)c] = (float)bgi_texture_channel(t, k, c);
    bg_status st = bgi_gpu_float_texture(r, t->width, t->height, MACS_FILTER_NEAREST, wrap, decoded, "scene texture", out);
    bgi_free(&r->allocator, decoded);
    return st;
}

bg_status bgi_gpu_scene_texture_upload(bg_renderer *r, const bg_texture_data *t, bool table, macs_texture **out,
                                       uint64_t *bytes)
{
    /* No mipmaps (docs/shading.md 5); both are GL row order: row 0 is v = 0. Always GL_NEAREST:
     * the hardware filter's weights are the driver's (8-bit fixed point on NVIDIA, no float
     * filtering at all on Radeon X1000), so GL_LINEAR is done in the shader. */
    macs_wrap wrap = t->wrap == BG_WRAP_REPEAT ? MACS_WRAP_REPEAT : MACS_WRAP_CLAMP_TO_EDGE;
    uint64_t texels = (uint64_t)t->width * (uint64_t)t->height;
    *bytes = texels * 16;
    if (t->texels)
        return bgi_gpu_float_texture(r, t->width, t->height, MACS_FILTER_NEAREST, wrap, t->texels, "scene texture", out);
    if (t->srgb && !table)
        return decoded_upload(r, t, wrap, out);
    /* An RGBA8 texel reaches the shader as k / 255 per channel: as it is for a linear texture, the
     * table's entry k for an sRGB one (bg_texture_srgb.glsl). */
    *bytes = texels * 4;
    macs_texture_desc d;
    memset(&d, 0, sizeof d);
    d.width = t->width;
    d.height = t->height;
    d.format = MACS_FORMAT_RGBA8;
    d.filter = MACS_FILTER_NEAREST;
    d.wrap = wrap;
    d.data = t->bytes;
    macs_status ms = macs_texture_create(r->ctx, &d, out);
    return ms ? bgi_gpu_fail_macs(r, ms, "scene texture") : BG_OK;
}

gpu_texture_mode bgi_gpu_texture_mode(const bg_texture_data *t, bool table)
{
    gpu_texture_mode m = {1, 1, false, false, false};
    if (t) {
        m.width = t->width;
        m.height = t->height;
        m.linear = t->filter == BG_FILTER_LINEAR;
        m.repeat = t->wrap == BG_WRAP_REPEAT;
        m.srgb = table && t->bytes && t->srgb;
    }
    return m;
}

bool bgi_gpu_texture_lookup(char *out, size_t size, const char *sampler, const char *uv, gpu_texture_mode m)
{
    int n;
    if (m.linear)
        n = snprintf(out, size, "bg_texture_linear%s(%s, %s, vec2(%d.0, %d.0), %s%s)", m.srgb ? "_srgb" : "", sampler,
                     uv, m.width, m.height, m.repeat ? "true" : "false", m.srgb ? ", bg_srgb_table" : "");
    else if (m.srgb)
        n = snprintf(out, size, "bg_srgb_decode(texture2D(%s, %s), bg_srgb_table)", sampler, uv);
    else
        n = snprintf(out, size, "texture2D(%s, %s)", sampler, uv);
    return n >= 0 && (size_t)n < size;
}
