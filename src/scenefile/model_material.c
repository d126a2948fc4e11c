/* A model file's materials as bg_materials: the mapping of docs/scene_format.md ("Materials of
 * model files"), one function per part of the material. Where the material model cannot say what
 * the file says texel by texel (ambient occlusion, a blend alpha), a texture is baked at load. */
#include "model_internal.h"

#include <assimp/GltfMaterial.h>
#include <assimp/scene.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static bool color4_of(const struct aiMaterial *am, const char *key, unsigned type, unsigned index, double rgba[4])
{
    struct aiColor4D c;
    if (aiGetMaterialColor(am, key, type, index, &c) != aiReturn_SUCCESS)
        return false;
    double v[4] = {c.r, c.g, c.b, c.a};
    for (int i = 0; i < 4; i++)
        rgba[i] = isfinite(v[i]) && v[i] > 0 ? v[i] : 0.0;
    return true;
}

static bool color_of(const struct aiMaterial *am, const char *key, unsigned type, unsigned index, double rgb[3])
{
    double rgba[4];
    if (!color4_of(am, key, type, index, rgba))
        return false;
    memcpy(rgb, rgba, 3 * sizeof *rgb);
    return true;
}

static bool float_of(const struct aiMaterial *am, const char *key, unsigned type, unsigned index, double *out)
{
    ai_real f;
    unsigned int n = 1;
    if (aiGetMaterialFloatArray(am, key, type, index, &f, &n) != aiReturn_SUCCESS || n < 1 || !isfinite(f))
        return false;
    *out = f;
    return true;
}

static double clamp01(double x)
{
    return x < 0 ? 0 : x > 1 ? 1 : x;
}

static bool has_extension(const char *path, const char *extension)
{
    size_t n = strlen(path), e = strlen(extension);
    return n >= e && strcasecmp(path + n - e, extension) == 0;
}

static bool is_gltf(const bgi_sf_model *md)
{
    return has_extension(md->desc->path, ".gltf") || has_extension(md->desc->path, ".glb");
}

/* glTF's alphaMode ("OPAQUE", "MASK" or "BLEND") into mode; false for a file that has none (not a
 * glTF file), whose opacity then means what the format says (MTL d). */
static bool gltf_alpha_mode(const struct aiMaterial *am, char mode[16])
{
    struct aiString s;
    if (aiGetMaterialString(am, AI_MATKEY_GLTF_ALPHAMODE, &s) != aiReturn_SUCCESS)
        return false;
    snprintf(mode, 16, "%.15s", s.data);
    return true;
}

/* The sRGB transfer function's inverse: an 8-bit sRGB colour sample as linear. */
static float srgb_to_linear(unsigned char v)
{
    double c = v / 255.0;
    return (float)(c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4));
}

/* The texel of image at the place of texel (x, y) of a w x h grid: the nearest one, texel centres
 * lined up, so that two images of different sizes over one surface meet where their uvs meet. */
static const unsigned char *nearest(const bg_image *image, int x, int y, int w, int h)
{
    int sx = (int)(((double)x + 0.5) * image->width / w), sy = (int)(((double)y + 0.5) * image->height / h);
    return (const unsigned char *)image->pixels + (size_t)sy * image->stride + 4 * (size_t)sx;
}

/* A linear value in [0, 1] as the nearest 8-bit sRGB code: a colour bake keeps the precision of the
 * 8-bit sRGB image it comes from (its steps are as fine in the darks), at 4 bytes a texel rather
 * than the 16 of floats (docs/shading.md 5.2). */
static unsigned char linear_to_srgb_byte(double l)
{
    l = l < 0.0 ? 0.0 : (l > 1.0 ? 1.0 : l);
    double c = l <= 0.0031308 ? 12.92 * l : 1.055 * pow(l, 1.0 / 2.4) - 0.055;
    return (unsigned char)floor(c * 255.0 + 0.5);
}

