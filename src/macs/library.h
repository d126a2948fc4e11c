/* Window-system libraries loaded at run time: the headless backends reach EGL and OSMesa through
 * dlopen by soname, so that libmacs links to neither and builds where Mesa ships no OSMesa (25.1 and
 * later). A backend whose library is missing is one more reason in the default order, never a
 * failed link or start of the program. */
#ifndef MACS_LIBRARY_H
#define MACS_LIBRARY_H

#include <stdbool.h>
#include <stddef.h>

/* A loaded library and the soname it was found by. */
typedef struct macsi_library {
    void *handle;
    const char *soname;
} macsi_library;

/* One function of a library's table: its symbol and where its pointer goes in the table. */
typedef struct macsi_library_symbol {
    const char *name;
    size_t offset;
} macsi_library_symbol;

/* Opens the first library of sonames (a NULL-terminated list, the preferred name first); false, with
 * every name tried and the loader's reason in message, where none loads. */
bool macsi_library_open(macsi_library *library, const char *const *sonames, char *message, size_t size);

/* Fills the function pointers of table at the offsets of symbols (count of them); false, with the
 * first missing symbol and the library named in message, where one is missing. */
bool macsi_library_find_all(const macsi_library *library, const macsi_library_symbol *symbols, size_t count,
                            void *table, char *message, size_t size);

/* Drops the reference of macsi_library_open (a library never opened is ignored). */
void macsi_library_close(macsi_library *library);

#endif
