/* Validation of bg_render_settings, shared by the CPU and GPU renderers. */
#ifndef BG_RENDER_SETTINGS_H
#define BG_RENDER_SETTINGS_H

#include "betelgeuse.h"

#define BG_MAX_THREADS 256

/* BG_OK, or BG_ERR_INVALID_ARGUMENT with a message "<where>: settings.<field> ..." in message. */
bg_status bgi_render_settings_check(const bg_render_settings *s, const char *where, char *message, size_t size);

#endif
