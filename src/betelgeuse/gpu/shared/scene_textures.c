/* The scene's textures on the GPU, one copy that every plan samples (r->scene_textures): uploaded
 * when what they hold changes, not on every commit, and not again when a frame switches plan.
 *
 * What they hold is keyed by a hash of every texture's size, sampling modes and texels. The scene
 * pointer and commit count cannot say it (a scene freed and another made can land at one address
 * with one count, and the allocator can hand a texel buffer back with other contents). A commit's
 * texels never change and its serial is unique in the process, so the hash is taken once per commit. */
#include <string.h>

#include "../../common/alloc.h"
#include "shared.h"

uint64_t bgi_gpu_hash_mix(uint64_t h, uint64_t v)
{
    /* splitmix64 finaliser over a running state: cheap and well spread. */
    uint64_t z = h ^ (v + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2));
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* The key of what the textures of a commit hold. */
static uint64_t textures_key(const bg_scene_state *state, bool table)
{
    uint64_t h = bgi_gpu_hash_mix(0x13198a2e03707344ull, state->texture_count);
    h = bgi_gpu_hash_mix(h, table);
    for (uint32_t i = 0; i < state->texture_count; i++) {
        const bg_texture_data *t = &state->textures[i];
        h = bgi_gpu_hash_mix(h, (uint64_t)t->width);
        h = bgi_gpu_hash_mix(h, (uint64_t)t->height);
        h = bgi_gpu_hash_mix(h, (uint64_t)t->wrap);
        h = bgi_gpu_hash_mix(h, (uint64_t)t->filter);
        h = bgi_gpu_hash_mix(h, (uint64_t)(t->bytes != NULL) | (uint64_t)t->srgb << 1);
        size_t n = bgi_texture_bytes(t);
        const unsigned char *p = t->texels ? (const unsigned char *)t->texels : t->bytes;
        for (size_t k = 0; k < n; k += 8) {
            uint64_t v = 0; /* an RGBA8 texture of an odd texel count ends in half a word */
            memcpy(&v, p + k, n - k < sizeof v ? n - k : sizeof v);
            h = bgi_gpu_hash_mix(h, v);
        }
    }
    return h;
}

void bgi_gpu_scene_textures_release(bg_renderer *r)
{
    gpu_scene_textures *t = &r->scene_textures;
    for (uint32_t i = 0; i < t->count; i++)
        macs_texture_destroy(t->texture[i]);
    bgi_free(&r->allocator, t->texture);
    t->texture = NULL;
    t->count = 0;
    macs_texture_destroy(t->srgb_table);
    t->srgb_table = NULL;
    t->bytes = 0;
    t->held = false;
    t->serial = 0;
    t->uploads++;
}

bg_status bgi_gpu_scene_textures_prepare(bg_renderer *r, const bg_scene_state *state)
{
    gpu_scene_textures *t = &r->scene_textures;
    if (t->serial != 0 && t->serial == state->serial)
        return BG_OK; /* the same commit: keyed, and held */
    bool table = bgi_gpu_srgb_table(r);
    uint64_t key = textures_key(state, table);
    if (t->held && t->key == key) {
        t->serial = state->serial;
        return BG_OK;
    }
    bgi_gpu_scene_textures_release(r);
    if (state->texture_count > 0) {
        t->texture = bgi_alloc(&r->allocator, state->texture_count * sizeof *t->texture);
        if (!t->texture)
            return bgi_gpu_fail(r, BG_ERR_OUT_OF_MEMORY, "out of memory for %u textures", state->texture_count);
        memset(t->texture, 0, state->texture_count * sizeof *t->texture);
        t->count = state->texture_count;
        bool decodes = false;
        for (uint32_t i = 0; i < state->texture_count; i++) {
            uint64_t bytes = 0;
            bg_status st = bgi_gpu_scene_texture_upload(r, &state->textures[i], table, &t->texture[i], &bytes);
            if (st != BG_OK)
                return st; /* not held: the next frame uploads them again */
            t->bytes += bytes;
            decodes |= bgi_gpu_texture_mode(&state->textures[i], table).srgb;
        }
        if (decodes) {
            bg_status st = bgi_gpu_srgb_table_upload(r, &t->srgb_table);
            if (st != BG_OK)
                return st;
            t->bytes += 256 * 16;
        }
    }
    t->key = key;
    t->held = true;
    t->serial = state->serial;
    return BG_OK;
}
