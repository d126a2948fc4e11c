/* Private declarations shared by the files of libmacs: the GL table, object layouts, helpers. */
#ifndef MACS_INTERNAL_H
#define MACS_INTERNAL_H

#include <GL/gl.h>
#include <GL/glext.h>

#include "macs.h"
#include "first_error.h"
#include "gl_functions.h"

/* The caller's stencil bits: everything but the bits MACS reserves for splitting. */
#define MACS_STENCIL_CALLER_BITS (0xFFu & ~MACS_STENCIL_RESERVED_BITS)

/* Every GL function MACS calls; nothing in the library calls GL any other way. */
typedef struct macs_gl {
#define MACS_GL_MEMBER_(ret, name, params) ret (GLAPIENTRY *name) params;
    MACS_GL_CORE(MACS_GL_MEMBER_)
    MACS_GL_FBO(MACS_GL_MEMBER_)
    MACS_GL_OPTIONAL(MACS_GL_MEMBER_)
#undef MACS_GL_MEMBER_
} macs_gl;

/* A linked program in the context's cache, shared by every pass chunk with the same source. */
typedef struct macs_program {
    char *source;        /* the fragment source */
    char *vertex_source; /* NULL: the full-screen vertex shader */
    uint64_t hash;
    GLuint id;
    int refs;
    struct macs_program *next;
} macs_program;

struct macs_texture {
    macs_context *ctx;
    GLuint id;
    int width, height;
    macs_format format;
    macs_filter filter; /* as set at creation or wrapping: decides whether a pass may sample it */
    bool wrapped; /* the caller's GL texture (macs_texture_wrap): forgotten, never deleted */
    struct macs_texture *prev, *next;
};

/* A pixel pack buffer that one read at a time goes through (readback.c). */
typedef enum macsi_readback_state { MACSI_READBACK_EMPTY = 0, MACSI_READBACK_PENDING, MACSI_READBACK_MAPPED } macsi_readback_state;
struct macs_readback {
    macs_context *ctx;
    GLuint buffer;
    size_t capacity;       /* bytes of the buffer's store (0: none yet) */
    macsi_readback_state state;
    int width, height;     /* of the texture the pending or mapped read is of */
    macs_format format;
    const void *mapped;
    struct macs_readback *prev, *next;
};

struct macs_depth_stencil {
    macs_context *ctx;
    GLuint renderbuffer;
    int width, height;
    macs_depth_format format;
    bool internal; /* owned by the context for split passes without a caller depth/stencil */
    struct macs_depth_stencil *prev, *next;
};

struct macs_geometry {
    macs_context *ctx;
    GLuint buffer;
    int vertex_count, floats_per_vertex;
    struct macs_geometry *prev, *next;
};

/* One uniform of a pass: its value lives on the CPU and is applied to each chunk's program at run. */
typedef struct macs_pass_uniform {
    char *name;
    macs_uniform_type type;
    int count;      /* 0 = not an array */
    size_t size;    /* bytes of value */
    void *value;
} macs_pass_uniform;

/* One program + framebuffer of a pass, writing outputs [first_output, first_output + output_count). */
typedef struct macs_chunk {
    macs_program *program;
    GLuint fbo;
    int first_output;
    int output_count;
    GLint *uniform_locations; /* one per pass uniform, -1 when the program does not use it */
} macs_chunk;

struct macs_pass {
    macs_context *ctx;
    int width, height;
    int input_count;
    char **input_names;
    macs_texture **inputs;
    int output_count;
    char **output_names;
    macs_texture **outputs;
    int uniform_count;
    macs_pass_uniform *uniforms;
    int chunk_count;
    macs_chunk *chunks;
    macs_depth_stencil *depth_stencil;
    macs_depth_stencil *attached_ds; /* what the framebuffers currently hold (caller's or internal) */
    macs_depth_state depth;
    macs_stencil_state stencil;
    macs_blend blend;
    unsigned color_mask;
    bool attachments_dirty;
    /* A geometry pass (vertex_main given): its attributes' floats per vertex, the location of its
     * internal macs_inverse_size uniform, and how many attributes it enables. */
    bool geometry;
    int attribute_floats, attribute_count;
    int attribute_sizes[16];
    GLint inverse_size_location;
    GLuint query;
    bool query_issued;
    struct macs_pass *prev, *next;
};

