/* Test helpers: headless GL from MACS_TEST_BACKEND (osmesa | egl | device) and MACS contexts with caps
 * and the limit profile MACS_TEST_PROFILE names. */
#ifndef UTIL_GL_H
#define UTIL_GL_H

#include <stdbool.h>
#include <stddef.h>

#include "macs.h"

/* True when MACS_TEST_QUICK is set (valgrind): loops shrink but still assert. */
bool util_quick(void);

/* A function of a window-system library loaded by soname (and kept loaded), or NULL where the library
 * or the function is missing: the tests link no such library, just as the libraries do not. */
macs_gl_proc util_library_function(const char *soname, const char *name);

/* Whether libOSMesa can be loaded here (Mesa 25.1 and later ship none). */
bool util_osmesa_present(void);

/* Creates the headless context the environment asks for; skips the test, saying so, where OSMesa is
 * asked for and not installed; fails the test if it cannot otherwise. */
macs_headless *util_headless(void);

/* The limit profile the environment asks for (MACS_TEST_PROFILE, a name of MACS_PROFILE_NAMES), or
 * NULL: the library reads no environment, so the tests pass it on through macs_context_desc.profile. */
const char *util_profile(void);

/* True when the last context util_context made blends no RGBA32F target (a profile such as geforce7
 * says so): the multipass then accumulates in RGBA16F, and images are held to its wider bound. */
bool util_half_accumulation(void);

/* Creates a MACS context on the current headless context with optional caps, under util_profile()
 * (its limits and the caps combine, the smaller winning); fails the test on error. */
macs_context *util_context(macs_headless *headless, const macs_limits *caps);
/* The same with the extensions hidden names (desc.hidden_extensions), as a driver without them. */
macs_context *util_context_hiding(macs_headless *headless, const char *hidden);
/* The same (with caps) on a driver whose glMapBuffer returns NULL: the context's loader hands MACS a
 * stand-in for that one function. One such context at a time. */
macs_context *util_context_null_map(macs_headless *headless, const macs_limits *caps);

/* Leaves the calling thread with no current GL context (EGL or OSMesa, whichever is current), as a
 * caller who forgot to make one current would; macs_headless_make_current restores it. */
void util_release_current(void);

/* cmocka group fixtures: *state becomes a macs_headless. */
int util_group_setup(void **state);
int util_group_teardown(void **state);

/* Creates a texture of the given size and format with no contents, failing the test on error; under
 * a limit profile a size beyond the profile's texture size skips the test, saying so. */
macs_texture *util_texture(macs_context *ctx, int width, int height, macs_format format);

/* Under a limit profile, skips the calling test, saying so, when ctx cannot hold a width x height
 * texture (the test's own GL textures of that size would be refused); does nothing otherwise. */
void util_require_texture_size(macs_context *ctx, int width, int height);

/* Fills n floats with a deterministic pattern of signs and magnitudes. */
void util_fill_pattern(float *data, size_t n, unsigned seed);

#endif
