/* Test helper: allocation hooks that count blocks and bytes and can fail on demand, for the
 * allocator of a MACS context, a scene or a renderer (macs_allocator and bg_allocator take the same
 * functions). */
#ifndef UTIL_ALLOC_H
#define UTIL_ALLOC_H

#include <stddef.h>

/* Blocks handed out and given back, the bytes live, and the allocations refused: from the
 * fail_after-th allocation on (counting from 0) every allocation fails; fail_after < 0 never
 * fails. Start from UTIL_ALLOC_COUNTER. */
typedef struct util_alloc_counter {
    long allocs, frees;
    long fail_after;
    long refused;
    size_t live_bytes;
} util_alloc_counter;

#define UTIL_ALLOC_COUNTER {0, 0, -1, 0, 0}

/* The hooks; user is a util_alloc_counter. A realloc of NULL counts as an allocation. */
void *util_counted_alloc(size_t size, void *user);
void *util_counted_realloc(void *ptr, size_t size, void *user);
void util_counted_free(void *ptr, void *user);

#endif
