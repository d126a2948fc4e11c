/* The first error an object keeps, and the one way a failure is recorded: MACS's context,
 * Betelgeuse's scene and its renderer all keep the same {status, message} record the same way.
 * Only the first error is kept until cleared (later ones are usually its consequences); every
 * failure, first or not, goes to the object's logger.
 *
 * Header-only, every function static inline: each library compiles its own copy, so libbetelgeuse
 * links to no internal symbol of libmacs (whose shared build exports only the public API), and the
 * include points from the upper layer down to the lower one, never back. Nothing here knows either
 * library's types: a status is an int, 0 (MACS_OK, BG_OK) meaning none. */
#ifndef MACS_FIRST_ERROR_H
#define MACS_FIRST_ERROR_H

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* Room for one message, of any of the three objects: the longest is a shader info log, truncated
 * to fit. */
#define MACS_MESSAGE_SIZE 4096

typedef struct macs_first_error {
    int status;                      /* 0: none */
    char message[MACS_MESSAGE_SIZE]; /* "" while status is 0 */
} macs_first_error;

/* "<prefix><format, args>" into buffer, truncated to MACS_MESSAGE_SIZE; prefix may be NULL. */
static inline void macs_message_vformat(char buffer[MACS_MESSAGE_SIZE], const char *prefix, const char *format,
                                        va_list args)
{
    size_t n = 0;
    buffer[0] = '\0';
    if (prefix) {
        int written = snprintf(buffer, MACS_MESSAGE_SIZE, "%s", prefix);
        if (written < 0)
            return;
        n = (size_t)written < MACS_MESSAGE_SIZE ? (size_t)written : MACS_MESSAGE_SIZE - 1;
    }
    vsnprintf(buffer + n, MACS_MESSAGE_SIZE - n, format, args);
}

/* Formats a failure into buffer and keeps it in e if e holds no error yet (a status of 0 is never
 * kept). Returns buffer: the message the caller hands to its object's logger, which stays the
 * caller's call because the two libraries' logger types differ. */
static inline const char *macs_first_error_vrecord(macs_first_error *e, int status, char buffer[MACS_MESSAGE_SIZE],
                                                   const char *prefix, const char *format, va_list args)
{
    macs_message_vformat(buffer, prefix, format, args);
    if (e->status == 0 && status != 0) {
        e->status = status;
        memcpy(e->message, buffer, MACS_MESSAGE_SIZE);
    }
    return buffer;
}

/* Forgets the kept error: the next failure is the first again. */
static inline void macs_first_error_clear(macs_first_error *e)
{
    e->status = 0;
    e->message[0] = '\0';
}

/* Copies a message into a caller's buffer (NULL or size 0: nothing), as the create calls do whose
 * object does not exist to keep it. */
static inline void macs_message_give(char *message, size_t size, const char *text)
{
    if (message && size > 0)
        snprintf(message, size, "%s", text);
}

#endif
