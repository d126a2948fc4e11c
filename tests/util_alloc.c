/* Counting allocation hooks for tests (util_alloc.h). Each block carries its size in a header, so
 * that frees can count bytes; the header is as wide as the strictest alignment malloc gives. */
#include <stdlib.h>

#include "util_alloc.h"

typedef union header {
    size_t size;
    long double align_ld;
    void *align_p;
    long long align_ll;
} header;

static int refuse(util_alloc_counter *c)
{
    if (c->fail_after >= 0 && c->allocs >= c->fail_after) {
        c->refused++;
        return 1;
    }
    return 0;
}

void *util_counted_alloc(size_t size, void *user)
{
    util_alloc_counter *c = user;
    if (refuse(c))
        return NULL;
    header *h = malloc(sizeof *h + size);
    if (!h)
        return NULL;
    h->size = size;
    c->allocs++;
    c->live_bytes += size;
    return h + 1;
}

void *util_counted_realloc(void *ptr, size_t size, void *user)
{
    util_alloc_counter *c = user;
    if (!ptr)
        return util_counted_alloc(size, user);
    if (refuse(c))
        return NULL;
    header *old = (header *)ptr - 1;
    size_t old_size = old->size;
    header *h = realloc(old, sizeof *h + size);
    if (!h)
        return NULL;
    h->size = size;
    c->live_bytes = c->live_bytes - old_size + size;
    return h + 1;
}

void util_counted_free(void *ptr, void *user)
{
    util_alloc_counter *c = user;
    if (!ptr)
        return;
    header *h = (header *)ptr - 1;
    c->frees++;
    c->live_bytes -= h->size;
    free(h);
}
