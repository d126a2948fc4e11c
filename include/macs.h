/* MACS: Massive Arbitrary Computations by Shaders.
 * GPGPU render passes over OpenGL 2.1 + ARB_framebuffer_object, with every shader in GLSL 1.10.
 * A pass runs GLSL fragment code over float textures; a pass whose outputs do not fit the hardware's
 * draw buffers is split into several programs and framebuffers and still gives the same bits. */
#ifndef MACS_H
#define MACS_H

#include <stddef.h>
#include <stdint.h>
#include <stdbool.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Marks the public functions: the shared library is built with hidden visibility and exports exactly
 * these. A caller may define MACS_API before including this header (e.g. for a Windows DLL import). */
#ifndef MACS_API
#if defined(__GNUC__) && __GNUC__ >= 4
#define MACS_API __attribute__((visibility("default")))
#else
#define MACS_API
#endif
#endif

/* ---------------------------------------------------------------------------------------------- */
/* Status codes                                                                                    */

/* Every status with its message, in one list so that codes and strings never disagree. */
#define MACS_STATUS_LIST(X) \
    X(MACS_OK, 0, "ok") \
    X(MACS_ERR_INVALID_ARGUMENT, 1, "invalid argument") \
    X(MACS_ERR_OUT_OF_MEMORY, 2, "out of memory") \
    X(MACS_ERR_GL_UNSUPPORTED, 3, "the OpenGL implementation lacks a required version, extension or function") \
    X(MACS_ERR_CONTEXT, 4, "could not create or make current a headless OpenGL context") \
    X(MACS_ERR_SHADER_COMPILE, 5, "a shader failed to compile") \
    X(MACS_ERR_SHADER_LINK, 6, "a shader program failed to link") \
    X(MACS_ERR_LIMIT, 7, "an implementation or configured limit was exceeded") \
    X(MACS_ERR_FRAMEBUFFER, 8, "a framebuffer is incomplete") \
    X(MACS_ERR_GPU_OUT_OF_MEMORY, 9, "the OpenGL implementation ran out of memory") \
    X(MACS_ERR_GL, 10, "unexpected OpenGL error") \
    X(MACS_ERR_NO_RESULT, 11, "no result is available yet")

/* Result of every fallible call; MACS_OK is 0. */
typedef enum macs_status {
#define MACS_STATUS_ENUM_(name, value, message) name = value,
    MACS_STATUS_LIST(MACS_STATUS_ENUM_)
#undef MACS_STATUS_ENUM_
    MACS_STATUS_COUNT_
} macs_status;

/* Returns the fixed English message of a status ("unknown status" for values outside the list). */
MACS_API const char *macs_status_string(macs_status status);

/* ---------------------------------------------------------------------------------------------- */
/* Logging, allocation, GL loading                                                                 */

/* Severity of a logged message; the same values as Betelgeuse's bg_log_level. */
typedef enum macs_log_level { MACS_LOG_ERROR = 0, MACS_LOG_WARNING, MACS_LOG_INFO, MACS_LOG_DEBUG } macs_log_level;

/* Receives diagnostics; the library itself never prints. message lives for the call only. */
typedef void (*macs_log_fn)(macs_log_level level, const char *message, void *user);

/* Where diagnostics go: func NULL (the default) drops them; user is passed through. */
typedef struct macs_logger {
    macs_log_fn func;
    void *user;
} macs_logger;

/* Any GL entry point, as the loaders return it; MACS casts it to the function's real type (a cast
 * between function pointer types is defined in ISO C, one from void * is not). */
typedef void (*macs_gl_proc)(void);

/* Returns the address of a GL function by name (NULL if absent); user is passed through.
 * The usual loaders need a one-line adapter each, with no cast through void *:
 *   EGL:   static macs_gl_proc egl_proc(const char *n, void *u) { (void)u; return (macs_gl_proc)eglGetProcAddress(n); }
 *   GLX:   static macs_gl_proc glx_proc(const char *n, void *u) { (void)u; return (macs_gl_proc)glXGetProcAddressARB((const GLubyte *)n); }
 *   WGL:   static macs_gl_proc wgl_proc(const char *n, void *u) { (void)u; return (macs_gl_proc)wglGetProcAddress(n); }
 *          (wglGetProcAddress knows no GL 1.1 function: fall back to GetProcAddress(opengl32_module, n),
 *          the module passed as user)
 *   GLFW:  static macs_gl_proc glfw_proc(const char *n, void *u) { (void)u; return (macs_gl_proc)glfwGetProcAddress(n); }
 *   SDL 3: static macs_gl_proc sdl_proc(const char *n, void *u) { (void)u; return (macs_gl_proc)SDL_GL_GetProcAddress(n); }
 *   SDL 2 returns void *, so its adapter needs the conversion POSIX (not ISO C) defines:
 *          static macs_gl_proc sdl2_proc(const char *n, void *u)
 *          { macs_gl_proc f; void *p = SDL_GL_GetProcAddress(n); (void)u; memcpy(&f, &p, sizeof f); return f; }
 * A headless context gives its own: macs_headless_get_proc_address(). */
typedef macs_gl_proc (*macs_get_proc_address_fn)(const char *name, void *user);

/* Defaults: all NULL = malloc, realloc and free of the C library.
 * Set alloc, realloc and free together or none of them. */
typedef struct macs_allocator {
    void *(*alloc)(size_t size, void *user);
    void *(*realloc)(void *ptr, size_t size, void *user);
    void (*free)(void *ptr, void *user);
    void *user;
} macs_allocator;

/* ---------------------------------------------------------------------------------------------- */
/* Headless OpenGL contexts                                                                        */

