/* Wrapping a caller's GL texture as a macs_texture (macs_texture_wrap).
 *
 * Invariant: a wrapped macs_texture describes its GL texture as one MACS made would be described: a
 * GL_TEXTURE_2D texture, its level-0 size, one of the three formats MACS exchanges data in, and
 * sampling without mipmaps. Size and format are read from GL (GL 2.1's glGetTexLevelParameteriv),
 * so a description that disagrees with the texture is refused, naming the field, rather than
 * trusted. Sampling is set, not read: GL's default minification filter uses mipmaps, and a texture
 * with only level 0 would then sample as incomplete (black) in every pass reading it.
 * The texture stays the caller's: destroying the macs_texture forgets it (texture.c). */
#include "internal.h"

static const char *format_name(macs_format f)
{
    switch (f) {
    case MACS_FORMAT_RGBA8: return "RGBA8";
    case MACS_FORMAT_RGBA16F: return "RGBA16F";
    case MACS_FORMAT_RGBA32F: return "RGBA32F";
    default: return "DEFAULT";
    }
}

/* The format of a level-0 image of the bound texture, MACS_FORMAT_DEFAULT when it is none MACS has.
 * An unsized GL_RGBA (or the legacy 4) counts as RGBA8 when GL stores 8 bits in every channel:
 * unsized formats are never float, and the sizes say what GL chose. */
static macs_format format_of(const macs_gl *gl, GLint internal)
{
    switch (internal) {
    case GL_RGBA8: return MACS_FORMAT_RGBA8;
    case GL_RGBA32F_ARB: return MACS_FORMAT_RGBA32F;
    case GL_RGBA16F_ARB: return MACS_FORMAT_RGBA16F;
    case GL_RGBA:
    case 4: {
        static const GLenum sizes[4] = {GL_TEXTURE_RED_SIZE, GL_TEXTURE_GREEN_SIZE, GL_TEXTURE_BLUE_SIZE,
                                        GL_TEXTURE_ALPHA_SIZE};
        for (int i = 0; i < 4; i++) {
            GLint bits = 0;
            gl->GetTexLevelParameteriv(GL_TEXTURE_2D, 0, sizes[i], &bits);
            if (bits != 8)
                return MACS_FORMAT_DEFAULT;
        }
        return MACS_FORMAT_RGBA8;
    }
    default: return MACS_FORMAT_DEFAULT;
    }
}

static macs_status check_desc(macs_context *ctx, const macs_texture_wrap_desc *d)
{
    if (d->gl_name == 0)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT,
                         "macs_texture_wrap: desc.gl_name is 0, GL's default texture, which is no caller's");
    if (d->width < 0 || d->height < 0)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT,
                         "macs_texture_wrap: desc.%s %d must be 0 (as GL reports) or the texture's",
                         d->width < 0 ? "width" : "height", d->width < 0 ? d->width : d->height);
    if ((unsigned)d->format > MACS_FORMAT_RGBA8)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT,
                         "macs_texture_wrap: desc.format %d is not a macs_format (0 .. %d)", (int)d->format,
                         (int)MACS_FORMAT_RGBA8);
    if ((unsigned)d->filter > MACS_FILTER_LINEAR)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT,
                         "macs_texture_wrap: desc.filter %d is not a macs_filter (0 .. %d)", (int)d->filter,
                         (int)MACS_FILTER_LINEAR);
    if ((unsigned)d->wrap > MACS_WRAP_REPEAT)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_texture_wrap: desc.wrap %d is not a macs_wrap (0 .. %d)",
                         (int)d->wrap, (int)MACS_WRAP_REPEAT);
    return MACS_OK;
}

/* Reads what GL holds for the texture bound to GL_TEXTURE_2D and compares the description with it;
 * *format gets the texture's format. */
