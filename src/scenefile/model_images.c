/* The images of one model load (model_internal.h): each named source (a file, by its resolved path,
 * or an image embedded in the model, by its index) is read and decoded once, on its first use, and
 * each of its encodings added to the scene once; later uses get the same texture. */
#include "model_internal.h"

#include <assimp/scene.h>

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* Larger image files are refused before they are read whole (a 16384^2 RGBA PNG fits well within). */
#define IMAGE_FILE_MAX ((long)512 << 20)

/* The file read whole into *data (malloc). */
static bg_status read_file(bgi_sf_model *md, const char *path, const char *what, unsigned char **data, size_t *size)
{
    FILE *f = NULL;
    BGI_SF_TRY(bgi_sf_open_input(md->ctx, path, what, &f));
    size_t cap = 1 << 16, n = 0;
    unsigned char *buf = malloc(cap);
    bg_status st = BG_OK;
    while (buf) {
        n += fread(buf + n, 1, cap - n, f);
        if (n < cap)
            break;
        unsigned char *more = cap < (size_t)IMAGE_FILE_MAX ? realloc(buf, cap * 2) : NULL;
        if (!more) {
            st = cap < (size_t)IMAGE_FILE_MAX ? BG_ERR_OUT_OF_MEMORY : BG_ERR_LIMIT;
            break;
        }
        buf = more;
        cap *= 2;
    }
    if (!buf)
        st = BG_ERR_OUT_OF_MEMORY;
    if (st == BG_OK && ferror(f))
        st = bgi_sf_fail(md->ctx, BG_ERR_IO, "%s: read error: %s", what, strerror(errno));
    else if (st == BG_ERR_LIMIT)
        st = bgi_sf_fail(md->ctx, st, "%s: larger than %ld bytes", what, IMAGE_FILE_MAX);
    else if (st != BG_OK)
        st = bgi_sf_fail(md->ctx, st, "%s: out of memory reading it", what);
    fclose(f);
    if (st != BG_OK) {
        free(buf);
        return st;
    }
    *data = buf;
    *size = n;
    return BG_OK;
}

/* Raw texels (mHeight > 0) are BGRA aiTexels; they become RGBA. */
static bg_status raw_texels(const struct aiTexture *t, bg_image *out, char *reason, size_t size)
{
    if (t->mWidth > BG_MAX_IMAGE_SIDE || t->mHeight > BG_MAX_IMAGE_SIDE || !t->pcData) {
        snprintf(reason, size, "its size %u x %u is outside 1..%d", t->mWidth, t->mHeight, BG_MAX_IMAGE_SIDE);
        return BG_ERR_IO;
    }
    size_t n = (size_t)t->mWidth * t->mHeight;
    unsigned char *px = malloc(n * 4);
    if (!px) {
        snprintf(reason, size, "out of memory for %u x %u texels", t->mWidth, t->mHeight);
        return BG_ERR_OUT_OF_MEMORY;
    }
    for (size_t i = 0; i < n; i++) {
        const struct aiTexel *x = &t->pcData[i];
        unsigned char *p = &px[4 * i];
        p[0] = x->r;
        p[1] = x->g;
        p[2] = x->b;
        p[3] = x->a;
    }
    *out = (bg_image){(int)t->mWidth, (int)t->mHeight, BG_PIXEL_RGBA8, (size_t)t->mWidth * 4, px};
    return BG_OK;
}

/* Decodes bytes into im, or marks im unsupported when their format is not read. hint is assimp's
 * format hint of an embedded image ("" for a file), named when the bytes say nothing. */
static bg_status decode(bgi_sf_model_image *im, const unsigned char *data, size_t size, const char *hint,
                        char *reason, size_t reason_size)
{
    bgi_sf_image_format f = bgi_sf_image_sniff(data, size);
    if (f != BGI_SF_IMAGE_PNG && f != BGI_SF_IMAGE_JPEG) {
        im->unsupported = true;
        snprintf(im->format, sizeof im->format, "%s", f == BGI_SF_IMAGE_UNKNOWN && hint[0] ? hint
                                                                                          : bgi_sf_image_format_name(f));
        return BG_OK;
    }
    return bgi_sf_image_decode(data, size, &im->image, reason, reason_size);
}

/* Reads and decodes image im of the model; what names it in failures. */
static bg_status load_image(bgi_sf_model *md, bgi_sf_model_image *im, const char *what)
{
    char reason[256] = "";
    bg_status st;
    if (im->embedded >= 0) {
        const struct aiTexture *t = md->sc->mTextures[im->embedded];
        if (t->mHeight > 0)
            st = raw_texels(t, &im->image, reason, sizeof reason);
        else
            st = t->pcData ? decode(im, (const unsigned char *)t->pcData, t->mWidth, t->achFormatHint, reason,
                                    sizeof reason)
                           : (snprintf(reason, sizeof reason, "it holds no data"), BG_ERR_IO);
    } else {
        unsigned char *data = NULL;
        size_t size = 0;
        BGI_SF_TRY(read_file(md, im->path, what, &data, &size));
        st = decode(im, data, size, "", reason, sizeof reason);
        free(data);
    }
    if (st != BG_OK)
        return bgi_sf_fail(md->ctx, st, "%s: %s", what, reason);
    return BG_OK;
}

