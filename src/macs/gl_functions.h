/* The whitelist of every GL entry point MACS calls, as one X-macro list.
 * MACS_GL_CORE: OpenGL 2.1 functions, looked up as "gl" name.
 * MACS_GL_FBO: framebuffer functions, looked up as "gl" name with ARB_framebuffer_object (or GL 3.0),
 *   or as "gl" name "EXT" with EXT_framebuffer_object + EXT_packed_depth_stencil.
 * MACS_GL_OPTIONAL: extension functions that may be NULL; only called when the extension string says so.
 * Each entry: X(return type, name, parameter list). */
#ifndef MACS_GL_FUNCTIONS_H
#define MACS_GL_FUNCTIONS_H

#define MACS_GL_CORE(X) \
    X(GLenum, GetError, (void)) \
    X(const GLubyte *, GetString, (GLenum name)) \
    X(void, GetIntegerv, (GLenum pname, GLint *data)) \
    X(void, Enable, (GLenum cap)) \
    X(void, Disable, (GLenum cap)) \
    X(void, Viewport, (GLint x, GLint y, GLsizei width, GLsizei height)) \
    X(void, Scissor, (GLint x, GLint y, GLsizei width, GLsizei height)) \
    X(void, Clear, (GLbitfield mask)) \
    X(void, ClearColor, (GLfloat r, GLfloat g, GLfloat b, GLfloat a)) \
    X(void, ClearDepth, (GLclampd depth)) \
    X(void, ClearStencil, (GLint s)) \
    X(void, ColorMask, (GLboolean r, GLboolean g, GLboolean b, GLboolean a)) \
    X(void, DepthMask, (GLboolean flag)) \
    X(void, DepthFunc, (GLenum func)) \
    X(void, StencilFunc, (GLenum func, GLint ref, GLuint mask)) \
    X(void, StencilOp, (GLenum fail, GLenum zfail, GLenum zpass)) \
    X(void, StencilMask, (GLuint mask)) \
    X(void, BlendFunc, (GLenum sfactor, GLenum dfactor)) \
    X(void, BlendEquation, (GLenum mode)) \
    X(void, PixelStorei, (GLenum pname, GLint param)) \
    X(void, ReadBuffer, (GLenum mode)) \
    X(void, GenTextures, (GLsizei n, GLuint *textures)) \
    X(void, DeleteTextures, (GLsizei n, const GLuint *textures)) \
    X(void, BindTexture, (GLenum target, GLuint texture)) \
    X(void, ActiveTexture, (GLenum texture)) \
    X(void, TexParameteri, (GLenum target, GLenum pname, GLint param)) \
    X(void, TexImage2D, (GLenum target, GLint level, GLint internalformat, GLsizei width, GLsizei height, \
                         GLint border, GLenum format, GLenum type, const void *pixels)) \
    X(void, TexSubImage2D, (GLenum target, GLint level, GLint xoffset, GLint yoffset, GLsizei width, \
                            GLsizei height, GLenum format, GLenum type, const void *pixels)) \
    X(void, GetTexImage, (GLenum target, GLint level, GLenum format, GLenum type, void *pixels)) \
    X(GLboolean, IsTexture, (GLuint texture)) \
    X(void, GetTexLevelParameteriv, (GLenum target, GLint level, GLenum pname, GLint *params)) \
    X(void, DrawArrays, (GLenum mode, GLint first, GLsizei count)) \
    X(void, GenBuffers, (GLsizei n, GLuint *buffers)) \
    X(void, DeleteBuffers, (GLsizei n, const GLuint *buffers)) \
    X(void, BindBuffer, (GLenum target, GLuint buffer)) \
    X(void, BufferData, (GLenum target, GLsizeiptr size, const void *data, GLenum usage)) \
    X(void *, MapBuffer, (GLenum target, GLenum access)) \
    X(GLboolean, UnmapBuffer, (GLenum target)) \
    X(void, VertexAttribPointer, (GLuint index, GLint size, GLenum type, GLboolean normalized, \
                                  GLsizei stride, const void *pointer)) \
    X(void, EnableVertexAttribArray, (GLuint index)) \
    X(void, DisableVertexAttribArray, (GLuint index)) \
    X(void, BufferSubData, (GLenum target, GLintptr offset, GLsizeiptr size, const void *data)) \
    X(void, PolygonMode, (GLenum face, GLenum mode)) \
    X(void, LineWidth, (GLfloat width)) \
    X(void, PointSize, (GLfloat size)) \
    X(void, GetFloatv, (GLenum pname, GLfloat *data)) \
    X(GLuint, CreateShader, (GLenum type)) \
    X(void, ShaderSource, (GLuint shader, GLsizei count, const GLchar *const *string, const GLint *length)) \
    X(void, CompileShader, (GLuint shader)) \
    X(void, GetShaderiv, (GLuint shader, GLenum pname, GLint *params)) \
    X(void, GetShaderInfoLog, (GLuint shader, GLsizei size, GLsizei *length, GLchar *log)) \
    X(void, DeleteShader, (GLuint shader)) \
    X(GLuint, CreateProgram, (void)) \
    X(void, AttachShader, (GLuint program, GLuint shader)) \
    X(void, BindAttribLocation, (GLuint program, GLuint index, const GLchar *name)) \
    X(void, LinkProgram, (GLuint program)) \
    X(void, GetProgramiv, (GLuint program, GLenum pname, GLint *params)) \
    X(void, GetProgramInfoLog, (GLuint program, GLsizei size, GLsizei *length, GLchar *log)) \
    X(void, DeleteProgram, (GLuint program)) \
    X(void, UseProgram, (GLuint program)) \
    X(GLint, GetUniformLocation, (GLuint program, const GLchar *name)) \
    X(void, Uniform1i, (GLint location, GLint v0)) \
    X(void, Uniform1iv, (GLint location, GLsizei count, const GLint *value)) \
    X(void, Uniform1fv, (GLint location, GLsizei count, const GLfloat *value)) \
    X(void, Uniform2fv, (GLint location, GLsizei count, const GLfloat *value)) \
    X(void, Uniform3fv, (GLint location, GLsizei count, const GLfloat *value)) \
    X(void, Uniform4fv, (GLint location, GLsizei count, const GLfloat *value)) \
    X(void, UniformMatrix3fv, (GLint location, GLsizei count, GLboolean transpose, const GLfloat *value)) \
    X(void, UniformMatrix4fv, (GLint location, GLsizei count, GLboolean transpose, const GLfloat *value)) \
    X(void, DrawBuffers, (GLsizei n, const GLenum *bufs)) \
    X(void, GenQueries, (GLsizei n, GLuint *ids)) \
    X(void, DeleteQueries, (GLsizei n, const GLuint *ids)) \
    X(void, BeginQuery, (GLenum target, GLuint id)) \
    X(void, EndQuery, (GLenum target)) \
    X(void, GetQueryObjectuiv, (GLuint id, GLenum pname, GLuint *params)) \
    X(void, Flush, (void)) \
    X(void, Finish, (void))