struct macs_context {
    macs_gl gl;
    macs_allocator allocator;
    macs_logger logger;
    macs_limits real, effective;
    macs_limits claims; /* desc.claims: limits above the driver's, named when GL then refuses */
    macs_features features;
    char *gl_strings[4];
    bool allow_float_depth;
    const struct macsi_profile *profile; /* desc.profile's entry, or NULL */
    int gl_version;                      /* the version MACS goes by, major * 10 + minor */
    macs_first_error error; /* status is a macs_status */
    GLuint vertex_shader;
    GLuint vertex_buffer;
    GLuint scratch_fbo;
    macs_program *programs;
    uint64_t programs_compiled; /* cache misses that compiled and linked */
    macs_work work;             /* the counted GL calls (work.c); programs_compiled is the field above */
    macs_texture *textures;
    macs_depth_stencil *depth_stencils;
    macs_pass *passes;
    macs_timer *timers;
    macs_timer *running_timer; /* the one timer between begin and end: GL times one stretch at a time */
    bool timer_arb; /* GL_ARB_timer_query is there (else features.timer_query means the EXT one) */
    /* glGetQueryObjectui64v of the timer extension found (ARB or EXT), NULL without one */
    void (GLAPIENTRY *query_result64)(GLuint id, GLenum pname, GLuint64 *params);
    macs_readback *readbacks;
    macs_geometry *geometries;
};

/* alloc.c: allocation through the caller's hooks; every result must be checked. */
bool macsi_allocator_valid(const macs_allocator *a);
void *macsi_alloc(const macs_allocator *a, size_t size);
void *macsi_calloc(const macs_allocator *a, size_t count, size_t size);
void macsi_free(const macs_allocator *a, void *ptr);
char *macsi_strdup(const macs_allocator *a, const char *s);

