/* Asynchronous read-back (macs_readback): the texels of a read begun are the texture's as it was at
 * the begin, whatever is done to it afterwards; the work counted is a plain read's (the bytes at the
 * begin, one sync at the map); every misuse is refused naming the argument; a driver whose
 * glMapBuffer gives NULL gets an error, never a crash. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "util_gl.h"

enum { W = 19, H = 7 };

static void fill_bytes(unsigned char *p, size_t n, unsigned seed)
{
    for (size_t i = 0; i < n; i++)
        p[i] = (unsigned char)((i * 37u + seed * 101u) & 0xFF);
}

/* The read holds the texels of the begin: the texture is overwritten before the map, and the map,
 * macs_readback_read (with a stride) and macs_texture_read agree, bottom row first. */
static void read_holds_the_texels_of_the_begin(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    for (int f = 0; f < 2; f++) {
        macs_format format = f ? MACS_FORMAT_RGBA32F : MACS_FORMAT_RGBA8;
        size_t texel = f ? 16 : 4, row = (size_t)W * texel, bytes = row * H;
        unsigned char *first = malloc(bytes), *second = malloc(bytes), *got = malloc(bytes + 2 * texel * H);
        assert_true(first && second && got);
        if (f) {
            util_fill_pattern((float *)first, bytes / 4, 5);
            util_fill_pattern((float *)second, bytes / 4, 6);
        } else {
            fill_bytes(first, bytes, 1);
            fill_bytes(second, bytes, 2);
        }
        macs_texture *t = util_texture(ctx, W, H, format);
        assert_int_equal(macs_texture_upload(t, first, 0), MACS_OK);
        macs_readback *rb = NULL;
        assert_int_equal(macs_readback_create(ctx, &rb), MACS_OK);
        assert_non_null(rb);
        assert_int_equal(macs_texture_read_begin(t, rb), MACS_OK);
        assert_int_equal(macs_texture_upload(t, second, 0), MACS_OK);
        const void *texels = NULL;
        size_t stride = 0;
        assert_int_equal(macs_readback_map(rb, &texels, &stride), MACS_OK);
        assert_non_null(texels);
        assert_int_equal(stride, row);
        assert_memory_equal(texels, first, bytes);
        assert_int_equal(macs_readback_unmap(rb), MACS_OK);
        /* The second contents, through macs_readback_read into rows two texels wider. */
        assert_int_equal(macs_texture_read_begin(t, rb), MACS_OK);
        size_t wide = row + 2 * texel;
        memset(got, 0x5A, wide * H);
        assert_int_equal(macs_readback_read(rb, got, wide), MACS_OK);
        for (int y = 0; y < H; y++) {
            assert_memory_equal(got + (size_t)y * wide, second + (size_t)y * row, row);
            for (size_t i = row; i < wide; i++)
                assert_int_equal(got[(size_t)y * wide + i], 0x5A);
        }
        /* A texture destroyed after the begin: the buffer has its copy. */
        assert_int_equal(macs_texture_read_begin(t, rb), MACS_OK);
        macs_texture_destroy(t);
        assert_int_equal(macs_readback_read(rb, got, 0), MACS_OK);
        assert_memory_equal(got, second, bytes);
        macs_readback_destroy(rb);
        free(first);
        free(second);
        free(got);
    }
    assert_int_equal(macs_context_error(ctx), MACS_OK);
    macs_context_destroy(ctx);
}

/* A read through a readback counts what macs_texture_read counts, split: the bytes and no sync at the
 * begin, one sync at the map. */
