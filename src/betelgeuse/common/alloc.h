/* Allocation through the caller's hooks. Every caller checks the result. */
#ifndef BG_ALLOC_H
#define BG_ALLOC_H

#include "betelgeuse.h"

/* True when the hooks are usable: all NULL, or alloc and free both set (realloc optional). */
bool bgi_allocator_valid(const bg_allocator *a);
/* size bytes, or NULL (also for size 0, so callers never keep a zero-size block). */
void *bgi_alloc(const bg_allocator *a, size_t size);
/* Resizes a block of old_size bytes; on failure returns NULL and leaves ptr untouched. */
void *bgi_realloc(const bg_allocator *a, void *ptr, size_t old_size, size_t new_size);
/* Frees a block from bgi_alloc or bgi_realloc; NULL is ignored. */
void bgi_free(const bg_allocator *a, void *ptr);
/* A copy of the string s through the hooks, or NULL. */
char *bgi_strdup(const bg_allocator *a, const char *s);
/* a * b into *out; false on overflow of size_t. */
bool bgi_size_mul(size_t a, size_t b, size_t *out);

#endif
