/* The model loader's own pieces: the load in progress (model.c), its images (model_images.c), its
 * materials (model_material.c), assimp's file access and the checks made before assimp reads a file.
 * Only the model files include this, so the rest of the library needs no assimp. */
#ifndef BG_SCENEFILE_MODEL_INTERNAL_H
#define BG_SCENEFILE_MODEL_INTERNAL_H

#include <assimp/cfileio.h>
#include <assimp/material.h>

#include "scenefile_internal.h"

/* ---- model_images.c ---- */

/* One image of the model, from a file beside it or embedded in it, added as a texture at most once
 * per encoding: a model whose materials share one image (a texture atlas) gets one texture. It is
 * decoded at its first use; once its textures are added its pixels are released (the scene holds
 * its own copy), and decoded again only if a later texture or bake needs them, so that a model's
 * decoded images do not all stay in memory until the end of the load. */
typedef struct bgi_sf_model_image {
    int embedded;              /* index in aiScene.mTextures, or -1 for a file */
    char *path;                /* the resolved file path (files only) */
    char name[64];             /* the image in messages: "\"*0\" (embedded image 0)" or the file's name */
    bool unsupported;          /* a format not read (KTX2, WebP, ...): every use is warned */
    char format[16];           /* what it is, in messages about an unsupported one */
    bg_image image;            /* RGBA8, tightly packed; pixels NULL while released */
    char *what;                /* the image as its first use named it, for a failure to decode it again */
    uint32_t texture[2];       /* per bg_texture_encoding, 0 until added */
} bgi_sf_model_image;

/* The load of one model file. */
typedef struct bgi_sf_model {
    bgi_sf_ctx *ctx;
    const bgi_sf_model_desc *desc;
    const struct aiScene *sc;
    char dir[BGI_SF_PATH_MAX];  /* the model's folder: its texture paths are relative to it */
    uint32_t *materials;        /* per file material, 0 until mapped */
    uint32_t *first;            /* per file mesh, its first object (later nodes instance it) */
    size_t *first_vertices;     /* per file mesh, the vertices its object holds (after welds and creases) */
    size_t added;               /* mesh objects added */
    bgi_sf_model_image **images; /* every image read so far, each allocated alone so that pointers stay */
    size_t image_count, image_capacity;
} bgi_sf_model;

/* The image of the material's first texture of the given types (slot names them in messages:
 * "base colour"), read and decoded at its first use. *out is NULL when the material has none, and
 * when the image is in a format not read: then a warning names the material, the slot, the image
 * and the file, and *dropped is true. A missing file or corrupt data is BG_ERR_IO naming the same. */
bg_status bgi_sf_model_image_of(bgi_sf_model *md, const struct aiMaterial *am, const enum aiTextureType *types,
                                int ntypes, const char *mname, const char *slot, bgi_sf_model_image **out,
                                bool *dropped);
/* The image's texture in the given encoding (repeat, linear filtering), added at its first use. */
bg_status bgi_sf_model_image_texture(bgi_sf_model *md, bgi_sf_model_image *im, bg_texture_encoding encoding,
                                     uint32_t *out);
/* A texture the loader made (a bake, RGBA8 in the encoding), added and counted; what names it in a failure. */
bg_status bgi_sf_model_add_texture(bgi_sf_model *md, const bg_image *image, bg_texture_encoding encoding,
                                   const char *what, uint32_t *out);
/* Makes im's pixels there again after a release (bgi_sf_model_images_release). */
bg_status bgi_sf_model_image_pixels(bgi_sf_model *md, bgi_sf_model_image *im);
/* Releases the decoded pixels of every image but keep (NULL: all). */
void bgi_sf_model_images_release(bgi_sf_model *md, const bgi_sf_model_image *keep);
void bgi_sf_model_images_free(bgi_sf_model *md);

/* ---- model_material.c ---- */

/* The material of the file's material index (docs/scene_format.md, "Materials of model files"),
 * mapped and added at its first use; an index past the file's materials gets the default one. */
bg_status bgi_sf_model_material(bgi_sf_model *md, unsigned index, uint32_t *out);

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
