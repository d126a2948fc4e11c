/* The few GL calls tests make themselves (util_raw_gl.h). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "util_raw_gl.h"

static macs_gl_proc lookup(macs_headless *headless, const char *name)
{
    macs_get_proc_address_fn gpa = macs_headless_get_proc_address(headless);
    macs_gl_proc p = gpa ? gpa(name, macs_headless_proc_user(headless)) : NULL;
    if (!p)
        fail_msg("GL function %s is missing", name);
    return p;
}

/* The generic function pointer goes into each entry's own function pointer type by copying its
 * representation (the same size, checked), which saves a typedef per entry in the header. */
#define UTIL_RAW_GL_LOAD_(field, name)                                                   \
    do {                                                                                 \
        macs_gl_proc p_ = lookup(headless, name);                                        \
        assert_int_equal(sizeof gl->field, sizeof p_);                                   \
        memcpy(&gl->field, &p_, sizeof gl->field);                                       \
    } while (0)

void util_raw_gl_load(macs_headless *headless, util_raw_gl *gl)
{
    UTIL_RAW_GL_LOAD_(GetError, "glGetError");
    UTIL_RAW_GL_LOAD_(GenTextures, "glGenTextures");
    UTIL_RAW_GL_LOAD_(DeleteTextures, "glDeleteTextures");
    UTIL_RAW_GL_LOAD_(BindTexture, "glBindTexture");
    UTIL_RAW_GL_LOAD_(IsTexture, "glIsTexture");
    UTIL_RAW_GL_LOAD_(TexParameteri, "glTexParameteri");
    UTIL_RAW_GL_LOAD_(TexImage2D, "glTexImage2D");
    UTIL_RAW_GL_LOAD_(TexImage1D, "glTexImage1D");
    UTIL_RAW_GL_LOAD_(GetTexImage, "glGetTexImage");
    UTIL_RAW_GL_LOAD_(GetTexParameteriv, "glGetTexParameteriv");
    UTIL_RAW_GL_LOAD_(GetIntegerv, "glGetIntegerv");
}

GLuint util_raw_texture(const util_raw_gl *gl, int width, int height, GLint internal_format, GLenum type,
                        const void *pixels)
{
    while (gl->GetError() != GL_NO_ERROR)
        ;
    GLuint name = 0;
    gl->GenTextures(1, &name);
    gl->BindTexture(GL_TEXTURE_2D, name);
    gl->TexImage2D(GL_TEXTURE_2D, 0, internal_format, width, height, 0, GL_RGBA, type, pixels);
    gl->BindTexture(GL_TEXTURE_2D, 0);
    GLenum e = gl->GetError();
    if (e != GL_NO_ERROR || name == 0)
        fail_msg("making a %dx%d GL texture of internal format 0x%04x: GL error 0x%04x", width, height,
                 (unsigned)internal_format, (unsigned)e);
    return name;
}