/* Which headless backend to use. DEFAULT tries, in this order, and keeps the first that gives a
 * context: EGL_DEVICE on each device EGL lists (a GPU, where its driver runs headless, as NVIDIA's and
 * Mesa's do; Mesa lists its software device last), EGL surfaceless, then OSMesa (always software). */
typedef enum macs_headless_backend {
    MACS_HEADLESS_DEFAULT = 0,
    MACS_HEADLESS_OSMESA,
    MACS_HEADLESS_EGL,        /* EGL surfaceless (EGL_MESA_platform_surfaceless) */
    MACS_HEADLESS_EGL_DEVICE  /* EGL device platform (EGL_EXT_platform_device), device desc.device_index */
} macs_headless_backend;

/* Defaults: backend DEFAULT (the order above); device_index 0; libc allocator; no logger.
 * device_index picks an EGL device in the order eglQueryDevicesEXT lists them (0 = the first): with
 * EGL_DEVICE only that device is tried; with DEFAULT, 0 tries every device in turn and n > 0 tries
 * device n only, before EGL surfaceless and OSMesa. An index beyond the devices EGL lists is refused
 * (MACS_ERR_INVALID_ARGUMENT, naming the index and the count), never replaced by another device or
 * backend; where EGL has no device platform or lists no device, DEFAULT moves on. OSMesa and EGL
 * surfaceless take only 0. The logger gets one info line saying what the context runs on.
 * The library never reads environment variables to choose the backend or the device. The backends'
 * libraries (libEGL.so.1, libOSMesa.so.8 or .so.6) are loaded at run time, when first asked for: one
 * that cannot be loaded is reported with the names tried (MACS_ERR_CONTEXT), and DEFAULT moves on. */
typedef struct macs_headless_desc {
    macs_headless_backend backend;
    macs_allocator allocator;
    macs_logger logger;
    int device_index;
} macs_headless_desc;

/* What a headless context runs on, found at creation; the strings belong to the headless context,
 * live as long as it and are never NULL. */
typedef struct macs_headless_info {
    macs_headless_backend backend; /* the backend created (never DEFAULT, but for a NULL context) */
    int device_index;              /* EGL_DEVICE: the device's index in EGL's list; else -1 */
    int device_count;              /* EGL_DEVICE: how many devices EGL lists; else 0 */
    const char *device_name;       /* EGL_DEVICE: "software" (EGL_MESA_device_software), the DRM device
                                      file or render node, or the device's renderer name; else "" */
    const char *device_extensions; /* EGL_DEVICE: the device's extension string (EGL_EXT_device_query); else "" */
    const char *renderer;          /* GL_RENDERER of the context ("" where GL gives none) */
} macs_headless_info;

/* An OpenGL 2.1 (compatibility) context without a window, current on the creating thread. */
typedef struct macs_headless macs_headless;

/* Creates a headless context and makes it current; on failure message (if not NULL) gets the reason. */
MACS_API macs_status macs_headless_create(const macs_headless_desc *desc, macs_headless **out, char *message,
                                          size_t message_size);

/* Releases and destroys a headless context (NULL is ignored). */
MACS_API void macs_headless_destroy(macs_headless *headless);

/* Makes the headless context current on the calling thread again. */
MACS_API macs_status macs_headless_make_current(macs_headless *headless);

/* Returns the backend that was actually created. */
MACS_API macs_headless_backend macs_headless_backend_used(const macs_headless *headless);

/* Copies what the headless context runs on: backend, EGL device and GL renderer (NULL: DEFAULT, -1, ""). */
MACS_API void macs_headless_get_info(const macs_headless *headless, macs_headless_info *info);

/* Returns the get_proc_address matching this backend (OSMesaGetProcAddress or eglGetProcAddress of the
 * library the context loaded); it needs macs_headless_proc_user as its user pointer, and returns NULL
 * for every name without it. */
MACS_API macs_get_proc_address_fn macs_headless_get_proc_address(const macs_headless *headless);

/* Returns the user pointer to pass along with macs_headless_get_proc_address(). */
MACS_API void *macs_headless_proc_user(const macs_headless *headless);

/* ---------------------------------------------------------------------------------------------- */
/* Context                                                                                         */

/* Hardware limits that decide how passes are split; in a caps override 0 means "what GL reports". */
typedef struct macs_limits {
    int max_draw_buffers;      /* GL_MAX_DRAW_BUFFERS */
    int max_color_attachments; /* GL_MAX_COLOR_ATTACHMENTS */
    int max_texture_units;     /* GL_MAX_TEXTURE_IMAGE_UNITS: inputs of one pass */
    int max_texture_size;      /* GL_MAX_TEXTURE_SIZE (and GL_MAX_RENDERBUFFER_SIZE, GL_MAX_VIEWPORT_DIMS):
                                  the largest texture a pass can draw whole */
    int max_uniform_components; /* GL_MAX_FRAGMENT_UNIFORM_COMPONENTS: floats of uniforms one fragment
                                   shader may declare (at least 64, as GL 2.0 promises) */
    int max_varying_components; /* GL_MAX_VARYING_FLOATS: MACS's own vertex shader passes one vec2
                                   (macs_uv, one 4-float slot); pass code cannot add varyings, so
                                   nothing else spends them. A context allowing fewer than 4 is refused. */
} macs_limits;

/* Every field of macs_limits, in order: the one list that caps, claims, profiles and their checks
 * walk, so that a new limit is added here and in the struct above and nowhere else. */
#define MACS_LIMIT_FIELDS(X) \
    X(max_draw_buffers) X(max_color_attachments) X(max_texture_units) X(max_texture_size) \
    X(max_uniform_components) X(max_varying_components)

