/* The model loader's own pieces (model.c): assimp's file access and the checks made before assimp
 * reads a file. Only the model files include this, so the rest of the library needs no assimp. */
#ifndef BG_SCENEFILE_MODEL_INTERNAL_H
#define BG_SCENEFILE_MODEL_INTERNAL_H

#include <assimp/cfileio.h>

#include "scenefile_internal.h"

/* ---- model_io.c ---- */

/* assimp's file callbacks over bgi_open_input (io is what aiImportFileEx takes). */
typedef struct bgi_sf_model_io {
    struct aiFileIO io;
    bgi_sf_ctx *ctx;
    char refused[512]; /* the first file refused for a reason other than being missing, and why */
} bgi_sf_model_io;

void bgi_sf_model_io_init(bgi_sf_model_io *m, bgi_sf_ctx *ctx);

/* ---- ply_check.c ---- */

/* When f (at its start) begins with "ply": the whole file checked as a PLY (a strict header, counts
 * that fit the file, numbers where numbers belong, face indices within the vertices), before
 * assimp, which trusts all of that, reads it; BG_ERR_INVALID_ARGUMENT naming the fault. BG_OK for
 * any other file. */
bg_status bgi_sf_check_ply(bgi_sf_ctx *ctx, const char *path, FILE *f);

#endif
