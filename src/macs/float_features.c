/* Float features GL 2.1 cannot report: linear filtering and blending of RGBA32F and RGBA16F.
 * A driver without them samples nearest or blends nothing (or falls back to software) and says
 * nothing, so MACS refuses a pass that would need one the context lacks, before it runs, naming the
 * input or output, the format and the feature: a caller never gets silently wrong output. RGBA8
 * always filters and blends. */
#include "internal.h"

static const char *format_name(macs_format f)
{
    return f == MACS_FORMAT_RGBA16F ? "RGBA16F" : f == MACS_FORMAT_RGBA8 ? "RGBA8" : "RGBA32F";
}

macs_status macsi_check_filterable(macs_context *ctx, const macs_texture *t, const char *where)
{
    if (!t || t->filter != MACS_FILTER_LINEAR || t->format == MACS_FORMAT_RGBA8)
        return MACS_OK;
    bool half = t->format == MACS_FORMAT_RGBA16F;
    if (half ? ctx->features.float16_filter : ctx->features.float32_filter)
        return MACS_OK;
    return macsi_fail(ctx, MACS_ERR_LIMIT,
                     "%s: its %s texture is sampled with MACS_FILTER_LINEAR, but this context cannot filter %s "
                     "(macs_features.%s is false: the profile or desc.lacking_float_features says the hardware "
                     "lacks it); sample it with MACS_FILTER_NEAREST and filter in the shader%s",
                     where, format_name(t->format), format_name(t->format),
                     half ? "float16_filter" : "float32_filter",
                     !half && ctx->features.float16_filter ? ", or use RGBA16F, which it filters" : "");
}

macs_status macsi_check_blendable(macs_context *ctx, const macs_texture *t, macs_blend blend, const char *where)
{
    if (!t || blend == MACS_BLEND_NONE || t->format == MACS_FORMAT_RGBA8)
        return MACS_OK;
    bool half = t->format == MACS_FORMAT_RGBA16F;
    if (half ? ctx->features.float16_blend : ctx->features.float32_blend)
        return MACS_OK;
    return macsi_fail(ctx, MACS_ERR_LIMIT,
                     "%s: the pass blends into its %s texture, but this context cannot blend %s (macs_features.%s "
                     "is false: the profile or desc.lacking_float_features says the hardware lacks it); use "
                     "MACS_BLEND_NONE and add in the shader%s",
                     where, format_name(t->format), format_name(t->format), half ? "float16_blend" : "float32_blend",
                     !half && ctx->features.float16_blend ? ", or an RGBA16F output, which it blends" : "");
}