/* Float capabilities GL 2.1 cannot be asked about: whether RGBA32F / RGBA16F textures filter linearly,
 * and whether float render targets blend. Drivers without them fall back silently (nearest sampling,
 * or software), so MACS refuses a pass that would need one the context lacks (MACS_ERR_LIMIT, naming
 * the input or output and the feature) rather than give wrong output. GeForce 6/7 filter and blend
 * only 16-bit floats; Radeon X1000 filters no float texture and blends only 16-bit floats. */
typedef enum macs_float_feature {
    MACS_FLOAT32_FILTER = 1, /* MACS_FILTER_LINEAR on an RGBA32F input */
    MACS_FLOAT16_FILTER = 2, /* MACS_FILTER_LINEAR on an RGBA16F input */
    MACS_FLOAT32_BLEND = 4,  /* a blend other than NONE into an RGBA32F output */
    MACS_FLOAT16_BLEND = 8   /* a blend other than NONE into an RGBA16F output */
} macs_float_feature;

/* The named limit profiles (desc.profile), each making any driver behave as a smaller one: caps,
 * extensions treated as absent, float features lacking, and a GL version. Values and their sources
 * are in docs/profiles.md.
 *   "geforce7"     NVIDIA GeForce 7 (G7x; GeForce 6 alike): 4 draw buffers, 16 units, 4096 texels,
 *                  896 uniform floats, 32 varying floats; no float32 filter or blend; GL 2.1
 *   "radeon_x1600" ATI Radeon X1600 (RV530, R5xx): 4 draw buffers, 16 units, 4096 texels, 1024
 *                  uniform floats, 40 varying floats; no float filter at all, no float32 blend;
 *                  EXT_framebuffer_object only; GL 2.1
 *   "gma_x3100"    Intel GMA X3100 (GM965, Gen4): 8 draw buffers, 16 units, 8192 texels, 1024
 *                  uniform floats, 64 varying floats; no float32 filter; GL 2.1
 *   "gl21"         the least GL 2.1 + ARB_framebuffer_object promises: 1 draw buffer, 2 units, 64
 *                  texels, 64 uniform floats, 32 varying floats; no optional extension, no float
 *                  filter or blend */
#define MACS_PROFILE_NAMES "geforce7, radeon_x1600, gma_x3100, gl21"

/* Defaults: get_proc_address is required; no logger; libc allocator; caps all 0 (no override; a cap
 * can only lower a limit, never raise it); allow_float_depth false (24-bit fixed depth); profile NULL
 * (none); claims all 0 (none); hidden_extensions NULL (none); max_gl_version 0 (the context's);
 * lacking_float_features 0 (every float feature the driver has, which MACS assumes is all).
 * A profile combines with the rest: the smaller of a profile's limit and a cap wins, the extensions
 * and float features a profile takes away join those the desc names, and the lower GL version wins.
 * An unknown profile is refused (MACS_ERR_INVALID_ARGUMENT, naming desc.profile and the valid names). */
typedef struct macs_context_desc {
    macs_get_proc_address_fn get_proc_address;
    void *get_proc_address_user;
    macs_logger logger;
    macs_allocator allocator;
    macs_limits caps;
    bool allow_float_depth; /* use DEPTH32F_STENCIL8 when ARB_depth_buffer_float is present */
    const char *profile;    /* a name of MACS_PROFILE_NAMES, or NULL */
    /* Limits reported and obeyed although the driver has less (0: none), to test the paths a big GPU
     * takes on a small one, e.g. max_texture_size 32768 where the driver has 16384. An allocation GL
     * then refuses comes back as MACS_ERR_LIMIT or MACS_ERR_GPU_OUT_OF_MEMORY naming what was asked,
     * never as a crash; a claimed draw buffer, unit or uniform beyond the driver's fails in GL the same
     * way. For tests only: a renderer sized by claims can fail where a real one would not. */
    macs_limits claims;
    /* Extension names, separated by spaces, that MACS treats as absent whatever the driver says:
     * optional ones (GL_ARB_depth_buffer_float, GL_ARB_color_buffer_float, GL_ARB_half_float_pixel,
     * GL_ARB_framebuffer_object for the EXT path) and required ones (GL_ARB_texture_float, which makes
     * macs_context_create refuse just as a driver without it would). Each name must start "GL_". */
    const char *hidden_extensions;
    /* 0: the context's version. 21 (major * 10 + minor, at least 21): MACS ignores what a later core
     * version adds (framebuffer objects are core from 3.0), so hidden extensions count on a context
     * that a driver made 4.6 by default. */
    int max_gl_version;
    unsigned lacking_float_features; /* macs_float_feature bits the hardware lacks */
} macs_context_desc;

/* Optional OpenGL features found in the extension string (less those desc.hidden_extensions or the
 * profile hide), and the float features GL 2.1 cannot report (true unless the desc or the profile
 * says the hardware lacks them). */
typedef struct macs_features {
    bool arb_framebuffer_object; /* false: the EXT_framebuffer_object + EXT_packed_depth_stencil path */
    bool depth_buffer_float;     /* ARB_depth_buffer_float */
    bool color_buffer_float;     /* ARB_color_buffer_float */
    bool half_float_pixel;       /* ARB_half_float_pixel */
    bool timer_query;            /* ARB_timer_query or EXT_timer_query: macs_timer measures GPU time */
    bool float32_filter;         /* RGBA32F inputs filter linearly (macs_float_feature) */
    bool float16_filter;         /* RGBA16F inputs filter linearly */
    bool float32_blend;          /* RGBA32F outputs blend */
    bool float16_blend;          /* RGBA16F outputs blend */
    float max_line_width;        /* GL_ALIASED_LINE_WIDTH_RANGE's upper end (at least 1) */
    float max_point_size;        /* GL_ALIASED_POINT_SIZE_RANGE's upper end (at least 1) */
} macs_features;

