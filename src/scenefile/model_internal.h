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

/* ---- ply_counts.c ---- */

/* When f (at its start) is a PLY file: BG_ERR_INVALID_ARGUMENT when its body is too short for the
 * element counts its header declares; BG_OK for any other file. */
bg_status bgi_sf_check_ply_counts(bgi_sf_ctx *ctx, const char *path, FILE *f);

#endif
