/* Test helpers: the few GL 2.1 calls a test makes itself, as a caller with its own GL code would
 * (its own textures to wrap, checks that MACS left them alive), looked up through the headless
 * context's get_proc_address so that they reach whichever backend is current. */
#ifndef UTIL_RAW_GL_H
#define UTIL_RAW_GL_H

#include <GL/gl.h>
#include <GL/glext.h>

#include "macs.h"

typedef struct util_raw_gl {
    GLenum (GLAPIENTRY *GetError)(void);
    void (GLAPIENTRY *GenTextures)(GLsizei n, GLuint *textures);
    void (GLAPIENTRY *DeleteTextures)(GLsizei n, const GLuint *textures);
    void (GLAPIENTRY *BindTexture)(GLenum target, GLuint texture);
    GLboolean (GLAPIENTRY *IsTexture)(GLuint texture);
    void (GLAPIENTRY *TexParameteri)(GLenum target, GLenum pname, GLint param);
    void (GLAPIENTRY *TexImage2D)(GLenum target, GLint level, GLint internalformat, GLsizei width, GLsizei height,
                                  GLint border, GLenum format, GLenum type, const void *pixels);
    void (GLAPIENTRY *TexImage1D)(GLenum target, GLint level, GLint internalformat, GLsizei width, GLint border,
                                  GLenum format, GLenum type, const void *pixels);
    void (GLAPIENTRY *GetTexImage)(GLenum target, GLint level, GLenum format, GLenum type, void *pixels);
    void (GLAPIENTRY *GetTexParameteriv)(GLenum target, GLenum pname, GLint *params);
    void (GLAPIENTRY *GetIntegerv)(GLenum pname, GLint *data);
} util_raw_gl;

/* Fills every entry from the headless context's loader; fails the test if one is missing. */
void util_raw_gl_load(macs_headless *headless, util_raw_gl *gl);

/* A texture of the caller's own, width x height of internal_format (GL_RGBA8, GL_RGBA32F_ARB, ...)
 * with GL's default parameters (a mipmap minification filter) and pixels (NULL: undefined) given as
 * type (GL_UNSIGNED_BYTE or GL_FLOAT) RGBA rows, bottom first; fails the test on a GL error. */
GLuint util_raw_texture(const util_raw_gl *gl, int width, int height, GLint internal_format, GLenum type,
                        const void *pixels);

#endif
