/* Lifetimes: many create/destroy cycles balance every allocation, objects outliving their context's
 * destroy are freed by it, several contexts coexist. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "util_alloc.h"
#include "util_gl.h"

/* One cycle: context, textures, depth/stencil, a split pass with an input, a run, destroy. */
static void cycle(void **state, util_alloc_counter *c, int i)
{
    macs_context_desc d = {0};
    d.get_proc_address = macs_headless_get_proc_address(*state);
    d.get_proc_address_user = macs_headless_proc_user(*state);
    d.allocator.alloc = util_counted_alloc;
    d.allocator.realloc = util_counted_realloc;
    d.allocator.free = util_counted_free;
    d.allocator.user = c;
    d.caps.max_draw_buffers = 1;
    macs_context *ctx = NULL;
    assert_int_equal(macs_context_create(&d, &ctx, NULL, 0), MACS_OK);
    float in[4 * 4 * 4];
    util_fill_pattern(in, 64, (unsigned)i);
    macs_texture_desc td = {4, 4, 0, 0, 0, in, 0};
    macs_texture *src = NULL, *out[2] = {NULL, NULL};
    assert_int_equal(macs_texture_create(ctx, &td, &src), MACS_OK);
    td.data = NULL;
    assert_int_equal(macs_texture_create(ctx, &td, &out[0]), MACS_OK);
    assert_int_equal(macs_texture_create(ctx, &td, &out[1]), MACS_OK);
    macs_depth_stencil_desc dd = {4, 4, 0};
    macs_depth_stencil *ds = NULL;
    assert_int_equal(macs_depth_stencil_create(ctx, &dd, &ds), MACS_OK);
    macs_input_desc inp = {"src"};
    macs_uniform_desc u = {"k", MACS_UNIFORM_FLOAT, 0};
    macs_output_desc o[2] = {{"a", "texture2D(src, macs_uv) * k"}, {"b", "texture2D(src, macs_uv) + k"}};
    macs_pass_desc pd = {0};
    pd.inputs = &inp;
    pd.input_count = 1;
    pd.input_textures = &src;
    pd.uniforms = &u;
    pd.uniform_count = 1;
    pd.outputs = o;
    pd.output_count = 2;
    pd.output_textures = out;
    pd.depth_stencil = (i & 2) ? ds : NULL; /* alternate caller's and internal stencil */
    macs_pass *p = NULL;
    assert_int_equal(macs_pass_create(ctx, &pd, &p), MACS_OK);
    assert_int_equal(macs_pass_chunk_count(p), 2);
    const float k = 3.0f;
    assert_int_equal(macs_pass_set_uniform(p, "k", &k), MACS_OK);
    assert_int_equal(macs_pass_run(p, NULL), MACS_OK);
    float px[64];
    assert_int_equal(macs_texture_read(out[1], px, 0), MACS_OK);
    assert_true(px[17] == in[17] + 3.0f);
    /* A failing pass in the middle must not leak either. */
    macs_output_desc broken = {"x", "vec4(undefined_name)"};
    pd.outputs = &broken;
    pd.output_count = 1;
    macs_pass *bad = NULL;
    assert_int_equal(macs_pass_create(ctx, &pd, &bad), MACS_ERR_SHADER_COMPILE);
    if (i & 1) {
        /* Odd cycles destroy everything explicitly, even ones let the context do it. */
        macs_pass_destroy(p);
        macs_texture_destroy(out[0]);
        macs_texture_destroy(out[1]);
        macs_texture_destroy(src);
        macs_depth_stencil_destroy(ds);
    }
    macs_context_destroy(ctx);
}

static void thousand_cycles_balance_allocations(void **state)
{
    util_alloc_counter c = UTIL_ALLOC_COUNTER;
    int n = util_quick() ? 6 : 1000;
    for (int i = 0; i < n; i++) {
        cycle(state, &c, i);
        if (c.allocs != c.frees)
            fail_msg("cycle %d left %ld allocations", i, c.allocs - c.frees);
    }
    assert_true(c.allocs > n * 10); /* the hooks really were used */
}

static void several_contexts_coexist(void **state)
{
    /* Two MACS contexts on one GL context, and a second headless GL context with its own. */
    macs_context *a = util_context(*state, NULL);
    macs_context *b = util_context(*state, NULL);
    macs_texture *ta = util_texture(a, 2, 2, 0), *tb = util_texture(b, 2, 2, 0);
    assert_int_equal(macs_texture_clear(ta, (const float[4]){1, 2, 3, 4}), MACS_OK);
    assert_int_equal(macs_texture_clear(tb, (const float[4]){5, 6, 7, 8}), MACS_OK);
    macs_context_destroy(a);
    float px[16];
    assert_int_equal(macs_texture_read(tb, px, 0), MACS_OK);
    assert_true(px[0] == 5.0f && px[15] == 8.0f);

    macs_headless *second = util_headless();
    macs_context *c = util_context(second, NULL);
    macs_texture *tc = util_texture(c, 2, 2, 0);
    assert_int_equal(macs_texture_clear(tc, (const float[4]){9, 9, 9, 9}), MACS_OK);
    assert_int_equal(macs_texture_read(tc, px, 0), MACS_OK);
    assert_true(px[3] == 9.0f);
    macs_context_destroy(c);
    macs_headless_destroy(second);
    assert_int_equal(macs_headless_make_current(*state), MACS_OK);
    assert_int_equal(macs_texture_read(tb, px, 0), MACS_OK);
    assert_true(px[0] == 5.0f);
    macs_context_destroy(b);
}

static void headless_reports_bad_arguments(void **state)
{
    (void)state;
    char message[256];
    macs_headless_desc d = {0};
    d.backend = (macs_headless_backend)9;
    macs_headless *h = NULL;
    assert_int_equal(macs_headless_create(&d, &h, message, sizeof message), MACS_ERR_INVALID_ARGUMENT);
    assert_null(h);
    assert_true(strlen(message) > 0);
    assert_int_equal(macs_headless_create(NULL, NULL, NULL, 0), MACS_ERR_INVALID_ARGUMENT);
    assert_int_equal(macs_headless_make_current(NULL), MACS_ERR_INVALID_ARGUMENT);
    assert_null(macs_headless_get_proc_address(NULL));
    assert_int_equal(macs_headless_make_current(*state), MACS_OK);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(thousand_cycles_balance_allocations),
        cmocka_unit_test(several_contexts_coexist),
        cmocka_unit_test(headless_reports_bad_arguments),
    };
    return cmocka_run_group_tests(tests, util_group_setup, util_group_teardown);
}
