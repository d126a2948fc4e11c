/* A masked stencil clear, in raw GL: the reduced form of the zink defect that blacked out the
 * multipass (README, "Run the tests"; docs/gpu_pipeline.md, "One frame"). Not a suite: `make
 * check-zink` runs it first.
 *
 * A packed DEPTH24_STENCIL8 renderbuffer is cleared to stencil 0x0F, then cleared again with
 * glStencilMask(0xB0) and glClearStencil(0x70). GL 2.1 (4.2.3, "Clearing the Buffers") makes the
 * clear honour the front stencil write mask, so every pixel must read (0x0F & ~0xB0) | (0x70 & 0xB0)
 * = 0x3F. Each case is checked twice: glReadPixels(GL_STENCIL_INDEX), and a fixed-function quad
 * drawn with the stencil test EQUAL 0x3F into a colour renderbuffer, which must cover every pixel.
 * Mesa 22.3's zink over lavapipe leaves the stencil at 0x0F in every masked case (the full-mask
 * control passes); llvmpipe and softpipe give 0x3F.
 *
 * The context comes from MACS's headless backend only because it loads EGL without linking it; every
 * call that matters is plain GL. Usage: probe_stencil_clear osmesa|egl|device. Exit 0: every case
 * right; 1: a case wrong (each is printed); 2: no context or a GL error. */
#include <stdio.h>
#include <string.h>

#include <GL/gl.h>
#include <GL/glext.h>

#include "macs.h"

#define SIZE 4

#define GL_ENTRIES(X) \
    X(void, GenFramebuffers, (GLsizei, GLuint *)) \
    X(void, BindFramebuffer, (GLenum, GLuint)) \
    X(void, FramebufferRenderbuffer, (GLenum, GLenum, GLenum, GLuint)) \
    X(GLenum, CheckFramebufferStatus, (GLenum)) \
    X(void, GenRenderbuffers, (GLsizei, GLuint *)) \
    X(void, BindRenderbuffer, (GLenum, GLuint)) \
    X(void, RenderbufferStorage, (GLenum, GLenum, GLsizei, GLsizei)) \
    X(void, DrawBuffers, (GLsizei, const GLenum *)) \
    X(void, ReadBuffer, (GLenum)) \
    X(void, ReadPixels, (GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void *)) \
    X(void, Enable, (GLenum)) \
    X(void, Disable, (GLenum)) \
    X(void, StencilMask, (GLuint)) \
    X(void, StencilFunc, (GLenum, GLint, GLuint)) \
    X(void, StencilOp, (GLenum, GLenum, GLenum)) \
    X(void, ClearStencil, (GLint)) \
    X(void, ClearDepth, (GLdouble)) \
    X(void, ClearColor, (GLfloat, GLfloat, GLfloat, GLfloat)) \
    X(void, Clear, (GLbitfield)) \
    X(void, DepthMask, (GLboolean)) \
    X(void, Viewport, (GLint, GLint, GLsizei, GLsizei)) \
    X(void, Begin, (GLenum)) \
    X(void, Vertex2f, (GLfloat, GLfloat)) \
    X(void, Color3f, (GLfloat, GLfloat, GLfloat)) \
    X(void, End, (void)) \
    X(void, Finish, (void)) \
    X(const GLubyte *, GetString, (GLenum)) \
    X(GLenum, GetError, (void))

typedef struct gl_api {
#define FIELD(ret, name, params) ret(APIENTRYP name) params;
    GL_ENTRIES(FIELD)
#undef FIELD
} gl_api;

/* One case: how the depth/stencil buffer is attached, what else is cleared with the stencil. */
typedef struct probe_case {
    const char *name;
    unsigned mask;        /* glStencilMask for the second clear */
    bool packed_point;    /* GL_DEPTH_STENCIL_ATTACHMENT rather than DEPTH and STENCIL apart */
    bool with_colour;     /* a colour attachment bound during the clear, not just NONE buffers */
    GLbitfield bits;      /* what the second glClear clears */
} probe_case;

static const probe_case cases[] = {
    {"control: full mask 0xFF, depth+stencil", 0xFF, false, false, GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT},
    {"mask 0xB0, depth+stencil, DEPTH and STENCIL attachments", 0xB0, false, false,
     GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT},
    {"mask 0xB0, stencil only", 0xB0, false, false, GL_STENCIL_BUFFER_BIT},
    {"mask 0xB0, DEPTH_STENCIL attachment", 0xB0, true, false, GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT},
    {"mask 0xB0, colour attachment bound", 0xB0, false, true, GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT},
};

static void attach_ds(const gl_api *gl, GLuint rb, bool packed_point)
{
    if (packed_point) {
        gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, rb);
    } else {
        gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb);
        gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_STENCIL_ATTACHMENT, GL_RENDERBUFFER, rb);
    }
}