/* error.c: recording and reporting errors. */
macs_status macsi_fail(macs_context *ctx, macs_status status, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((__format__(__printf__, 3, 4)))
#endif
    ;
void macsi_report(macs_logger logger, char *message, size_t size, macs_status status,
                 const char *format, ...)
#if defined(__GNUC__)
    __attribute__((__format__(__printf__, 5, 6)))
#endif
    ;
void macsi_log(const macs_context *ctx, macs_log_level level, const char *message);
void macsi_gl_drain(macs_context *ctx);
/* MACS_ERR_CONTEXT, naming where, when no GL context is current on the calling thread. */
macs_status macsi_gl_current(macs_context *ctx, const char *where);
macs_status macsi_gl_check(macs_context *ctx, const char *what);

/* gl_load.c: filling the GL table. */
bool macsi_gl_has_extension(const char *extensions, const char *name);
macs_status macsi_gl_load(macs_gl *gl, macs_get_proc_address_fn gpa, void *user, bool ext_fbo, char *missing,
                         size_t missing_size);

/* limits.c */
void macsi_limits_query(macs_context *ctx);
macs_status macsi_limits_check_caps(const macs_limits *caps, const char *field, char *message, size_t size);
int macsi_outputs_per_chunk(const macs_context *ctx);
/* effective = claims over real, then lowered by each cap (NULL: none). */
void macsi_apply_caps(macs_context *ctx, const macs_limits *claims, const macs_limits *profile_caps,
                      const macs_limits *caps);

/* profiles.c: a profile is caps, extensions taken away, float features lacking and a GL version. */
typedef struct macsi_profile {
    const char *name;
    macs_limits caps;
    const char *hidden_extensions; /* separated by spaces */
    unsigned lacking_float_features;
    int max_gl_version; /* major * 10 + minor */
} macsi_profile;
const macsi_profile *macsi_profile_find(const char *name);
/* The valid names, separated by ", ". */
void macsi_profile_names(char *out, size_t size);

/* float_features.c: refusing a sampling or blending the context's float features cannot give. */
macs_status macsi_check_filterable(macs_context *ctx, const macs_texture *t, const char *where);
macs_status macsi_check_blendable(macs_context *ctx, const macs_texture *t, macs_blend blend, const char *where);

/* program_cache.c */
/* vertex_source NULL: the shared full-screen vertex shader; else that source, with attribute i of
 * attribute_names bound to location i. */
macs_status macsi_program_acquire(macs_context *ctx, const char *vertex_source, const char *fragment_source,
                                 int input_count, char *const *input_names, int attribute_count,
                                 const char *const *attribute_names, macs_program **out);
void macsi_program_release(macs_context *ctx, macs_program *program);
void macsi_program_cache_destroy(macs_context *ctx);

/* pass_source.c */
char *macsi_pass_source(const macs_allocator *a, const macs_pass_desc *desc, int first_output, int output_count);
/* The vertex source of a geometry pass (desc->vertex_main set). */
char *macsi_pass_vertex_source(const macs_allocator *a, const macs_pass_desc *desc);
/* "float", "vec2" .. "vec4" for an attribute of 1 .. 4 floats. */
const char *macsi_attribute_type(int size);
size_t macsi_uniform_value_size(macs_uniform_type type, int count);

/* depth_stencil.c */
macs_status macsi_depth_stencil_internal(macs_context *ctx, int width, int height, macs_depth_stencil **out);
void macsi_fbo_attach_depth_stencil(macs_context *ctx, const macs_depth_stencil *ds);
macs_status macsi_fbo_check(macs_context *ctx, const char *what);

/* split.c */
macs_status macsi_split_check_state(macs_context *ctx, const macs_stencil_state *stencil, int chunk_count);
void macsi_split_apply_state(const macs_pass *pass, int chunk, bool caller_ds, bool any_ds);

/* timer.c: picks the loaded result function of the timer extension found; none loaded, no timers. */
void macsi_timer_probe(macs_context *ctx);

/* query.c */
macs_status macsi_query_begin(macs_pass *pass);
void macsi_query_end(macs_pass *pass);
void macsi_query_destroy(macs_pass *pass);

/* pass_validate.c: refuses a pass description, naming the bad argument and the rule it breaks. */
macs_status macsi_pass_validate(macs_context *ctx, const macs_pass_desc *desc);

/* texture.c: the sampling parameters of the texture bound to GL_TEXTURE_2D (no mipmaps ever). */
void macsi_texture_apply_sampling(macs_context *ctx, macs_filter filter, macs_wrap wrap);
/* texture.c: bytes per texel, the GL type and the checked pixel-store row length of host transfers. */
size_t macsi_texel_size(macs_format format);
GLenum macsi_texel_type(macs_format format);
void macsi_reset_pixel_store(macs_context *ctx);

/* pass.c: detaching destroyed objects from passes */
void macsi_pass_forget_texture(macs_context *ctx, const macs_texture *texture);
void macsi_pass_forget_depth_stencil(macs_context *ctx, const macs_depth_stencil *ds);

/* work.c: the GL calls macs_work counts, each counted and issued in one place. region is x, y, width,
 * height; the target is always GL_TEXTURE_2D level 0 and the draw one full-screen triangle. */
void macsi_draw_triangle(macs_context *ctx);
/* glDrawArrays(GL_TRIANGLES, first, count) of a geometry pass. */
void macsi_draw_triangles(macs_context *ctx, GLint first, GLsizei count);
/* glBufferData (create: the whole store, data may be NULL) or glBufferSubData of the bound
 * GL_ARRAY_BUFFER; the bytes of data handed over are counted as vertex_bytes. */
void macsi_buffer_data(macs_context *ctx, GLintptr offset, GLsizeiptr bytes, const void *data, bool create);
void macsi_use_program(macs_context *ctx, GLuint program);
void macsi_bind_framebuffer(macs_context *ctx, GLuint framebuffer);
void macsi_uniform(macs_context *ctx, macs_uniform_type type, GLint location, GLsizei count, const void *value);
void macsi_tex_image(macs_context *ctx, GLint internal_format, GLsizei width, GLsizei height, GLenum format,
                     GLenum type, const void *pixels);
void macsi_tex_sub_image(macs_context *ctx, const int region[4], GLenum format, GLenum type, const void *pixels);
void macsi_get_tex_image(macs_context *ctx, GLsizei width, GLsizei height, GLenum format, GLenum type, void *pixels);
/* glGetTexImage into the bound GL_PIXEL_PACK_BUFFER (offset 0): bytes counted, no sync (GL queues it). */
void macsi_get_tex_image_queued(macs_context *ctx, GLsizei width, GLsizei height, GLenum format, GLenum type);
/* glMapBuffer(GL_PIXEL_PACK_BUFFER, GL_READ_ONLY) of the bound buffer: one sync (it waits for the copy). */
void *macsi_map_pack_buffer(macs_context *ctx);
void macsi_finish(macs_context *ctx);
void macsi_query_result(macs_context *ctx, GLuint query, GLuint *value);
void macsi_timer_result(macs_context *ctx, GLuint query, GLuint64 *nanoseconds);

/* GL enum of a comparison, with the default given. */
GLenum macsi_gl_compare(macs_compare c, GLenum fallback);
GLenum macsi_gl_stencil_op(macs_stencil_op op);

/* Doubly linked list helpers for the context's object lists. */
#define MACS_LIST_PUSH(head, node) \
    do { \
        (node)->prev = NULL; \
        (node)->next = (head); \
        if (head) \
            (head)->prev = (node); \
        (head) = (node); \
    } while (0)
#define MACS_LIST_REMOVE(head, node) \
    do { \
        if ((node)->prev) \
            (node)->prev->next = (node)->next; \
        else \
            (head) = (node)->next; \
        if ((node)->next) \
            (node)->next->prev = (node)->prev; \
        (node)->prev = (node)->next = NULL; \
    } while (0)

#endif