/* An RGBA8 image for a bake. */
static unsigned char *alloc_byte_image(bgi_sf_model *md, int w, int h, bg_image *out)
{
    unsigned char *px = malloc((size_t)w * h * 4);
    if (!px)
        bgi_sf_fail(md->ctx, BG_ERR_OUT_OF_MEMORY, "out of memory baking a %d x %d texture of \"%s\"", w, h,
                    md->desc->path);
    *out = (bg_image){w, h, BG_PIXEL_RGBA8, 0, px};
    return px;
}

/* The base colour and its texture (sRGB). base_image is the decoded texture, NULL when there is none. */
static bg_status map_base(bgi_sf_model *md, const struct aiMaterial *am, const char *mname, bg_material *m,
                          bool *pbr, double *alpha, bgi_sf_model_image **base_image)
{
    static const enum aiTextureType color_types[] = {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE};
    double rgba[4] = {0, 0, 0, 1};
    bool dropped;
    *pbr = color4_of(am, AI_MATKEY_BASE_COLOR, rgba);
    if (*pbr || color4_of(am, AI_MATKEY_COLOR_DIFFUSE, rgba))
        m->base.reflectance = (bg_color_param){rgba[0], rgba[1], rgba[2], 0};
    *alpha = clamp01(rgba[3]);
    BGI_SF_TRY(bgi_sf_model_image_of(md, am, color_types, 2, mname, "base colour", base_image, &dropped));
    if (*base_image)
        BGI_SF_TRY(bgi_sf_model_image_texture(md, *base_image, BG_TEXTURE_SRGB, &m->base.reflectance.texture));
    return BG_OK;
}

/* glTF metallic and roughness: the factors times the B and G channels of the metallicRoughness
 * texture (linear). Roughness follows the texture texel by texel. The material model cannot switch
 * between metal and dielectric texel by texel, so the whole material is a metal when metallicFactor
 * times the mean of B is at least 1/2 (a metal: the base colour is its glossy reflectance), and
 * otherwise a dielectric (the Lambertian base under a coat of reflectance 0.04). */
static bg_status map_metal_rough(bgi_sf_model *md, const struct aiMaterial *am, const char *mname, bg_material *m)
{
    /* assimp 5.2 names the packed texture three ways (METALNESS, DIFFUSE_ROUGHNESS and glTF's own
     * UNKNOWN 0), later versions only the first two. */
    static const enum aiTextureType types[] = {aiTextureType_METALNESS, aiTextureType_DIFFUSE_ROUGHNESS,
                                               aiTextureType_UNKNOWN};
    double metallic = 0.0, roughness = 1.0;
    float_of(am, AI_MATKEY_METALLIC_FACTOR, &metallic);
    float_of(am, AI_MATKEY_ROUGHNESS_FACTOR, &roughness);
    bg_scalar_param r = {clamp01(roughness), 0, 1};
    bgi_sf_model_image *im = NULL;
    bool dropped;
    if (is_gltf(md))
        BGI_SF_TRY(bgi_sf_model_image_of(md, am, types, 3, mname, "metallic-roughness", &im, &dropped));
    if (im) {
        BGI_SF_TRY(bgi_sf_model_image_texture(md, im, BG_TEXTURE_LINEAR, &r.texture));
        double sum = 0;
        for (int y = 0; y < im->image.height; y++)
            for (int x = 0; x < im->image.width; x++)
                sum += ((const unsigned char *)im->image.pixels)[im->image.stride * y + 4 * (size_t)x + 2];
        metallic *= sum / 255.0 / ((double)im->image.width * im->image.height);
    }
    if (metallic >= 0.5) {
        m->base.roughness = r;
    } else if (r.value < 1.0 || r.texture) {
        m->has_coat = true;
        m->coat.roughness = r;
    }
    return BG_OK;
}

/* Emission: the factor times the emissive texture, times KHR_materials_emissive_strength. A factor
 * without a texture is a plain colour; a factor whose texture cannot be read is left out with the
 * texture, since the factor alone (often [1, 1, 1] beside a texture) would light the whole surface. */