/* The GL strings of the current context; any of them may be NULL (Mesa returns NULL for the shading
 * language version under MESA_GLSL_VERSION_OVERRIDE=110). */
typedef struct macs_gl_info {
    const char *vendor;
    const char *renderer;
    const char *version;
    const char *shading_language_version;
} macs_gl_info;

/* A MACS context: works on the GL context current on the calling thread, which must stay current for
 * every call on this context and its objects. One thread per context. MACS sets the GL state it needs
 * (framebuffer, program, textures, tests, blending, viewport, scissor) on every call and leaves it
 * changed, apart from restoring framebuffer 0, program 0 and the pixel-store defaults. */
typedef struct macs_context macs_context;

/* Creates a context over the current GL context; on failure message (if not NULL) gets the reason. */
MACS_API macs_status macs_context_create(const macs_context_desc *desc, macs_context **out, char *message,
                                         size_t message_size);

/* Destroys a context and every texture, depth/stencil object and pass still alive in it (NULL ok). */
MACS_API void macs_context_destroy(macs_context *ctx);

/* Returns the first error recorded since creation or the last clear (MACS_OK if none). */
MACS_API macs_status macs_context_error(const macs_context *ctx);

/* Returns the message of the first recorded error ("" if none); it holds shader info logs. */
MACS_API const char *macs_context_error_message(const macs_context *ctx);

/* Forgets the recorded error so that the next one is kept. */
MACS_API void macs_context_clear_error(macs_context *ctx);

/* Copies the limits GL reports (real) and the ones passes obey (effective: the claims, then the
 * profile's caps and desc.caps); either may be NULL. */
MACS_API void macs_context_get_limits(const macs_context *ctx, macs_limits *real, macs_limits *effective);

/* The effective max_uniform_components (after caps), for callers that size generated shaders by it
 * (0 for a NULL context). */
MACS_API int macs_context_max_uniform_components(const macs_context *ctx);

/* How many programs the context has compiled and linked so far: passes whose source its program
 * cache already held count nothing (0 for a NULL context). The difference over a frame tells what
 * the frame compiled. */
MACS_API uint64_t macs_context_programs_compiled(const macs_context *ctx);

/* The GL work a context has issued since its creation, counted exactly at the GL calls themselves
 * (src/macs/work.c), so the counts are the same on every driver and a caller may assert them. Every
 * count only grows; the difference of two copies (macs_work_since) is the work between them.
 * Nothing is counted twice: a GL call is counted where MACS issues it, whichever function asked. */
typedef struct macs_work {
    uint64_t draws;             /* glDrawArrays calls: one per chunk of a pass run, one per pass draw */
    uint64_t program_binds;     /* glUseProgram calls, the unbinding ones (program 0) included */
    uint64_t framebuffer_binds; /* glBindFramebuffer calls, the unbinding ones (framebuffer 0) included */
    uint64_t uniform_calls;     /* glUniform* calls: each pass uniform a chunk's program uses, per run,
                                   and each sampler set once when a program is linked */
    uint64_t upload_bytes;      /* texel bytes handed to glTexImage2D and glTexSubImage2D (width x height
                                   x bytes per texel of the format and type given; a texture created
                                   without data counts 0) */
    uint64_t vertex_bytes;      /* vertex bytes handed to glBufferData and glBufferSubData by
                                   macs_geometry_create and macs_geometry_upload */
    uint64_t readback_bytes;    /* texel bytes glGetTexImage wrote into host memory or queued into a
                                   read-back buffer (macs_texture_read_begin), counted the same way */
    uint64_t syncs;             /* calls that wait for the GPU: glFinish, glGetTexImage into host memory,
                                   glMapBuffer of a read-back buffer (macs_readback_map), and a query's
                                   GL_QUERY_RESULT read (macs_pass_occlusion_result, macs_timer_result);
                                   a queued read (macs_texture_read_begin) is none */
    uint64_t programs_compiled; /* programs compiled and linked (macs_context_programs_compiled) */
    uint64_t timer_results;     /* macs_timer_result reads (each one of the syncs above; a read after
                                   the work is done, such as after a read-back, finds the time ready) */
} macs_work;

/* Copies the context's work counters (all zero for a NULL context; work may not be NULL). */
MACS_API void macs_context_get_work(const macs_context *ctx, macs_work *work);

/* after - before, field by field: the work issued between two macs_context_get_work copies. */
MACS_API macs_work macs_work_since(const macs_work *after, const macs_work *before);

/* Copies the GL strings read at creation. */
MACS_API void macs_context_get_gl_info(const macs_context *ctx, macs_gl_info *info);

/* Copies which optional extensions were found and which float features the context has. */
MACS_API void macs_context_get_features(const macs_context *ctx, macs_features *features);

/* Waits until GL has finished every command issued so far (glFinish): for timing, not correctness. */
MACS_API void macs_context_finish(macs_context *ctx);

/* Submits every command issued so far without waiting for it (glFlush), so the GPU works on it while
 * the caller does host work (NULL ok). */
MACS_API void macs_context_flush(macs_context *ctx);

/* ---------------------------------------------------------------------------------------------- */
/* GPU timers                                                                                      */

/* A GPU timer: the time the GPU spent on the GL commands issued between macs_timer_begin and
 * macs_timer_end, from a GL_TIME_ELAPSED query (GL_ARB_timer_query, else GL_EXT_timer_query;
 * macs_features.timer_query says whether either is there). Neither begin nor end waits, and nothing
 * is drained between commands, so timing does not change the work it times. macs_timer_result waits
 * until the commands are done: read it after the work has finished anyway (after a read-back), and
 * it costs no stall. GL times one stretch at a time, so one timer of a context runs at once. A timer
 * may be begun again once ended; its result is then of the latest stretch. Destroyed with its
 * context at the latest. */
