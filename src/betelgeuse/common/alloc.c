/* The library's only calls to malloc, realloc and free, so the caller's hooks see everything. */
#include "alloc.h"

#include <stdlib.h>
#include <string.h>

bool bgi_allocator_valid(const bg_allocator *a)
{
    bool none = !a->alloc && !a->realloc && !a->free;
    return none || (a->alloc && a->free);
}

void *bgi_alloc(const bg_allocator *a, size_t size)
{
    if (size == 0)
        return NULL;
    return a->alloc ? a->alloc(size, a->user) : malloc(size);
}

void *bgi_realloc(const bg_allocator *a, void *ptr, size_t old_size, size_t new_size)
{
    if (new_size == 0)
        return NULL;
    if (!a->alloc)
        return realloc(ptr, new_size);
    if (a->realloc)
        return a->realloc(ptr, new_size, a->user);
    /* Hooks without realloc: move by hand, which needs the old size. */
    void *p = a->alloc(new_size, a->user);
    if (!p)
        return NULL;
    if (ptr) {
        memcpy(p, ptr, old_size < new_size ? old_size : new_size);
        a->free(ptr, a->user);
    }
    return p;
}

void bgi_free(const bg_allocator *a, void *ptr)
{
    if (!ptr)
        return;
    if (a->free)
        a->free(ptr, a->user);
    else
        free(ptr);
}

bool bgi_size_mul(size_t a, size_t b, size_t *out)
{
    if (a != 0 && b > (size_t)-1 / a)
        return false;
    *out = a * b;
    return true;
}

char *bgi_strdup(const bg_allocator *a, const char *s)
{
    size_t n = strlen(s) + 1;
    char *c = bgi_alloc(a, n);
    if (c)
        memcpy(c, s, n);
    return c;
}
