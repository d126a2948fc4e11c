/* Allocation through the caller's hooks (or libc); nothing in MACS allocates any other way. */
#include <stdlib.h>
#include <string.h>

#include "internal.h"

bool macsi_allocator_valid(const macs_allocator *a)
{
    /* Mixing a custom alloc with libc free would corrupt the heap, so it is all or nothing. */
    bool any = a->alloc || a->realloc || a->free;
    bool all = a->alloc && a->realloc && a->free;
    return !any || all;
}

void *macsi_alloc(const macs_allocator *a, size_t size)
{
    if (size == 0)
        size = 1; /* a zero-size request must still give a pointer that free accepts */
    return a->alloc ? a->alloc(size, a->user) : malloc(size);
}

void *macsi_calloc(const macs_allocator *a, size_t count, size_t size)
{
    if (size != 0 && count > (size_t)-1 / size)
        return NULL;
    size_t n = count * size;
    void *p = macsi_alloc(a, n);
    if (p)
        memset(p, 0, n > 0 ? n : 1);
    return p;
}

void macsi_free(const macs_allocator *a, void *ptr)
{
    if (!ptr)
        return;
    if (a->free)
        a->free(ptr, a->user);
    else
        free(ptr);
}

char *macsi_strdup(const macs_allocator *a, const char *s)
{
    size_t n = strlen(s) + 1;
    char *p = macsi_alloc(a, n);
    if (p)
        memcpy(p, s, n);
    return p;
}