typedef struct macs_timer macs_timer;

/* MACS_ERR_GL_UNSUPPORTED, naming both extensions, where the context has neither (or its desc or
 * profile hides them). */
MACS_API macs_status macs_timer_create(macs_context *ctx, macs_timer **timer);
/* MACS_ERR_INVALID_ARGUMENT when this or another timer of the context is running. */
MACS_API macs_status macs_timer_begin(macs_timer *timer);
/* MACS_ERR_INVALID_ARGUMENT when the timer is not running. */
MACS_API macs_status macs_timer_end(macs_timer *timer);
/* The GPU time of the timer's last stretch, in nanoseconds, as the driver reports it; waits for it.
 * MACS_ERR_NO_RESULT when the timer was never ended, or is running. A driver's value may be wrong:
 * Mesa's llvmpipe (22.3) reports its absolute clock for a stretch begun before the GL context's first
 * draw, so a caller should hold a time to the host's clock (no stretch outlasts the wall time from its
 * begin to its result). */
MACS_API macs_status macs_timer_result(macs_timer *timer, uint64_t *nanoseconds);
/* Ends a running timer first. NULL is ignored. */
MACS_API void macs_timer_destroy(macs_timer *timer);

/* ---------------------------------------------------------------------------------------------- */
/* Textures                                                                                        */

/* Texel format of a texture; float formats exchange float data, RGBA8 exchanges uint8_t data. */
typedef enum macs_format {
    MACS_FORMAT_DEFAULT = 0, /* RGBA32F */
    MACS_FORMAT_RGBA32F,
    MACS_FORMAT_RGBA16F,
    MACS_FORMAT_RGBA8
} macs_format;

/* Sampling filter of a texture input (no mipmaps ever). */
typedef enum macs_filter { MACS_FILTER_DEFAULT = 0, MACS_FILTER_NEAREST, MACS_FILTER_LINEAR } macs_filter;

/* Wrap mode of a texture input in both directions. */
typedef enum macs_wrap { MACS_WRAP_DEFAULT = 0, MACS_WRAP_CLAMP_TO_EDGE, MACS_WRAP_REPEAT } macs_wrap;

/* Defaults: width and height required (1 .. max_texture_size); format RGBA32F; filter NEAREST;
 * wrap CLAMP_TO_EDGE; data NULL (contents undefined until written); stride 0 (tight rows).
 * data holds height rows of width RGBA texels, bottom row first; stride is in bytes and must be a
 * multiple of the texel size (16 bytes for float formats, 4 for RGBA8). */
typedef struct macs_texture_desc {
    int width;
    int height;
    macs_format format;
    macs_filter filter;
    macs_wrap wrap;
    const void *data;
    size_t stride;
} macs_texture_desc;

/* A 2D RGBA texture usable as pass input and output. */
typedef struct macs_texture macs_texture;

/* Creates a texture, optionally with initial contents. */
MACS_API macs_status macs_texture_create(macs_context *ctx, const macs_texture_desc *desc, macs_texture **out);

/* Destroys a texture; passes that used it lose that input or output until another is set (NULL ok). */
MACS_API void macs_texture_destroy(macs_texture *texture);

/* Replaces the whole contents from caller memory (float for float formats, uint8_t for RGBA8). */
MACS_API macs_status macs_texture_upload(macs_texture *texture, const void *data, size_t stride);

/* Replaces the width x height texels whose bottom-left texel is (x, y) (texel coordinates, row 0 at
 * the bottom) from caller memory laid out as for macs_texture_upload: height rows of width texels,
 * bottom row first, stride 0 = tight rows. A region not inside the texture, or empty, is refused
 * (MACS_ERR_INVALID_ARGUMENT, naming it and the size). */
MACS_API macs_status macs_texture_upload_region(macs_texture *texture, int x, int y, int width, int height,
                                                const void *data, size_t stride);

/* Reads the whole contents back into caller memory; RGBA32F returns exactly the bits written. */
MACS_API macs_status macs_texture_read(macs_texture *texture, void *data, size_t stride);

/* A read-back buffer (a GL pixel pack buffer, core in GL 2.1) for reading a texture without waiting:
 * macs_texture_read_begin queues the copy of the texture into it behind the GL work already issued
 * and returns at once; the caller issues more work (the next tile of an image) or does host work,
 * then takes the texels with macs_readback_map (which waits for the copy, if it is not done) and
 * macs_readback_unmap, or with macs_readback_read. One read at a time: begin, map, unmap, begin...
 * The texture may change or be destroyed once the read is begun: the buffer holds its copy. The
 * buffer's store is made at the first begin and kept while the texture size stays the same.
 * Work counted (macs_work): a begin counts the texel bytes and no sync, a map one sync; so a read
 * through a readback counts what macs_texture_read does. */
typedef struct macs_readback macs_readback;

/* Creates an empty readback of ctx; macs_context_destroy destroys those still alive. */
MACS_API macs_status macs_readback_create(macs_context *ctx, macs_readback **out);

/* Destroys a readback, unmapping it first if mapped (NULL ok). */
MACS_API void macs_readback_destroy(macs_readback *readback);

/* Queues the read of the whole texture into readback and submits it (glFlush) without waiting; a read
 * begun earlier and not taken is replaced. Errors: MACS_ERR_INVALID_ARGUMENT for a NULL argument, a
 * readback of another context or one still mapped; MACS_ERR_GPU_OUT_OF_MEMORY when GL cannot make the
 * buffer's store. After an error readback holds no read. */
MACS_API macs_status macs_texture_read_begin(macs_texture *texture, macs_readback *readback);