static bg_status map_emission(bgi_sf_model *md, const struct aiMaterial *am, const char *mname, bg_material *m)
{
    static const enum aiTextureType emissive_types[] = {aiTextureType_EMISSIVE};
    double rgb[3], strength = 1.0;
    if (!color_of(am, AI_MATKEY_COLOR_EMISSIVE, rgb))
        return BG_OK;
    if (float_of(am, AI_MATKEY_EMISSIVE_INTENSITY, &strength) && strength >= 0)
        for (int k = 0; k < 3; k++)
            rgb[k] *= strength;
    bool dropped;
    bgi_sf_model_image *im = NULL;
    uint32_t texture = 0;
    BGI_SF_TRY(bgi_sf_model_image_of(md, am, emissive_types, 1, mname, "emissive", &im, &dropped));
    if (im)
        BGI_SF_TRY(bgi_sf_model_image_texture(md, im, BG_TEXTURE_SRGB, &texture));
    if (dropped)
        bgi_sf_warn(md->ctx, "material \"%s\": its emissive factor is left out with its texture", mname);
    else
        m->emission = (bg_color_param){rgb[0], rgb[1], rgb[2], texture};
    return BG_OK;
}

/* The ambient colour follows the base colour and its texture, so that a textured surface keeps its
 * texture under ambient light; an eighth of it, so that the default grey 0.8 keeps the default
 * ambient colour 0.1. A file's own ambient colour (MTL Ka) is not read: exporters write white or a
 * copy of Kd by habit, which washed every textured surface out. A glTF occlusion texture scales it
 * texel by texel: a texture baked here, the base texture (as linear) times the occlusion,
 * 1 + strength (R - 1), at the larger size of the two, each read at its nearest texel, stored as
 * 8-bit sRGB like the base texture (within half a code of the product). */
static bg_status map_ambient(bgi_sf_model *md, const struct aiMaterial *am, const char *mname, bg_material *m,
                             bgi_sf_model_image *base)
{
    static const enum aiTextureType occlusion_types[] = {aiTextureType_AMBIENT_OCCLUSION, aiTextureType_LIGHTMAP};
    const bg_color_param *b = &m->base.reflectance;
    m->ambient = (bg_color_param){b->r / 8, b->g / 8, b->b / 8, b->texture};
    bgi_sf_model_image *occ = NULL;
    bool dropped;
    if (is_gltf(md))
        BGI_SF_TRY(bgi_sf_model_image_of(md, am, occlusion_types, 2, mname, "occlusion", &occ, &dropped));
    if (!occ)
        return BG_OK;
    BGI_SF_TRY(bgi_sf_model_image_pixels(md, occ));
    if (base)
        BGI_SF_TRY(bgi_sf_model_image_pixels(md, base));
    double strength = 1.0;
    if (!float_of(am, AI_MATKEY_GLTF_TEXTURE_STRENGTH(aiTextureType_LIGHTMAP, 0), &strength))
        float_of(am, AI_MATKEY_GLTF_TEXTURE_STRENGTH(aiTextureType_AMBIENT_OCCLUSION, 0), &strength);
    strength = clamp01(strength);
    int w = occ->image.width, h = occ->image.height;
    if (base) {
        w = base->image.width > w ? base->image.width : w;
        h = base->image.height > h ? base->image.height : h;
    }
    bg_image baked;
    unsigned char *px = alloc_byte_image(md, w, h, &baked);
    if (!px)
        return BG_ERR_OUT_OF_MEMORY;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double o = 1.0 + strength * (nearest(&occ->image, x, y, w, h)[0] / 255.0 - 1.0);
            const unsigned char *c = base ? nearest(&base->image, x, y, w, h) : NULL;
            unsigned char *p = &px[4 * ((size_t)y * w + x)];
            for (int k = 0; k < 3; k++)
                p[k] = linear_to_srgb_byte((c ? srgb_to_linear(c[k]) : 1.0) * o);
            p[3] = 255;
        }
    bg_status st = bgi_sf_model_add_texture(md, &baked, BG_TEXTURE_SRGB, "the baked ambient occlusion texture",
                                            &m->ambient.texture);
    free(px);
    return st;
}

