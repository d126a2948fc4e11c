/* Model files through assimp's C API: every triangle mesh of the file's node tree becomes a mesh
 * object (a mesh that several nodes show is added once and instanced), placed by the node's world
 * transform after the caller's; materials are mapped by model_material.c. */
#include "model_internal.h"

#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/version.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* assimp's validation first: its importers pass a file's face indices on unchecked (a PLY face
 * "3 0 1 7" over 3 vertices), and the steps after it index arrays with them. Then triangulate
 * polygons, join identical vertices (formats such as STL and assimp's OBJ reader give three per
 * face), and sort by primitive type so that point and line meshes stand apart and are skipped. */
#define MODEL_FLAGS \
    (aiProcess_ValidateDataStructure | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType)

/* Node trees deeper than this are refused rather than risking the stack. */
#define MODEL_MAX_DEPTH 256

typedef bgi_sf_model model;

static bg_mat4 from_ai(const struct aiMatrix4x4 *a)
{
    bg_mat4 m;
    const ai_real *r[4] = {&a->a1, &a->b1, &a->c1, &a->d1};
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            m.m[i][j] = (double)r[i][j];
    return m;
}

static bool is_identity(bg_mat4 m)
{
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            if (m.m[i][j] != (i == j ? 1.0 : 0.0))
                return false;
    return true;
}

/* a then b, skipping identities so that an untransformed model keeps the caller's bits. */
static bg_mat4 compose(bg_mat4 outer, bg_mat4 inner)
{
    if (is_identity(inner))
        return outer;
    if (is_identity(outer))
        return inner;
    return bg_mat4_mul(outer, inner);
}

/* True when the mesh's normals are its faces' own (every triangle's three corners alike), as an STL
 * file's facet normals are: they say nothing a renderer's geometric normal does not, so the mesh is
 * taken as one without normals, which smoothing may fill in. */
static bool normals_are_facets(const struct aiMesh *am)
{
    for (unsigned f = 0; f < am->mNumFaces; f++) {
        const struct aiFace *face = &am->mFaces[f];
        if (face->mNumIndices != 3)
            continue;
        const struct aiVector3D *a = &am->mNormals[face->mIndices[0]], *b = &am->mNormals[face->mIndices[1]],
                                *c = &am->mNormals[face->mIndices[2]];
        if (a->x != b->x || a->y != b->y || a->z != b->z || a->x != c->x || a->y != c->y || a->z != c->z)
            return false;
    }
    return true;
}