/* Runs one case; returns the number of wrong pixels (read back or drawn), or -1 on a GL failure. */
static int run_case(const gl_api *gl, const probe_case *c, unsigned expect)
{
    GLuint rb = 0, fbo = 0, colour_rb = 0;
    gl->GenRenderbuffers(1, &rb);
    gl->BindRenderbuffer(GL_RENDERBUFFER, rb);
    gl->RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, SIZE, SIZE);
    gl->GenRenderbuffers(1, &colour_rb);
    gl->BindRenderbuffer(GL_RENDERBUFFER, colour_rb);
    gl->RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, SIZE, SIZE);
    gl->GenFramebuffers(1, &fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, fbo);
    attach_ds(gl, rb, c->packed_point);
    if (c->with_colour) {
        gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_rb);
    } else {
        static const GLenum none = GL_NONE;
        gl->DrawBuffers(1, &none);
        gl->ReadBuffer(GL_NONE);
    }
    if (gl->CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return -1;
    gl->Disable(GL_SCISSOR_TEST);
    gl->Disable(GL_STENCIL_TEST);
    gl->DepthMask(GL_TRUE);
    gl->StencilMask(0xFF);
    gl->ClearDepth(1.0);
    gl->ClearStencil(0x0F);
    gl->Clear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    gl->StencilMask(c->mask);
    gl->ClearDepth(0.5);
    gl->ClearStencil(0x70);
    gl->Clear(c->bits);
    gl->StencilMask(0xFF);

    unsigned char stencil[SIZE * SIZE];
    memset(stencil, 0xAA, sizeof stencil);
    gl->ReadPixels(0, 0, SIZE, SIZE, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, stencil);

    /* The same values seen by the stencil test: a white quad where stencil == expect, on black. */
    gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_rb);
    static const GLenum colour = GL_COLOR_ATTACHMENT0;
    gl->DrawBuffers(1, &colour);
    gl->ReadBuffer(GL_COLOR_ATTACHMENT0);
    if (gl->CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return -1;
    gl->Viewport(0, 0, SIZE, SIZE);
    gl->ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    gl->Clear(GL_COLOR_BUFFER_BIT);
    gl->Enable(GL_STENCIL_TEST);
    gl->StencilFunc(GL_EQUAL, (GLint)expect, 0xFF);
    gl->StencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    gl->Color3f(1.0f, 1.0f, 1.0f);
    gl->Begin(GL_QUADS);
    gl->Vertex2f(-1.0f, -1.0f);
    gl->Vertex2f(1.0f, -1.0f);
    gl->Vertex2f(1.0f, 1.0f);
    gl->Vertex2f(-1.0f, 1.0f);
    gl->End();
    gl->Disable(GL_STENCIL_TEST);
    unsigned char rgba[SIZE * SIZE * 4];
    gl->ReadPixels(0, 0, SIZE, SIZE, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    gl->Finish();
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (gl->GetError() != GL_NO_ERROR)
        return -1;

    int wrong_read = 0, wrong_test = 0;
    for (int i = 0; i < SIZE * SIZE; i++) {
        wrong_read += stencil[i] != expect;
        wrong_test += rgba[4 * i] != 255;
    }
    int wrong = wrong_read + wrong_test;
    printf("%-58s stencil read 0x%02x (want 0x%02x, %d of %d pixels wrong), EQUAL test fails on %d: %s\n",
           c->name, stencil[0], expect, wrong_read, SIZE * SIZE, wrong_test, wrong ? "WRONG" : "right");
    return wrong;
}

int main(int argc, char **argv)
{
    static const struct { const char *name; macs_headless_backend backend; } names[] = {
        {"osmesa", MACS_HEADLESS_OSMESA}, {"egl", MACS_HEADLESS_EGL}, {"device", MACS_HEADLESS_EGL_DEVICE}};
    size_t n = 0;
    while (argc == 2 && n < sizeof names / sizeof names[0] && strcmp(argv[1], names[n].name) != 0)
        n++;
    if (argc != 2 || n == sizeof names / sizeof names[0]) {
        fprintf(stderr, "usage: probe_stencil_clear osmesa|egl|device\n");
        return 2;
    }
    macs_headless_desc desc = {0};
    desc.backend = names[n].backend;
    char message[1024];
    macs_headless *h = NULL;
    if (macs_headless_create(&desc, &h, message, sizeof message) != MACS_OK) {
        printf("no context: %s\n", message);
        return 2;
    }
    macs_get_proc_address_fn gpa = macs_headless_get_proc_address(h);
    void *user = macs_headless_proc_user(h);
    gl_api gl;
    bool loaded = true;
#define LOAD(ret, name, params)                                        \
    {                                                                  \
        macs_gl_proc p = gpa("gl" #name, user);                        \
        if (!p) {                                                      \
            printf("GL function gl%s is missing\n", #name);            \
            loaded = false;                                            \
        }                                                              \
        memcpy(&gl.name, &p, sizeof gl.name);                          \
    }
    GL_ENTRIES(LOAD)
#undef LOAD
    int status = 2;
    if (loaded) {
        printf("GL_RENDERER %s, GL_VERSION %s\n", (const char *)gl.GetString(GL_RENDERER),
               (const char *)gl.GetString(GL_VERSION));
        status = 0;
        for (size_t i = 0; i < sizeof cases / sizeof cases[0] && status != 2; i++) {
            unsigned expect = (0x0Fu & ~cases[i].mask) | (0x70u & cases[i].mask);
            int wrong = run_case(&gl, &cases[i], expect);
            if (wrong < 0) {
                printf("%s: GL error or incomplete framebuffer\n", cases[i].name);
                status = 2;
            } else if (wrong > 0) {
                status = 1;
            }
        }
    }
    macs_headless_destroy(h);
    return status;
}