/* Waits for the read begun into readback and maps it: *texels points at the texture's rows, bottom
 * row first, *stride bytes apart (width x texel size; stride may be NULL), valid until
 * macs_readback_unmap or macs_readback_destroy. Errors: MACS_ERR_NO_RESULT when no read was begun
 * (or it was taken already); MACS_ERR_INVALID_ARGUMENT when mapped already or texels is NULL;
 * MACS_ERR_GL when the driver returns no mapping (glMapBuffer NULL): the read is then lost, never
 * half given, and *texels is NULL. */
MACS_API macs_status macs_readback_map(macs_readback *readback, const void **texels, size_t *stride);

/* Unmaps a mapped readback, which then holds no read. MACS_ERR_GL when GL says the buffer's contents
 * were lost while mapped (glUnmapBuffer GL_FALSE): the texels read from the map may be wrong. */
MACS_API macs_status macs_readback_unmap(macs_readback *readback);

/* Map, copy into caller memory as macs_texture_read lays it out (stride 0 = tight rows, else a
 * multiple of the texel size of at least a row), unmap. */
MACS_API macs_status macs_readback_read(macs_readback *readback, void *data, size_t stride);

/* Sets every texel to one value (for RGBA8 the value is scaled from 0..1). */
MACS_API macs_status macs_texture_clear(macs_texture *texture, const float rgba[4]);

/* Reports the size of a texture (either pointer may be NULL). */
MACS_API void macs_texture_size(const macs_texture *texture, int *width, int *height);

/* Reports the format of a texture. */
MACS_API macs_format macs_texture_format(const macs_texture *texture);

/* Returns the GL name (a GLuint) of a texture, for the caller's own GL code: glBindTexture(GL_TEXTURE_2D,
 * name) to draw it, or to sample it in a shader of the caller's (0 for NULL). Its level-0 image holds
 * row 0 at the bottom, as every MACS texture and GL do. The name stays MACS's for a texture MACS
 * created: never delete it or respecify its image (glTexImage2D); changing its filter or wrap
 * parameters changes how passes sample it. */
MACS_API unsigned macs_texture_gl_name(const macs_texture *texture);

/* Returns the context a texture belongs to (NULL for NULL). */
MACS_API macs_context *macs_texture_context(const macs_texture *texture);

/* Defaults: gl_name required; width and height 0 = as GL reports the level-0 image, else they must
 * equal it; format DEFAULT = as GL reports its internal format, else it must equal it; filter
 * NEAREST; wrap CLAMP_TO_EDGE.
 * The texture must be a GL_TEXTURE_2D texture of the GL context current for ctx with a level-0 image
 * in GL_RGBA8 (or unsized GL_RGBA that GL stores in 8 bits a channel), GL_RGBA32F_ARB or
 * GL_RGBA16F_ARB, of at most max_texture_size per side. */
typedef struct macs_texture_wrap_desc {
    unsigned gl_name; /* a GLuint from the caller's glGenTextures, bound and given an image */
    int width;
    int height;
    macs_format format;
    macs_filter filter;
    macs_wrap wrap;
} macs_texture_wrap_desc;

/* Wraps a caller-owned GL texture as a macs_texture that works wherever one MACS created does (pass
 * input and output, upload, read, clear), checked against GL first (glIsTexture, glBindTexture,
 * glGetTexLevelParameteriv). Wrapping sets its minification and magnification filters and its wrap
 * modes as desc says (a mipmap filter would make passes sample it as incomplete) and changes
 * nothing else. The texture stays the caller's: macs_texture_destroy, and macs_context_destroy for
 * every wrapped texture still alive, detach it from MACS's framebuffers and forget it, never
 * deleting it; until then the caller must not delete it or respecify its image.
 * Errors: MACS_ERR_INVALID_ARGUMENT naming desc.gl_name when it is 0, names no texture
 * (glIsTexture false), a texture of another target or one without a level-0 image or of another
 * internal format, and naming desc.width, desc.height or desc.format when one given differs from
 * what GL reports; MACS_ERR_LIMIT when the texture is larger than max_texture_size. */
MACS_API macs_status macs_texture_wrap(macs_context *ctx, const macs_texture_wrap_desc *desc, macs_texture **out);

/* ---------------------------------------------------------------------------------------------- */
/* Depth/stencil buffers                                                                           */

/* Stencil bits MACS owns to split passes exactly; callers own the other bits (0x7F), which keep their
 * values across passes. MACS keeps the reserved bit 0 between runs. */
#define MACS_STENCIL_RESERVED_BITS 0x80u

/* Depth format of a depth/stencil object. */
typedef enum macs_depth_format {
    MACS_DEPTH24_STENCIL8 = 1, /* the GL 2.1 baseline */
    MACS_DEPTH32F_STENCIL8     /* ARB_depth_buffer_float, when present and allowed by the context */
} macs_depth_format;

/* Defaults: width and height required (they must equal the size of the outputs of passes using it);
 * format 0 = DEPTH32F_STENCIL8 when the context allows float depth and GL has it, else
 * DEPTH24_STENCIL8. MACS_DEPTH24_STENCIL8 asks for 24-bit depth even where float depth is allowed. */
typedef struct macs_depth_stencil_desc {
    int width;
    int height;
    macs_depth_format format;
} macs_depth_stencil_desc;

/* A packed depth + 8-bit stencil buffer, cleared to depth 1 and stencil 0 at creation. */
typedef struct macs_depth_stencil macs_depth_stencil;

/* Creates a depth/stencil object. */
MACS_API macs_status macs_depth_stencil_create(macs_context *ctx, const macs_depth_stencil_desc *desc,
                                               macs_depth_stencil **out);

/* Destroys a depth/stencil object; passes using it refuse to run until given another (NULL ok). */
MACS_API void macs_depth_stencil_destroy(macs_depth_stencil *ds);