/* glTF alphaMode BLEND: transparency 1 - alpha, alpha the base colour factor's times the base
 * texture's, with ior 1 so that light passes straight through as a blended surface lets it. A base
 * texture with alpha gets a linear 8-bit texture baked here holding 1 - alpha in channel 0 (to
 * the nearest 1/255, the precision of the texture's alpha). MASK: a
 * cut-out where that alpha is below alphaCutoff (default 0.5): the coverage is the factor's alpha
 * times the base texture's alpha channel, which the texture keeps linear. OPAQUE ignores alpha, as
 * glTF says. A file without alphaMode (MTL) takes its opacity (d) as given. */
static bg_status map_alpha(bgi_sf_model *md, const struct aiMaterial *am, bg_material *m, double alpha,
                           bgi_sf_model_image *base)
{
    char mode[16];
    double x;
    if (!gltf_alpha_mode(am, mode)) {
        if (float_of(am, AI_MATKEY_OPACITY, &x))
            m->transparency.value = clamp01(1.0 - x);
        return BG_OK;
    }
    if (strcmp(mode, "MASK") == 0) {
        double cutoff = 0.5;
        float_of(am, AI_MATKEY_GLTF_ALPHACUTOFF, &cutoff);
        m->coverage = (bg_scalar_param){alpha, base ? m->base.reflectance.texture : 0, 3};
        m->coverage_cutoff = clamp01(cutoff);
        return BG_OK;
    }
    if (strcmp(mode, "BLEND") != 0)
        return BG_OK;
    m->ior = 1.0;
    m->transparency.value = 1.0 - alpha;
    if (base)
        BGI_SF_TRY(bgi_sf_model_image_pixels(md, base));
    bool has_alpha = false;
    const bg_image *im = base ? &base->image : NULL;
    for (int y = 0; im && y < im->height && !has_alpha; y++)
        for (int i = 0; i < im->width && !has_alpha; i++)
            has_alpha = ((const unsigned char *)im->pixels)[im->stride * y + 4 * (size_t)i + 3] < 255;
    if (!has_alpha)
        return BG_OK;
    bg_image baked;
    unsigned char *px = alloc_byte_image(md, im->width, im->height, &baked);
    if (!px)
        return BG_ERR_OUT_OF_MEMORY;
    for (int y = 0; y < im->height; y++)
        for (int i = 0; i < im->width; i++) {
            unsigned char *p = &px[4 * ((size_t)y * im->width + i)];
            double t = 1.0 - alpha * ((const unsigned char *)im->pixels)[im->stride * y + 4 * (size_t)i + 3] / 255.0;
            p[0] = (unsigned char)floor(t * 255.0 + 0.5);
            p[1] = p[2] = 0;
            p[3] = 255;
        }
    m->transparency = (bg_scalar_param){1.0, 0, 0};
    bg_status st = bgi_sf_model_add_texture(md, &baked, BG_TEXTURE_LINEAR, "the baked transparency texture",
                                            &m->transparency.texture);
    free(px);
    return st;
}

/* PLY and STL carry no materials, and an OBJ without its MTL names none: assimp then invents one,
 * white with a white ambient and specular colour (PLY, STL) that would render as a white silhouette
 * or a dark mirror. Such a file gets the neutral grey diffuse of bg_material_init instead. */
static bool invented_by_assimp(const bgi_sf_model *md, const char *mname)
{
    return has_extension(md->desc->path, ".ply") || has_extension(md->desc->path, ".stl") ||
           strcmp(mname, AI_DEFAULT_MATERIAL_NAME) == 0;
}