static bg_status add_new_mesh(model *md, const struct aiMesh *am, uint32_t material, bg_mat4 m, uint32_t *out,
                              size_t *out_vertices)
{
    bgi_sf_ctx *ctx = md->ctx;
    size_t nv = am->mNumVertices, nt = 0;
    for (unsigned f = 0; f < am->mNumFaces; f++)
        nt += am->mFaces[f].mNumIndices == 3;
    bool file_normals = md->desc->normals == BGI_SF_NORMALS_FILE && am->mNormals && !normals_are_facets(am);
    /* "smooth" in a scene file smooths whatever the file has; desc->smooth_angle_degrees only fills
     * in the normals a file lacks. */
    double smooth = md->desc->normals == BGI_SF_NORMALS_SMOOTH ? 180.0
                    : md->desc->normals == BGI_SF_NORMALS_FILE && !file_normals ? md->desc->smooth_angle
                                                                                : 0.0;
    bool uvs = am->mTextureCoords[0] != NULL;
    float *p = malloc(nv * 3 * sizeof *p), *n = file_normals ? malloc(nv * 3 * sizeof *n) : NULL;
    float *uv = uvs ? malloc(nv * 2 * sizeof *uv) : NULL;
    uint32_t *idx = malloc(nt * 3 * sizeof *idx);
    bg_status st = BG_OK;
    if (!p || !idx || (file_normals && !n) || (uvs && !uv)) {
        st = bgi_sf_fail(ctx, BG_ERR_OUT_OF_MEMORY, "out of memory for mesh \"%s\" of %s (%zu vertices)",
                         am->mName.data, md->desc->path, nv);
        goto done;
    }
    for (size_t v = 0; v < nv; v++) {
        p[3 * v] = am->mVertices[v].x;
        p[3 * v + 1] = am->mVertices[v].y;
        p[3 * v + 2] = am->mVertices[v].z;
        if (file_normals) {
            n[3 * v] = am->mNormals[v].x;
            n[3 * v + 1] = am->mNormals[v].y;
            n[3 * v + 2] = am->mNormals[v].z;
        }
        if (uvs) {
            uv[2 * v] = am->mTextureCoords[0][v].x;
            uv[2 * v + 1] = am->mTextureCoords[0][v].y;
        }
    }
    size_t t = 0;
    for (unsigned f = 0; f < am->mNumFaces; f++)
        if (am->mFaces[f].mNumIndices == 3) {
            memcpy(&idx[3 * t], am->mFaces[f].mIndices, 3 * sizeof *idx);
            t++;
        }
    /* Averaging needs shared vertices: files that repeat every corner per face (STL) get them here. */
    if (smooth > 0 && (st = bgi_sf_weld_vertices(p, uv, &nv, idx, nt)) != BG_OK) {
        st = bgi_sf_fail(ctx, st, "out of memory welding the vertices of mesh \"%s\" of %s (%zu vertices)",
                         am->mName.data, md->desc->path, nv);
        goto done;
    }
    if (smooth > 0 && (st = bgi_sf_crease_normals(&p, &uv, &nv, idx, nt, smooth, &n)) != BG_OK) {
        st = bgi_sf_fail(ctx, st, "%s computing the normals of mesh \"%s\" of %s (%zu vertices)",
                         st == BG_ERR_LIMIT ? "more vertices than 32-bit indices reach" : "out of memory",
                         am->mName.data, md->desc->path, nv);
        goto done;
    }
    bg_mesh_desc d = bg_mesh_desc_init(material);
    d.positions = p;
    d.vertex_count = nv;
    d.indices = idx;
    d.triangle_count = nt;
    d.normals = n;
    d.uvs = uv;
    d.transform = m;
    d.casts_shadows = md->desc->casts_shadows;
    st = bg_scene_add_mesh(ctx->scene, &d, out);
    *out_vertices = nv;
    if (st != BG_OK) {
        char what[512];
        snprintf(what, sizeof what, "mesh \"%.200s\" of %.255s", am->mName.data, md->desc->path);
        st = bgi_sf_scene_fail(ctx, st, what);
    }
done:
    free(p);
    free(n);
    free(uv);
    free(idx);
    return st;
}

static bg_status add_mesh(model *md, unsigned index, bg_mat4 m)
{
    const struct aiMesh *am = md->sc->mMeshes[index];
    if (!(am->mPrimitiveTypes & aiPrimitiveType_TRIANGLE))
        return BG_OK; /* points and lines: nothing a ray tracer can hit */
    uint32_t material = md->desc->material;
    if (!material)
        BGI_SF_TRY(bgi_sf_model_material(md, am->mMaterialIndex, &material));
    uint32_t id;
    if (md->first[index]) {
        bg_status st = bg_scene_add_mesh_instance(md->ctx->scene, md->first[index], &m, material,
                                                  md->desc->casts_shadows, &id);
        if (st != BG_OK)
            return bgi_sf_scene_fail(md->ctx, st, "a mesh instance");
    } else {
        BGI_SF_TRY(add_new_mesh(md, am, material, m, &id, &md->first_vertices[index]));
        md->first[index] = id;
    }
    bg_scenefile_summary *s = &md->ctx->out->summary;
    s->objects++;
    s->meshes++;
    for (unsigned f = 0; f < am->mNumFaces; f++)
        s->triangles += am->mFaces[f].mNumIndices == 3;
    s->vertices += md->first_vertices[index];
    for (unsigned v = 0; v < am->mNumVertices; v++)
        bgi_sf_summary_point(s, m, am->mVertices[v].x, am->mVertices[v].y, am->mVertices[v].z);
    md->added++;
    return BG_OK;
}