static void work_is_counted_at_begin_and_map(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    macs_texture *t = util_texture(ctx, W, H, MACS_FORMAT_RGBA8);
    macs_readback *rb = NULL;
    assert_int_equal(macs_readback_create(ctx, &rb), MACS_OK);
    macs_work a, b, c, d;
    macs_context_get_work(ctx, &a);
    assert_int_equal(macs_texture_read_begin(t, rb), MACS_OK);
    macs_context_get_work(ctx, &b);
    const void *texels = NULL;
    assert_int_equal(macs_readback_map(rb, &texels, NULL), MACS_OK);
    assert_int_equal(macs_readback_unmap(rb), MACS_OK);
    macs_context_get_work(ctx, &c);
    macs_context_flush(ctx);
    macs_context_get_work(ctx, &d);
    macs_work begin = macs_work_since(&b, &a), map = macs_work_since(&c, &b), flush = macs_work_since(&d, &c);
    assert_int_equal(begin.readback_bytes, (uint64_t)W * H * 4);
    assert_int_equal(begin.syncs, 0);
    assert_int_equal(map.readback_bytes, 0);
    assert_int_equal(map.syncs, 1);
    assert_int_equal(flush.syncs + flush.readback_bytes + flush.draws, 0);
    /* The same as a blocking read of the texture. */
    unsigned char px[W * H * 4];
    assert_int_equal(macs_texture_read(t, px, 0), MACS_OK);
    macs_context_get_work(ctx, &a);
    macs_work plain = macs_work_since(&a, &d);
    assert_int_equal(plain.readback_bytes, begin.readback_bytes + map.readback_bytes);
    assert_int_equal(plain.syncs, begin.syncs + map.syncs);
    macs_readback_destroy(rb);
    macs_context_destroy(ctx);
}

static void expect_error(macs_context *ctx, macs_status got, macs_status want, const char *needle)
{
    assert_int_equal(got, want);
    assert_int_equal(macs_context_error(ctx), want);
    if (!strstr(macs_context_error_message(ctx), needle))
        fail_msg("message \"%s\" does not name \"%s\"", macs_context_error_message(ctx), needle);
    macs_context_clear_error(ctx);
}