static bg_status map_material(bgi_sf_model *md, const struct aiMaterial *am, const char *mname, bg_material *m)
{
    double rgb[3], x, alpha;
    bool pbr;
    bgi_sf_model_image *base = NULL;
    BGI_SF_TRY(map_base(md, am, mname, m, &pbr, &alpha, &base));
    if (pbr) {
        BGI_SF_TRY(map_metal_rough(md, am, mname, m));
    } else if (color_of(am, AI_MATKEY_COLOR_SPECULAR, rgb) && (rgb[0] > 0 || rgb[1] > 0 || rgb[2] > 0)) {
        m->has_coat = true;
        m->coat.reflectance = (bg_color_param){rgb[0], rgb[1], rgb[2], 0};
        if (float_of(am, AI_MATKEY_SHININESS, &x) && x >= 0)
            m->coat.roughness.value = clamp01(sqrt(2.0 / (x + 2.0)));
    }
    BGI_SF_TRY(map_emission(md, am, mname, m));
    /* Only the base image is read again (by the bakes below): the others' textures are added. */
    bgi_sf_model_images_release(md, base);
    if (float_of(am, AI_MATKEY_REFRACTI, &x) && x > 0)
        m->ior = x;
    BGI_SF_TRY(map_alpha(md, am, m, alpha, base));
    /* glTF: a material is single-sided unless doubleSided (assimp's twosided) says otherwise; a
     * single-sided surface is culled from behind, a double-sided one lit on both sides. Other formats
     * say nothing of sides, and their meshes stay closed solids. */
    int two_sided = 0;
    if (is_gltf(md))
        m->sides = aiGetMaterialIntegerArray(am, AI_MATKEY_TWOSIDED, &two_sided, NULL) == aiReturn_SUCCESS && two_sided
                       ? BG_SIDES_BOTH
                       : BG_SIDES_FRONT;
    BGI_SF_TRY(map_ambient(md, am, mname, m, base));
    bgi_sf_model_images_release(md, NULL);
    /* Normal and bump maps need a per-vertex tangent frame and a perturbed shading normal, which
     * neither renderer has (docs/scene_format.md says so); the surface keeps its interpolated normals. */
    if (aiGetMaterialTextureCount(am, aiTextureType_NORMALS) > 0 || aiGetMaterialTextureCount(am, aiTextureType_HEIGHT) > 0)
        bgi_sf_warn(md->ctx, "material \"%s\": its normal (or bump) map is left out: the renderers shade with the "
                    "mesh's interpolated normals and have no normal mapping", mname);
    static const enum aiTextureType unmapped[] = {aiTextureType_SPECULAR, aiTextureType_OPACITY,
                                                  aiTextureType_SHININESS};
    for (size_t i = 0; i < sizeof unmapped / sizeof unmapped[0]; i++)
        if (aiGetMaterialTextureCount(am, unmapped[i]) > 0)
            bgi_sf_warn(md->ctx, "material \"%s\": its %s texture is left out (only the colour, emissive, glTF "
                        "metallic-roughness and occlusion textures are mapped)", mname,
                        aiTextureTypeToString(unmapped[i]));
    return BG_OK;
}

bg_status bgi_sf_model_material(bgi_sf_model *md, unsigned index, uint32_t *out)
{
    if (index >= md->sc->mNumMaterials)
        return bgi_sf_default_material(md->ctx, out);
    if (md->materials[index]) {
        *out = md->materials[index];
        return BG_OK;
    }
    const struct aiMaterial *am = md->sc->mMaterials[index];
    struct aiString name;
    const char *mname = aiGetMaterialString(am, AI_MATKEY_NAME, &name) == aiReturn_SUCCESS ? name.data : "";
    bg_material m = bg_material_init();
    if (invented_by_assimp(md, mname)) {
        const bg_color_param *b = &m.base.reflectance;
        m.ambient = (bg_color_param){b->r / 8, b->g / 8, b->b / 8, 0};
    } else {
        BGI_SF_TRY(map_material(md, am, mname, &m));
    }
    bg_status st = bg_scene_add_material(md->ctx->scene, &m, &md->materials[index]);
    if (st != BG_OK)
        return bgi_sf_scene_fail(md->ctx, st, "the model's material");
    md->ctx->out->summary.materials++;
    *out = md->materials[index];
    return BG_OK;
}