/* The cache entry of a source (embedded index, or path when index < 0), made if new. */
static bg_status entry(bgi_sf_model *md, int index, const char *path, const char *name, bgi_sf_model_image **out,
                       bool *fresh)
{
    for (size_t i = 0; i < md->image_count; i++) {
        bgi_sf_model_image *im = md->images[i];
        if (im->embedded == index && (index >= 0 || strcmp(im->path, path) == 0)) {
            *out = im;
            *fresh = false;
            return BG_OK;
        }
    }
    if (md->image_count == md->image_capacity) {
        size_t cap = md->image_capacity ? 2 * md->image_capacity : 8;
        bgi_sf_model_image **more = realloc(md->images, cap * sizeof *more);
        if (!more)
            return bgi_sf_fail(md->ctx, BG_ERR_OUT_OF_MEMORY, "out of memory reading \"%s\"", md->desc->path);
        md->images = more;
        md->image_capacity = cap;
    }
    bgi_sf_model_image *im = calloc(1, sizeof *im);
    if (!im)
        return bgi_sf_fail(md->ctx, BG_ERR_OUT_OF_MEMORY, "out of memory reading \"%s\"", md->desc->path);
    md->images[md->image_count] = im;
    im->embedded = index;
    if (index < 0 && !(im->path = strdup(path))) {
        free(im);
        return bgi_sf_fail(md->ctx, BG_ERR_OUT_OF_MEMORY, "out of memory reading \"%s\"", md->desc->path);
    }
    snprintf(im->name, sizeof im->name, "%s", name);
    md->image_count++;
    *out = im;
    *fresh = true;
    return BG_OK;
}

/* "*N" (assimp's name of embedded image N): N when it is one of the scene's images, else -1. */
static int embedded_index(const bgi_sf_model *md, const char *file)
{
    if (file[0] != '*' || file[1] < '0' || file[1] > '9')
        return -1;
    char *end;
    errno = 0;
    unsigned long n = strtoul(file + 1, &end, 10);
    return *end || errno || n >= md->sc->mNumTextures ? -1 : (int)n;
}

/* "C:\..." or "C:/...": an absolute path on a Windows drive. */
static bool is_drive_path(const char *file)
{
    return ((file[0] >= 'A' && file[0] <= 'Z') || (file[0] >= 'a' && file[0] <= 'z')) && file[1] == ':' &&
           (file[2] == '\\' || file[2] == '/');
}

/* A texture path as the system that wrote it meant it, for this one: backslashes are separators
 * (exporters on Windows write ".\\tex.jpg" and "maps\\wood.png"), leading "./" parts go, and a path
 * on a drive ("C:\\art\\tex.jpg") keeps only its file name, to be looked for beside the model.
 * False when it does not fit out. */
static bool local_path(const char *file, char *out, size_t size)
{
    if (is_drive_path(file)) {
        const char *base = file;
        for (const char *c = file; *c; c++)
            if (*c == '\\' || *c == '/')
                base = c + 1;
        file = base;
    }
    size_t n = 0;
    for (const char *c = file; *c; c++) {
        if (n + 1 >= size)
            return false;
        out[n++] = *c == '\\' ? '/' : *c;
    }
    out[n] = '\0';
    while (out[0] == '.' && out[1] == '/') {
        size_t skip = 2;
        while (out[skip] == '/')
            skip++;
        memmove(out, out + skip, strlen(out + skip) + 1);
    }
    return true;
}

