/* Fills the GL table through the caller's get_proc_address, from the one whitelist in gl_functions.h. */
#include <stdio.h>
#include <string.h>

#include "internal.h"

bool macsi_gl_has_extension(const char *extensions, const char *name)
{
    /* Whole-token match: "GL_EXT_foo" must not be found inside "GL_EXT_foo_bar". */
    if (!extensions || !name || !*name)
        return false;
    size_t n = strlen(name);
    for (const char *p = extensions; (p = strstr(p, name)) != NULL; p += n) {
        bool starts = p == extensions || p[-1] == ' ';
        bool ends = p[n] == ' ' || p[n] == '\0';
        if (starts && ends)
            return true;
    }
    return false;
}

/* The loader gives every entry point as a macs_gl_proc; converting it to the function's own pointer
 * type is a cast ISO C defines (between function pointer types), and calls go through that type. */
#define MACS_SET_FN_(dst, ret, params, proc) ((dst) = (ret (GLAPIENTRY *) params)(proc))

static void note_missing(char *missing, size_t size, const char *name)
{
    size_t used = strlen(missing);
    if (used + 2 < size)
        snprintf(missing + used, size - used, "%s%s", used ? ", " : "", name);
}

macs_status macsi_gl_load(macs_gl *gl, macs_get_proc_address_fn gpa, void *user, bool ext_fbo, char *missing,
                         size_t missing_size)
{
    bool ok = true;
    char name[64];
    missing[0] = '\0';
#define MACS_LOAD_CORE_(ret, fn, params) \
    { macs_gl_proc p_ = gpa("gl" #fn, user); MACS_SET_FN_(gl->fn, ret, params, p_); \
      if (!p_) { ok = false; note_missing(missing, missing_size, "gl" #fn); } }
    MACS_GL_CORE(MACS_LOAD_CORE_)
#undef MACS_LOAD_CORE_
#define MACS_LOAD_FBO_(ret, fn, params) \
    { snprintf(name, sizeof name, "gl%s%s", #fn, ext_fbo ? "EXT" : ""); \
      macs_gl_proc p_ = gpa(name, user); MACS_SET_FN_(gl->fn, ret, params, p_); \
      if (!p_) { ok = false; note_missing(missing, missing_size, name); } }
    MACS_GL_FBO(MACS_LOAD_FBO_)
#undef MACS_LOAD_FBO_
    /* Optional functions may stay NULL; their extension string entry decides whether they are called. */
#define MACS_LOAD_OPTIONAL_(ret, fn, params) \
    { macs_gl_proc p_ = gpa("gl" #fn, user); MACS_SET_FN_(gl->fn, ret, params, p_); }
    MACS_GL_OPTIONAL(MACS_LOAD_OPTIONAL_)
#undef MACS_LOAD_OPTIONAL_
    return ok ? MACS_OK : MACS_ERR_GL_UNSUPPORTED;
}