/* Reports the depth format actually allocated. */
MACS_API macs_depth_format macs_depth_stencil_format(const macs_depth_stencil *ds);

/* Sets depth to depth (clamped to 0..1) and the stencil bits in write_mask to stencil; the reserved
 * bits are always cleared to 0, whatever the mask. */
MACS_API macs_status macs_depth_stencil_clear(macs_depth_stencil *ds, float depth, unsigned stencil, unsigned write_mask);

/* ---------------------------------------------------------------------------------------------- */
/* Passes                                                                                          */

/* GLSL type of a pass uniform. */
typedef enum macs_uniform_type {
    MACS_UNIFORM_FLOAT = 1,
    MACS_UNIFORM_VEC2,
    MACS_UNIFORM_VEC3,
    MACS_UNIFORM_VEC4,
    MACS_UNIFORM_INT,
    MACS_UNIFORM_BOOL,
    MACS_UNIFORM_MAT3,
    MACS_UNIFORM_MAT4
} macs_uniform_type;

/* A uniform of a pass: count 0 declares a single value, count n > 0 an array of n. */
typedef struct macs_uniform_desc {
    const char *name;
    macs_uniform_type type;
    int count;
} macs_uniform_desc;

/* A texture input, declared as `uniform sampler2D name;` (sample it at texture2D(name, macs_uv) to
 * read the texel under the output pixel, or anywhere else). */
typedef struct macs_input_desc {
    const char *name;
} macs_input_desc;

/* An output: name (an identifier used in messages) and a GLSL vec4 expression written to it, evaluated
 * after the pass's main code in the same scope. */
typedef struct macs_output_desc {
    const char *name;
    const char *value;
} macs_output_desc;

/* Comparison function of the depth and stencil tests. */
typedef enum macs_compare {
    MACS_COMPARE_DEFAULT = 0, /* LESS for depth, ALWAYS for stencil */
    MACS_COMPARE_NEVER,
    MACS_COMPARE_LESS,
    MACS_COMPARE_EQUAL,
    MACS_COMPARE_LEQUAL,
    MACS_COMPARE_GREATER,
    MACS_COMPARE_NOTEQUAL,
    MACS_COMPARE_GEQUAL,
    MACS_COMPARE_ALWAYS
} macs_compare;

/* Stencil operation. */
typedef enum macs_stencil_op {
    MACS_STENCIL_OP_DEFAULT = 0, /* KEEP */
    MACS_STENCIL_OP_KEEP,
    MACS_STENCIL_OP_ZERO,
    MACS_STENCIL_OP_REPLACE,
    MACS_STENCIL_OP_INCR,
    MACS_STENCIL_OP_DECR,
    MACS_STENCIL_OP_INVERT
} macs_stencil_op;

/* Defaults: test off; func LESS; write off (depth writes happen only with test and write on). */
typedef struct macs_depth_state {
    bool test;
    bool write;
    macs_compare func;
} macs_depth_state;

/* Defaults: test off; func ALWAYS; ref 0; read_mask and write_mask 0 = every caller bit (0x7F); all ops
 * KEEP. The reserved bits are removed from ref and both masks. A pass that needs splitting accepts only
 * KEEP for fail and depth_fail and KEEP or REPLACE for pass (else MACS_ERR_LIMIT at creation). */
typedef struct macs_stencil_state {
    bool test;
    macs_compare func;
    unsigned ref;
    unsigned read_mask;
    unsigned write_mask;
    macs_stencil_op fail;
    macs_stencil_op depth_fail;
    macs_stencil_op pass;
} macs_stencil_state;

/* Blending of every output with its texture's contents. */
typedef enum macs_blend {
    MACS_BLEND_NONE = 0,  /* replace */
    MACS_BLEND_ADD,       /* ONE, ONE */
    MACS_BLEND_MULTIPLY,  /* DST_COLOR, ZERO */
    MACS_BLEND_MAX        /* the larger of source and destination, per channel (GL_MAX, core since 1.4) */
} macs_blend;

/* Colour write mask bits; MACS_COLOR_MASK_NONE writes no channel at all. */
enum {
    MACS_COLOR_MASK_R = 1,
    MACS_COLOR_MASK_G = 2,
    MACS_COLOR_MASK_B = 4,
    MACS_COLOR_MASK_A = 8,
    MACS_COLOR_MASK_NONE = 16
};

/* A vertex attribute of a geometry pass: declared as `attribute <float|vec2|vec3|vec4> name;` in its
 * vertex shader. A geometry's vertices hold the pass's attributes in declaration order, packed. */
typedef struct macs_attribute_desc {
    const char *name;
    int size; /* floats: 1 .. 4 */
} macs_attribute_desc;

/* Defaults: functions and main NULL (empty); no inputs; no uniforms; outputs required (output_count >= 1,
 * output_textures[i] for each output, all of one size); input_textures NULL (bind them later with
 * macs_pass_set_input); depth_stencil NULL; depth and stencil tests off; blend NONE; color_mask 0 = RGBA.
 * In the generated shader, source string 1 is functions, 2 is main and 3 + i is output i, and lines
 * count from 1 within each, so info logs point into the caller's own strings (Mesa prints the line
 * right but every source number as 0). Identifiers starting with gl_ or macs_, or holding "__", are
 * reserved. Each chunk of a split pass runs main again, so main must give the same result (and make
 * the same discard decision) each time it runs for a pixel: no side effects, as GLSL 1.10 allows none. */