bg_status bgi_sf_model_image_of(bgi_sf_model *md, const struct aiMaterial *am, const enum aiTextureType *types,
                                int ntypes, const char *mname, const char *slot, bgi_sf_model_image **out,
                                bool *dropped)
{
    struct aiString s;
    bool found = false;
    *out = NULL;
    *dropped = false;
    for (int i = 0; i < ntypes && !found; i++)
        found = aiGetMaterialTexture(am, types[i], 0, &s, NULL, NULL, NULL, NULL, NULL, NULL) == aiReturn_SUCCESS;
    if (!found)
        return BG_OK;
    const char *file = s.data;
    if (strlen(file) != s.length)
        return bgi_sf_fail(md->ctx, BG_ERR_INVALID_ARGUMENT, "model file \"%s\": material \"%s\": the %s texture "
                           "file name holds a NUL character", md->desc->path, mname, slot);
    int index = file[0] == '*' ? embedded_index(md, file) : -1;
    if (file[0] == '*' && index < 0)
        return bgi_sf_fail(md->ctx, BG_ERR_INVALID_ARGUMENT, "model file \"%s\": material \"%s\": the %s texture "
                           "\"%s\" names no embedded image (the file has %u)", md->desc->path, mname, slot, file,
                           md->sc->mNumTextures);
    char path[BGI_SF_PATH_MAX], name[64], local[BGI_SF_PATH_MAX];
    if (index >= 0) {
        snprintf(name, sizeof name, "\"*%d\" (embedded image %d)", index, index);
    } else {
        if (!local_path(file, local, sizeof local))
            return bgi_sf_fail(md->ctx, BG_ERR_INVALID_ARGUMENT, "model file \"%s\": material \"%s\": the %s "
                               "texture path is too long", md->desc->path, mname, slot);
        if (strcmp(local, file) != 0 && is_drive_path(file))
            bgi_sf_warn(md->ctx, "model file \"%s\": material \"%s\": the %s texture \"%.200s\" is a path on "
                        "another system's drive; it is looked for beside the model", md->desc->path, mname, slot,
                        file);
        file = local;
        int n = snprintf(path, sizeof path, "%s%s", file[0] == '/' ? "" : md->dir, file);
        if (n < 0 || n >= (int)sizeof path)
            return bgi_sf_fail(md->ctx, BG_ERR_INVALID_ARGUMENT, "model file \"%s\": material \"%s\": the %s "
                               "texture path is too long", md->desc->path, mname, slot);
        const char *base = strrchr(file, '/');
        snprintf(name, sizeof name, "\"%.60s\"", base ? base + 1 : file);
    }
    /* Model viewers render a material whose texture file is missing with its factors, and say which
     * file: a model is often passed around without every texture. Any other failure to read one
     * stays an error. */
    struct stat st;
    if (index < 0 && stat(path, &st) != 0 && errno == ENOENT) {
        bgi_sf_warn(md->ctx, "model file \"%s\": material \"%s\": its %s texture file \"%s\" is missing; the "
                    "material keeps its factors", md->desc->path, mname, slot, path);
        *dropped = true;
        return BG_OK;
    }
    bgi_sf_model_image *im = NULL;
    bool fresh = false;
    BGI_SF_TRY(entry(md, index, path, name, &im, &fresh));
    if (fresh) {
        char what[2 * BGI_SF_PATH_MAX];
        if (index >= 0)
            snprintf(what, sizeof what, "model file \"%s\": material \"%.200s\": %s texture %s", md->desc->path,
                     mname, slot, im->name);
        else
            snprintf(what, sizeof what, "model file \"%s\": material \"%.200s\": %s texture file \"%s\"",
                     md->desc->path, mname, slot, path);
        if (!(im->what = strdup(what)))
            return bgi_sf_fail(md->ctx, BG_ERR_OUT_OF_MEMORY, "out of memory reading \"%s\"", md->desc->path);
        BGI_SF_TRY(load_image(md, im, what));
    }
    if (im->unsupported) {
        bgi_sf_warn(md->ctx, "model file \"%s\": material \"%s\": its %s texture %s is left out (%s images are "
                    "not read; PNG and JPEG are)", md->desc->path, mname, slot, im->name, im->format);
        *dropped = true;
        return BG_OK;
    }
    *out = im;
    return BG_OK;
}

/* Adds image as a texture (repeat, linear filtering) and counts it; what names it in a failure. */
static bg_status add(bgi_sf_model *md, const bg_image *image, bg_texture_encoding encoding, const char *what,
                     uint32_t *out)
{
    bg_texture_desc d = {BG_WRAP_REPEAT, encoding, BG_FILTER_LINEAR};
    bg_status st = bg_scene_add_texture(md->ctx->scene, image, &d, out);
    if (st != BG_OK)
        return bgi_sf_scene_fail(md->ctx, st, what);
    md->ctx->out->summary.textures++;
    return BG_OK;
}

bg_status bgi_sf_model_add_texture(bgi_sf_model *md, const bg_image *image, bg_texture_encoding encoding,
                                   const char *what, uint32_t *out)
{
    return add(md, image, encoding, what, out);
}

bg_status bgi_sf_model_image_texture(bgi_sf_model *md, bgi_sf_model_image *im, bg_texture_encoding encoding,
                                     uint32_t *out)
{
    if (!im->texture[encoding]) {
        char what[128];
        snprintf(what, sizeof what, "the texture of image %s", im->name);
        BGI_SF_TRY(bgi_sf_model_image_pixels(md, im));
        BGI_SF_TRY(add(md, &im->image, encoding, what, &im->texture[encoding]));
    }
    *out = im->texture[encoding];
    return BG_OK;
}

bg_status bgi_sf_model_image_pixels(bgi_sf_model *md, bgi_sf_model_image *im)
{
    return im->image.pixels || im->unsupported ? BG_OK : load_image(md, im, im->what);
}

void bgi_sf_model_images_release(bgi_sf_model *md, const bgi_sf_model_image *keep)
{
    for (size_t i = 0; i < md->image_count; i++)
        if (md->images[i] != keep) {
            free(md->images[i]->image.pixels);
            md->images[i]->image.pixels = NULL;
        }
}

void bgi_sf_model_images_free(bgi_sf_model *md)
{
    for (size_t i = 0; i < md->image_count; i++) {
        free(md->images[i]->path);
        free(md->images[i]->what);
        free(md->images[i]->image.pixels);
        free(md->images[i]);
    }
    free(md->images);
    md->images = NULL;
    md->image_count = md->image_capacity = 0;
}
