/* Exact splitting of a pass over several programs and framebuffers.
 *
 * Chunk 0 runs with the caller's full state (depth test, caller stencil, blending) and marks every
 * fragment that survives discard, stencil and depth in the reserved stencil bit. Later chunks run with
 * depth test and depth writes off and write only where that bit is set; the last one clears the bit
 * again, so it is 0 between runs. Nothing relies on two programs computing the same depth: the winner
 * is decided once, by chunk 0, and later chunks just follow the mark. */
#include "internal.h"

#define RESERVED MACS_STENCIL_RESERVED_BITS
#define CALLER MACS_STENCIL_CALLER_BITS

static bool op_is_keep(macs_stencil_op op)
{
    return op == MACS_STENCIL_OP_DEFAULT || op == MACS_STENCIL_OP_KEEP;
}

macs_status macsi_split_check_state(macs_context *ctx, const macs_stencil_state *s, int chunk_count)
{
    if (chunk_count <= 1 || !s->test)
        return MACS_OK;
    /* Chunk 0 must be free to set the mark on depth-pass and leave it clear elsewhere; ops that change
     * bits on failure or do arithmetic on the stencil value would disturb the reserved bit. */
    if (!op_is_keep(s->fail) || !op_is_keep(s->depth_fail) ||
        !(op_is_keep(s->pass) || s->pass == MACS_STENCIL_OP_REPLACE))
        return macsi_fail(ctx, MACS_ERR_LIMIT,
                         "this pass needs %d chunks (more outputs than draw buffers); a split pass takes only KEEP "
                         "for stencil fail and depth_fail and KEEP or REPLACE for pass",
                         chunk_count);
    return MACS_OK;
}

static void caller_stencil(const macs_gl *gl, const macs_stencil_state *s)
{
    unsigned read = s->read_mask ? s->read_mask & CALLER : CALLER;
    unsigned write = s->write_mask ? s->write_mask & CALLER : CALLER;
    gl->Enable(GL_STENCIL_TEST);
    gl->StencilFunc(macsi_gl_compare(s->func, GL_ALWAYS), (GLint)(s->ref & CALLER), read);
    gl->StencilOp(macsi_gl_stencil_op(s->fail), macsi_gl_stencil_op(s->depth_fail), macsi_gl_stencil_op(s->pass));
    gl->StencilMask(write);
}

void macsi_split_apply_state(const macs_pass *pass, int chunk, bool caller_ds, bool any_ds)
{
    const macs_gl *gl = &pass->ctx->gl;
    const macs_stencil_state *s = &pass->stencil;
    bool split = pass->chunk_count > 1;
    if (!any_ds) {
        gl->Disable(GL_DEPTH_TEST);
        gl->Disable(GL_STENCIL_TEST);
        return;
    }
    if (chunk == 0) {
        if (caller_ds && pass->depth.test) {
            gl->Enable(GL_DEPTH_TEST);
            gl->DepthFunc(macsi_gl_compare(pass->depth.func, GL_LESS));
            gl->DepthMask(pass->depth.write ? GL_TRUE : GL_FALSE);
        } else {
            gl->Disable(GL_DEPTH_TEST);
            gl->DepthMask(GL_FALSE);
        }
        bool caller_test = caller_ds && s->test;
        if (!split) {
            if (caller_test)
                caller_stencil(gl, s);
            else
                gl->Disable(GL_STENCIL_TEST);
            return;
        }
        /* Marking: the caller's comparison on its own bits, REPLACE on depth-pass writing the mark
         * (and the caller's bits too when the caller asked for REPLACE). */
        GLenum func = caller_test ? macsi_gl_compare(s->func, GL_ALWAYS) : GL_ALWAYS;
        unsigned read = caller_test ? (s->read_mask ? s->read_mask & CALLER : CALLER) : 0;
        unsigned ref = (caller_test ? s->ref & CALLER : 0) | RESERVED;
        unsigned write = RESERVED;
        if (caller_test && s->pass == MACS_STENCIL_OP_REPLACE)
            write |= s->write_mask ? s->write_mask & CALLER : CALLER;
        gl->Enable(GL_STENCIL_TEST);
        gl->StencilFunc(func, (GLint)ref, read);
        gl->StencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
        gl->StencilMask(write);
        return;
    }
    /* Later chunks: the mark alone decides; depth is neither tested nor written. */
    bool last = chunk == pass->chunk_count - 1;
    gl->Disable(GL_DEPTH_TEST);
    gl->DepthMask(GL_FALSE);
    gl->Enable(GL_STENCIL_TEST);
    gl->StencilFunc(GL_EQUAL, (GLint)RESERVED, RESERVED);
    gl->StencilOp(GL_KEEP, GL_KEEP, last ? GL_ZERO : GL_KEEP);
    gl->StencilMask(last ? RESERVED : 0u);
}