static bg_status walk(model *md, const struct aiNode *node, bg_mat4 parent, int depth)
{
    if (depth > MODEL_MAX_DEPTH)
        return bgi_sf_fail(md->ctx, BG_ERR_LIMIT, "%s: the node tree is deeper than %d", md->desc->path, MODEL_MAX_DEPTH);
    bg_mat4 world = compose(parent, from_ai(&node->mTransformation));
    for (unsigned i = 0; i < node->mNumMeshes; i++)
        if (node->mMeshes[i] < md->sc->mNumMeshes)
            BGI_SF_TRY(add_mesh(md, node->mMeshes[i], world));
    for (unsigned i = 0; i < node->mNumChildren; i++)
        BGI_SF_TRY(walk(md, node->mChildren[i], world, depth + 1));
    return BG_OK;
}

/* The world transform of the node named name (cameras and lights are placed by theirs). */
static bool find_node(const struct aiNode *node, const char *name, bg_mat4 parent, bg_mat4 *out, int depth)
{
    if (depth > MODEL_MAX_DEPTH)
        return false;
    bg_mat4 world = compose(parent, from_ai(&node->mTransformation));
    if (strcmp(node->mName.data, name) == 0) {
        *out = world;
        return true;
    }
    for (unsigned i = 0; i < node->mNumChildren; i++)
        if (find_node(node->mChildren[i], name, world, out, depth + 1))
            return true;
    return false;
}

static bg_vec3 apply(bg_mat4 m, struct aiVector3D v, double w)
{
    double p[3];
    for (int r = 0; r < 3; r++)
        p[r] = m.m[r][0] * v.x + m.m[r][1] * v.y + m.m[r][2] * v.z + m.m[r][3] * w;
    return bg_vec3_make(p[0], p[1], p[2]);
}

static bg_mat4 node_world(model *md, const char *name)
{
    bg_mat4 m = md->desc->transform;
    if (!find_node(md->sc->mRootNode, name, md->desc->transform, &m, 0))
        m = md->desc->transform;
    return m;
}

static bool is_gltf(const char *path)
{
    size_t n = strlen(path);
    return (n >= 5 && strcasecmp(path + n - 5, ".gltf") == 0) || (n >= 4 && strcasecmp(path + n - 4, ".glb") == 0);
}

/* The file's camera number (from 1), placed by its node. Two quirks of assimp's glTF 2.0 reader are undone
 * here (docs/scene_format.md, "Model files"): before 5.3 it gives the camera's position already in
 * world space (the node's translation baked in), so the position is taken from the node alone; and
 * its mHorizontalFOV is not the half horizontal angle that other readers give, but a formula that
 * depends on the version (bgi_sf_gltf_fov_y). */
