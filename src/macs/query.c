/* Occlusion queries: samples that passed the tests in a run (its first chunk, which runs the tests). */
#include "internal.h"

macs_status macsi_query_begin(macs_pass *pass)
{
    const macs_gl *gl = &pass->ctx->gl;
    if (!pass->query)
        gl->GenQueries(1, &pass->query);
    gl->BeginQuery(GL_SAMPLES_PASSED, pass->query);
    return MACS_OK;
}

void macsi_query_end(macs_pass *pass)
{
    pass->ctx->gl.EndQuery(GL_SAMPLES_PASSED);
    pass->query_issued = true;
}

void macsi_query_destroy(macs_pass *pass)
{
    if (pass->query)
        pass->ctx->gl.DeleteQueries(1, &pass->query);
    pass->query = 0;
    pass->query_issued = false;
}

macs_status macs_pass_occlusion_result(macs_pass *pass, uint64_t *samples)
{
    if (!pass)
        return MACS_ERR_INVALID_ARGUMENT;
    if (!samples)
        return macsi_fail(pass->ctx, MACS_ERR_INVALID_ARGUMENT, "macs_pass_occlusion_result: samples is NULL");
    if (!pass->query_issued)
        return macsi_fail(pass->ctx, MACS_ERR_NO_RESULT,
                         "macs_pass_occlusion_result: no run of this pass asked for an occlusion query");
    macsi_gl_drain(pass->ctx);
    GLuint value = 0;
    /* GL_QUERY_RESULT waits for the GPU; that is the documented blocking behaviour. */
    macsi_query_result(pass->ctx, pass->query, &value);
    macs_status st = macsi_gl_check(pass->ctx, "glGetQueryObjectuiv");
    if (st == MACS_OK)
        *samples = value;
    return st;
}