static void misuse_is_refused_by_name(void **state)
{
    macs_context *ctx = util_context(*state, NULL);
    macs_texture *t = util_texture(ctx, W, H, MACS_FORMAT_RGBA8);
    macs_readback *rb = (macs_readback *)&rb; /* overwritten with NULL on failure */
    assert_int_equal(macs_readback_create(NULL, &rb), MACS_ERR_INVALID_ARGUMENT);
    assert_null(rb);
    expect_error(ctx, macs_readback_create(ctx, NULL), MACS_ERR_INVALID_ARGUMENT, "out is NULL");
    assert_int_equal(macs_readback_create(ctx, &rb), MACS_OK);
    assert_int_equal(macs_texture_read_begin(NULL, NULL), MACS_ERR_INVALID_ARGUMENT);
    expect_error(ctx, macs_texture_read_begin(NULL, rb), MACS_ERR_INVALID_ARGUMENT, "texture is NULL");
    expect_error(ctx, macs_texture_read_begin(t, NULL), MACS_ERR_INVALID_ARGUMENT, "readback is NULL");
    const void *texels = (const void *)&texels;
    size_t stride = 99;
    assert_int_equal(macs_readback_map(NULL, &texels, &stride), MACS_ERR_INVALID_ARGUMENT);
    assert_null(texels);
    assert_int_equal(stride, 0);
    expect_error(ctx, macs_readback_map(rb, NULL, NULL), MACS_ERR_INVALID_ARGUMENT, "texels is NULL");
    expect_error(ctx, macs_readback_map(rb, &texels, NULL), MACS_ERR_NO_RESULT, "no read was begun");
    expect_error(ctx, macs_readback_unmap(rb), MACS_ERR_INVALID_ARGUMENT, "not mapped");
    assert_int_equal(macs_readback_unmap(NULL), MACS_ERR_INVALID_ARGUMENT);
    unsigned char px[W * H * 4];
    assert_int_equal(macs_readback_read(NULL, px, 0), MACS_ERR_INVALID_ARGUMENT);
    expect_error(ctx, macs_readback_read(rb, NULL, 0), MACS_ERR_INVALID_ARGUMENT, "data is NULL");
    expect_error(ctx, macs_readback_read(rb, px, 0), MACS_ERR_NO_RESULT, "no read was begun");
    assert_int_equal(macs_texture_read_begin(t, rb), MACS_OK);
    expect_error(ctx, macs_readback_read(rb, px, W * 4 - 4), MACS_ERR_INVALID_ARGUMENT, "stride");
    expect_error(ctx, macs_readback_read(rb, px, W * 4 + 2), MACS_ERR_INVALID_ARGUMENT, "stride");
    /* A refused read leaves the read begun: it is still there to take. */
    assert_int_equal(macs_readback_map(rb, &texels, NULL), MACS_OK);
    expect_error(ctx, macs_readback_map(rb, &texels, NULL), MACS_ERR_INVALID_ARGUMENT, "mapped already");
    expect_error(ctx, macs_texture_read_begin(t, rb), MACS_ERR_INVALID_ARGUMENT, "unmap it first");
    expect_error(ctx, macs_readback_read(rb, px, 0), MACS_ERR_INVALID_ARGUMENT, "mapped");
    assert_int_equal(macs_readback_unmap(rb), MACS_OK);
    expect_error(ctx, macs_readback_map(rb, &texels, NULL), MACS_ERR_NO_RESULT, "taken already");
    /* A readback of another context. */
    macs_context *other = util_context(*state, NULL);
    macs_readback *theirs = NULL;
    assert_int_equal(macs_readback_create(other, &theirs), MACS_OK);
    expect_error(ctx, macs_texture_read_begin(t, theirs), MACS_ERR_INVALID_ARGUMENT, "another macs_context");
    macs_readback_destroy(NULL);
    macs_context_flush(NULL);
    /* Destroyed mapped, and left to the context: nothing leaks (the sanitizer build checks). */
    assert_int_equal(macs_texture_read_begin(t, rb), MACS_OK);
    assert_int_equal(macs_readback_map(rb, &texels, NULL), MACS_OK);
    macs_readback_destroy(rb);
    macs_context_destroy(other);
    macs_readback *left = NULL;
    assert_int_equal(macs_readback_create(ctx, &left), MACS_OK);
    assert_int_equal(macs_texture_read_begin(t, left), MACS_OK);
    macs_context_destroy(ctx);
}

/* A driver whose glMapBuffer returns NULL (the loader hands MACS a stand-in). */
static void a_null_map_is_an_error(void **state)
{
    macs_context *ctx = util_context_null_map(*state, NULL);
    macs_texture *t = util_texture(ctx, W, H, MACS_FORMAT_RGBA8);
    macs_readback *rb = NULL;
    assert_int_equal(macs_readback_create(ctx, &rb), MACS_OK);
    assert_int_equal(macs_texture_read_begin(t, rb), MACS_OK);
    const void *texels = (const void *)&texels;
    expect_error(ctx, macs_readback_map(rb, &texels, NULL), MACS_ERR_GL, "glMapBuffer");
    assert_null(texels);
    /* The read is lost, and said so; the readback takes the next one. */
    expect_error(ctx, macs_readback_map(rb, &texels, NULL), MACS_ERR_NO_RESULT, "no read was begun");
    unsigned char px[W * H * 4];
    assert_int_equal(macs_texture_read_begin(t, rb), MACS_OK);
    expect_error(ctx, macs_readback_read(rb, px, 0), MACS_ERR_GL, "returned NULL");
    macs_context_destroy(ctx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(read_holds_the_texels_of_the_begin),
        cmocka_unit_test(work_is_counted_at_begin_and_map),
        cmocka_unit_test(misuse_is_refused_by_name),
        cmocka_unit_test(a_null_map_is_an_error),
    };
    return cmocka_run_group_tests(tests, util_group_setup, util_group_teardown);
}
