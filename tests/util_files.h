/* Files for the tests: a file read whole. */
#ifndef UTIL_FILES_H
#define UTIL_FILES_H

#include <stddef.h>

/* The bytes of path, whole (malloc'd; free it), their count in *size; fails the test when the file
 * cannot be read or is empty. */
unsigned char *util_read_file(const char *path, size_t *size);

#endif