static void read_camera(model *md, int number)
{
    const struct aiCamera *c = md->sc->mCameras[number - 1];
    bg_mat4 m = node_world(md, c->mName.data);
    bg_scenefile_result *out = md->ctx->out;
    bool gltf = is_gltf(md->desc->path);
    struct aiVector3D origin = {0, 0, 0};
    bg_vec3 pos = apply(m, gltf ? origin : c->mPosition, 1.0);
    bg_vec3 dir = apply(m, c->mLookAt, 0.0);
    out->camera.position = pos;
    out->camera.look_at = bg_vec3_make(pos.x + dir.x, pos.y + dir.y, pos.z + dir.z);
    out->camera.up = apply(m, c->mUp, 0.0);
    bool has_aspect = c->mAspect > 0 && isfinite(c->mAspect);
    double aspect = has_aspect ? c->mAspect : (double)out->image.width / out->image.height;
    if (has_aspect) {
        double h = floor(out->image.width / aspect + 0.5);
        out->image.height = h < 1 ? 1 : h > BG_MAX_IMAGE_SIDE ? BG_MAX_IMAGE_SIDE : (int)h;
    }
    /* An orthographic camera (glTF's "orthographic": assimp hands xmag over as the half-width and
     * xmag / ymag as the aspect): its half-height follows, and the image takes its aspect above. */
    if (c->mOrthographicWidth > 0 && isfinite(c->mOrthographicWidth)) {
        out->camera.projection = BG_PROJECTION_ORTHOGRAPHIC;
        out->camera.half_height = c->mOrthographicWidth / aspect;
        out->camera_from_file = true;
        out->camera_number = number;
        return;
    }
    double fov = 0.0;
    if (c->mHorizontalFOV > 0 && isfinite(c->mHorizontalFOV))
        fov = gltf ? bgi_sf_gltf_fov_y(c->mHorizontalFOV, has_aspect ? aspect : 0.0, aiGetVersionMajor(),
                                       aiGetVersionMinor())
                   : 2.0 * atan(tan(c->mHorizontalFOV) / aspect);
    fov *= 180.0 / 3.14159265358979323846;
    if (fov > 0 && fov < 180)
        out->camera.fov_y_degrees = fov;
    out->camera_from_file = true;
    out->camera_number = number;
}

/* The camera desc->camera asks for: the first by default, none when framing is asked for, and an
 * error naming the field and the file's count when the file has fewer. */
static bg_status choose_camera(model *md)
{
    int count = md->sc->mNumCameras > INT32_MAX ? INT32_MAX : (int)md->sc->mNumCameras;
    md->ctx->out->file_cameras = count;
    int want = md->desc->camera;
    if (want == BG_SCENEFILE_CAMERA_FRAME || (want == 0 && count == 0))
        return BG_OK;
    if (want > count) {
        if (count == 0)
            return bgi_sf_fail(md->ctx, BG_ERR_INVALID_ARGUMENT, "desc->camera: camera %d asked for, but the file "
                               "has no camera (a framing camera is made without desc->camera)", want);
        return bgi_sf_fail(md->ctx, BG_ERR_INVALID_ARGUMENT, "desc->camera: camera %d asked for, but the file has "
                           "%d camera%s (1 .. %d)", want, count, count == 1 ? "" : "s", count);
    }
    read_camera(md, want == 0 ? 1 : want);
    return BG_OK;
}

static bg_status read_lights(model *md)
{
    for (unsigned i = 0; i < md->sc->mNumLights; i++) {
        const struct aiLight *al = md->sc->mLights[i];
        if (al->mType != aiLightSource_POINT && al->mType != aiLightSource_DIRECTIONAL &&
            al->mType != aiLightSource_SPOT) {
            bgi_sf_warn(md->ctx, "%s: light \"%s\" is left out (only point, spot and directional lights)",
                        md->desc->path, al->mName.data);
            continue;
        }
        bg_mat4 m = node_world(md, al->mName.data);
        bg_light l = bg_light_init();
        l.type = al->mType == aiLightSource_DIRECTIONAL ? BG_LIGHT_DIRECTIONAL : BG_LIGHT_POINT;
        l.position = apply(m, al->mPosition, 1.0);
        l.direction = apply(m, al->mDirection, 0.0);
        double c[3] = {al->mColorDiffuse.r, al->mColorDiffuse.g, al->mColorDiffuse.b};
        for (int k = 0; k < 3; k++)
            l.color[k] = isfinite(c[k]) && c[k] > 0 ? c[k] : 0.0;
        double a[3] = {al->mAttenuationConstant, al->mAttenuationLinear, al->mAttenuationQuadratic};
        if (al->mType != aiLightSource_DIRECTIONAL && isfinite(a[0] + a[1] + a[2]) && a[0] >= 0 && a[1] >= 0 &&
            a[2] >= 0 && a[0] + a[1] + a[2] > 0)
            memcpy(l.attenuation, a, sizeof a);
        if (al->mType == aiLightSource_SPOT) {
            double cut = al->mAngleOuterCone * 180.0 / 3.14159265358979323846;
            l.spot_cutoff_degrees = cut > 0 && cut <= 90 ? cut : 90;
        }
        uint32_t id;
        bg_status st = bg_scene_add_light(md->ctx->scene, &l, &id);
        if (st != BG_OK) {
            char what[512];
            snprintf(what, sizeof what, "light \"%.200s\" of %.255s", al->mName.data, md->desc->path);
            return bgi_sf_scene_fail(md->ctx, st, what);
        }
        md->ctx->out->summary.lights++;
        md->ctx->out->lights_from_file = true;
    }
    return BG_OK;
}