typedef struct macs_pass_desc {
    const char *functions;
    const char *main;
    const macs_input_desc *inputs;
    int input_count;
    const macs_uniform_desc *uniforms;
    int uniform_count;
    const macs_output_desc *outputs;
    int output_count;
    macs_texture *const *output_textures;
    macs_texture *const *input_textures;
    macs_depth_stencil *depth_stencil;
    macs_depth_state depth;
    macs_stencil_state stencil;
    macs_blend blend;
    unsigned color_mask;
    /* A geometry pass: vertex_main non-NULL (statements that must set gl_Position) makes the pass draw
     * the triangles of a macs_geometry with macs_pass_draw instead of running over its outputs with
     * macs_pass_run. Its vertex shader declares the attributes, every uniform of the pass (samplers
     * excepted: the inputs are for the fragment code) and `varyings`, then vertex_functions, then
     * main; varyings (declarations such as "varying float id;") go into both shaders. In the
     * fragment code of a geometry pass macs_uv is gl_FragCoord.xy over the output size, the same
     * point a full-screen pass interpolates. A geometry pass never splits: one with more outputs
     * than the limits allow in one program is refused (MACS_ERR_LIMIT). */
    const char *vertex_functions;
    const char *vertex_main;
    const char *varyings;
    const macs_attribute_desc *attributes;
    int attribute_count; /* 1 .. 16 with vertex_main, 0 without */
} macs_pass_desc;

/* A compiled render pass: one or more programs and framebuffers, run as a full-screen quad. */
typedef struct macs_pass macs_pass;

/* Compiles (or reuses from the context's cache) the programs of a pass and builds its framebuffers. */
MACS_API macs_status macs_pass_create(macs_context *ctx, const macs_pass_desc *desc, macs_pass **out);

/* Destroys a pass (NULL ok). */
MACS_API void macs_pass_destroy(macs_pass *pass);

/* Binds a texture (or NULL) to input index; it must not be one of the pass's outputs. */
MACS_API macs_status macs_pass_set_input(macs_pass *pass, int index, macs_texture *texture);

/* Binds a texture to output index; it must have the size of the pass's outputs. */
MACS_API macs_status macs_pass_set_output(macs_pass *pass, int index, macs_texture *texture);

/* Binds another depth/stencil object (or NULL if no test is enabled); it must have the output size. */
MACS_API macs_status macs_pass_set_depth_stencil(macs_pass *pass, macs_depth_stencil *ds);

/* Stores a uniform value, applied at every run: float data for float/vec/mat types (column-major
 * matrices), int data for int and bool; arrays take count elements. */
MACS_API macs_status macs_pass_set_uniform(macs_pass *pass, const char *name, const void *value);

/* Returns how many program/framebuffer chunks the pass runs as (1 when it fits the limits). */
MACS_API int macs_pass_chunk_count(const macs_pass *pass);

/* Defaults: scissor off (whole output); occlusion_query off. */
typedef struct macs_run_desc {
    bool scissor;
    int scissor_x, scissor_y, scissor_width, scissor_height;
    bool occlusion_query; /* count the samples that pass the tests (of the first chunk) */
} macs_run_desc;

/* Runs the pass once over its outputs (run may be NULL for defaults). */
MACS_API macs_status macs_pass_run(macs_pass *pass, const macs_run_desc *run);

/* ---------------------------------------------------------------------------------------------- */
/* Geometry                                                                                        */

/* Defaults: none; vertex_count > 0 and floats_per_vertex 1 .. 64 are required. vertices NULL leaves
 * the contents undefined until macs_geometry_upload. */
typedef struct macs_geometry_desc {
    int vertex_count;
    int floats_per_vertex;
    const float *vertices; /* vertex_count x floats_per_vertex floats, or NULL */
} macs_geometry_desc;

/* A vertex buffer in GPU memory, drawn by geometry passes (macs_pass_draw). */
typedef struct macs_geometry macs_geometry;

/* Creates a geometry; a buffer GL cannot allocate is MACS_ERR_GPU_OUT_OF_MEMORY, naming its size. */
MACS_API macs_status macs_geometry_create(macs_context *ctx, const macs_geometry_desc *desc, macs_geometry **out);

/* Replaces vertices [first, first + count) with count x floats_per_vertex floats. */
MACS_API macs_status macs_geometry_upload(macs_geometry *geometry, int first, int count, const float *vertices);

/* Destroys a geometry (NULL ok). */
MACS_API void macs_geometry_destroy(macs_geometry *geometry);

/* How the triangles of a draw are rasterised: filled (GL's fill rule decides pixels on a shared
 * edge), or as their edges (lines) or corners (square points) `size` pixels wide. With the same
 * fragment code, solid + edges + corners cover every pixel whose centre lies within size / 2 of a
 * triangle, drawn or not by the fill rule: the conservative cover a fragment-side exact test needs. */
typedef enum macs_fill {
    MACS_FILL_SOLID = 0,
    MACS_FILL_EDGES,
    MACS_FILL_CORNERS
} macs_fill;

/* Defaults: geometry required; all vertices from first (vertex_count 0); solid; size 0 = 1 pixel;
 * scissor off. vertex_count must be a multiple of 3 (triangles), and size within
 * macs_features.max_line_width (edges) or max_point_size (corners). */
typedef struct macs_draw_desc {
    const macs_geometry *geometry;
    int first;
    int vertex_count;
    macs_fill fill;
    float size;
    bool scissor;
    int scissor_x, scissor_y, scissor_width, scissor_height;
} macs_draw_desc;

/* Draws a geometry's triangles with a geometry pass into its outputs: the attributes read the
 * geometry's floats, which must be the pass's attribute floats per vertex. One glDrawArrays. */
MACS_API macs_status macs_pass_draw(macs_pass *pass, const macs_draw_desc *draw);

/* Waits for and returns the sample count of the last run with occlusion_query set. */
MACS_API macs_status macs_pass_occlusion_result(macs_pass *pass, uint64_t *samples);

#ifdef __cplusplus
}
#endif

#endif /* MACS_H */