#define MACS_GL_FBO(X) \
    X(void, GenFramebuffers, (GLsizei n, GLuint *framebuffers)) \
    X(void, DeleteFramebuffers, (GLsizei n, const GLuint *framebuffers)) \
    X(void, BindFramebuffer, (GLenum target, GLuint framebuffer)) \
    X(void, FramebufferTexture2D, (GLenum target, GLenum attachment, GLenum textarget, GLuint texture, \
                                   GLint level)) \
    X(void, FramebufferRenderbuffer, (GLenum target, GLenum attachment, GLenum rbtarget, GLuint rb)) \
    X(GLenum, CheckFramebufferStatus, (GLenum target)) \
    X(void, GenRenderbuffers, (GLsizei n, GLuint *renderbuffers)) \
    X(void, DeleteRenderbuffers, (GLsizei n, const GLuint *renderbuffers)) \
    X(void, BindRenderbuffer, (GLenum target, GLuint renderbuffer)) \
    X(void, RenderbufferStorage, (GLenum target, GLenum internalformat, GLsizei width, GLsizei height))

#define MACS_GL_OPTIONAL(X) \
    X(void, ClampColorARB, (GLenum target, GLenum clamp)) \
    X(void, GetQueryObjectui64v, (GLuint id, GLenum pname, GLuint64 *params)) \
    X(void, GetQueryObjectui64vEXT, (GLuint id, GLenum pname, GLuint64 *params))

#endif