/* The file opened as a regular file and checked where assimp would trust it (a PLY), then read through the
 * same checked file access, with assimp's validation as the first step. It must run inside the
 * import: assimp 5.2's aiApplyPostProcessing releases a scene that fails validation twice. */
static const struct aiScene *import(bgi_sf_ctx *ctx, const char *path, bg_status *st)
{
    char what[BGI_SF_PATH_MAX + 32];
    snprintf(what, sizeof what, "model file \"%s\"", path);
    FILE *f = NULL;
    if ((*st = bgi_sf_open_input(ctx, path, what, &f)) != BG_OK)
        return NULL;
    *st = bgi_sf_check_ply(ctx, path, f);
    fclose(f);
    if (*st != BG_OK)
        return NULL;
    bgi_sf_model_io io;
    bgi_sf_model_io_init(&io, ctx);
    const struct aiScene *sc = aiImportFileEx(path, MODEL_FLAGS, &io.io);
    if (io.refused[0])
        *st = bgi_sf_fail(ctx, BG_ERR_IO, "%s: %s", what, io.refused);
    else if (!sc || !sc->mRootNode || (sc->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
        *st = bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "cannot read %s: %s", what,
                          sc ? "the file holds no complete scene" : aiGetErrorString());
    else
        return sc;
    aiReleaseImport(sc);
    return NULL;
}

bg_status bgi_sf_load_model(bgi_sf_ctx *ctx, const bgi_sf_model_desc *desc)
{
    bg_status st = BG_OK;
    const struct aiScene *sc = import(ctx, desc->path, &st);
    if (!sc)
        return st;
    model md;
    memset(&md, 0, sizeof md);
    md.ctx = ctx;
    md.desc = desc;
    md.sc = sc;
    const char *slash = strrchr(desc->path, '/');
    size_t dl = slash ? (size_t)(slash - desc->path) + 1 : 0;
    memcpy(md.dir, desc->path, dl);
    md.dir[dl] = '\0';
    md.materials = calloc(sc->mNumMaterials + 1, sizeof *md.materials);
    md.first = calloc(sc->mNumMeshes + 1, sizeof *md.first);
    md.first_vertices = calloc(sc->mNumMeshes + 1, sizeof *md.first_vertices);
    if (!md.materials || !md.first || !md.first_vertices)
        st = bgi_sf_fail(ctx, BG_ERR_OUT_OF_MEMORY, "out of memory reading \"%s\"", desc->path);
    if (st == BG_OK)
        st = walk(&md, sc->mRootNode, desc->transform, 0);
    if (st == BG_OK && md.added == 0)
        st = bgi_sf_fail(ctx, BG_ERR_INVALID_ARGUMENT, "model file \"%s\" holds no triangles", desc->path);
    if (st == BG_OK && desc->scene_items)
        st = choose_camera(&md);
    if (st == BG_OK && desc->scene_items)
        st = read_lights(&md);
    free(md.materials);
    free(md.first);
    free(md.first_vertices);
    bgi_sf_model_images_free(&md);
    aiReleaseImport(sc);
    return st;
}