static macs_status check_level0(macs_context *ctx, const macs_texture_wrap_desc *d, int *width, int *height,
                                macs_format *format)
{
    const macs_gl *gl = &ctx->gl;
    GLint w = 0, h = 0, internal = 0;
    gl->GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &w);
    gl->GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_HEIGHT, &h);
    gl->GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_INTERNAL_FORMAT, &internal);
    if (w <= 0 || h <= 0)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT,
                         "macs_texture_wrap: desc.gl_name %u has no level-0 image (glTexImage2D never gave it one)",
                         d->gl_name);
    if (d->width != 0 && d->width != w)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT,
                         "macs_texture_wrap: desc.width %d differs from the texture's level-0 width %d", d->width, w);
    if (d->height != 0 && d->height != h)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT,
                         "macs_texture_wrap: desc.height %d differs from the texture's level-0 height %d", d->height,
                         h);
    int max = ctx->effective.max_texture_size;
    if (w > max || h > max)
        return macsi_fail(ctx, MACS_ERR_LIMIT, "macs_texture_wrap: the texture's size %dx%d exceeds the maximum %d",
                         w, h, max);
    macs_format f = format_of(gl, internal);
    if (f == MACS_FORMAT_DEFAULT)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT,
                         "macs_texture_wrap: desc.gl_name %u has internal format 0x%04x, none of GL_RGBA8, "
                         "GL_RGBA32F_ARB, GL_RGBA16F_ARB (or GL_RGBA of 8-bit channels) that MACS exchanges data in",
                         d->gl_name, (unsigned)internal);
    if (d->format != MACS_FORMAT_DEFAULT && d->format != f)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT,
                         "macs_texture_wrap: desc.format %s differs from the texture's internal format (%s, 0x%04x)",
                         format_name(d->format), format_name(f), (unsigned)internal);
    *width = w;
    *height = h;
    *format = f;
    return MACS_OK;
}

/* Binds the texture to GL_TEXTURE_2D of unit 0 and checks it, leaving it bound on success. */
static macs_status bind_checked(macs_context *ctx, GLuint name)
{
    const macs_gl *gl = &ctx->gl;
    /* glIsTexture is false for a name glGenTextures made but nothing bound yet: it names no texture. */
    if (!gl->IsTexture(name))
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT,
                         "macs_texture_wrap: desc.gl_name %u is no texture of the current GL context (glIsTexture "
                         "is false: never bound, deleted, or of another context)",
                         (unsigned)name);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D, name);
    if (gl->GetError() != GL_NO_ERROR) {
        macsi_gl_drain(ctx);
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT,
                         "macs_texture_wrap: desc.gl_name %u is a texture of another target than GL_TEXTURE_2D "
                         "(glBindTexture refused it)",
                         (unsigned)name);
    }
    return MACS_OK;
}

macs_status macs_texture_wrap(macs_context *ctx, const macs_texture_wrap_desc *desc, macs_texture **out)
{
    if (out)
        *out = NULL;
    if (!ctx)
        return MACS_ERR_INVALID_ARGUMENT;
    if (!desc || !out)
        return macsi_fail(ctx, MACS_ERR_INVALID_ARGUMENT, "macs_texture_wrap: %s is NULL", desc ? "out" : "desc");
    macs_status st = check_desc(ctx, desc);
    if (st == MACS_OK)
        st = macsi_gl_current(ctx, "macs_texture_wrap");
    if (st != MACS_OK)
        return st;
    macsi_gl_drain(ctx);
    st = bind_checked(ctx, desc->gl_name);
    if (st != MACS_OK)
        return st;
    int w = 0, h = 0;
    macs_format format = MACS_FORMAT_DEFAULT;
    st = check_level0(ctx, desc, &w, &h, &format);
    macs_texture *t = NULL;
    if (st == MACS_OK) {
        t = macsi_calloc(&ctx->allocator, 1, sizeof *t);
        if (!t)
            st = macsi_fail(ctx, MACS_ERR_OUT_OF_MEMORY, "macs_texture_wrap: allocating the texture");
    }
    if (st == MACS_OK)
        macsi_texture_apply_sampling(ctx, desc->filter, desc->wrap);
    ctx->gl.BindTexture(GL_TEXTURE_2D, 0);
    if (st == MACS_OK)
        st = macsi_gl_check(ctx, "macs_texture_wrap: setting the sampling parameters");
    if (st != MACS_OK) {
        macsi_free(&ctx->allocator, t);
        return st;
    }
    t->ctx = ctx;
    t->id = desc->gl_name;
    t->width = w;
    t->height = h;
    t->format = format;
    t->filter = desc->filter;
    t->wrapped = true;
    MACS_LIST_PUSH(ctx->textures, t);
    *out = t;
    return MACS_OK;
}
