/* Run-time loading of the window-system libraries (library.h). The libraries stay mapped after the
 * last close (RTLD_NODELETE): Mesa's drivers bring LLVM, whose static state does not survive being
 * unloaded and loaded again within one process, and a program that makes a second headless context
 * after destroying its first must get a working one. */
#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

#include "library.h"

bool macsi_library_open(macsi_library *library, const char *const *sonames, char *message, size_t size)
{
    size_t used = 0;
    message[0] = '\0';
    library->handle = NULL;
    library->soname = NULL;
    for (int i = 0; sonames[i]; i++) {
        library->handle = dlopen(sonames[i], RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
        if (library->handle) {
            library->soname = sonames[i];
            return true;
        }
        const char *why = dlerror();
        if (used + 1 < size)
            snprintf(message + used, size - used, "%s%s could not be loaded (%s)", used ? "; " : "", sonames[i],
                     why ? why : "no reason given");
        used = strlen(message);
    }
    return false;
}

bool macsi_library_find_all(const macsi_library *library, const macsi_library_symbol *symbols, size_t count,
                            void *table, char *message, size_t size)
{
    /* dlsym returns a data pointer, which POSIX (not ISO C) lets stand for a function pointer of the
     * same size: the bits are copied rather than cast. */
    typedef char function_pointer_fits_a_data_pointer[sizeof(void (*)(void)) == sizeof(void *) ? 1 : -1];
    (void)sizeof(function_pointer_fits_a_data_pointer);
    for (size_t i = 0; i < count; i++) {
        void *address = dlsym(library->handle, symbols[i].name);
        if (!address) {
            snprintf(message, size, "%s has no %s", library->soname, symbols[i].name);
            return false;
        }
        memcpy((char *)table + symbols[i].offset, &address, sizeof address);
    }
    return true;
}

void macsi_library_close(macsi_library *library)
{
    if (library->handle)
        dlclose(library->handle);
    library->handle = NULL;
    library->soname = NULL;
}
