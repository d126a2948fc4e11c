/* Counting allocation hooks for tests (util_alloc.h). */
#include <stdlib.h>

#include "util_alloc.h"

static int refused(const util_alloc_counter *c)
{
    return c->fail_after >= 0 && c->allocs >= c->fail_after;
}

void *util_counted_alloc(size_t size, void *user)
{
    util_alloc_counter *c = user;
    if (refused(c))
        return NULL;
    void *p = malloc(size);
    if (p)
        c->allocs++;
    return p;
}

void *util_counted_realloc(void *ptr, size_t size, void *user)
{
    util_alloc_counter *c = user;
    if (refused(c))
        return NULL;
    void *p = realloc(ptr, size);
    if (p && !ptr)
        c->allocs++;
    return p;
}

void util_counted_free(void *ptr, void *user)
{
    util_alloc_counter *c = user;
    if (ptr)
        c->frees++;
    free(ptr);
}
