/* Slots with generation-counted handles (scene_private.h). Invariant: an id is accepted only while
 * its slot is live in that id's generation. A slot's generation only grows, and a slot retires
 * rather than wrap, so every id ever handed out for a slot stays distinct from its later ones and
 * is refused for good once its item is removed. */
#include <stdio.h>
#include <string.h>

#include "scene_private.h"

static uint32_t generation_of(uint32_t id)
{
    return id >> BG_HANDLE_SLOT_BITS;
}

void bgi_pool_init(bg_pool *pool, const char *kind, const char *a_kind, size_t elem)
{
    memset(pool, 0, sizeof *pool);
    pool->kind = kind;
    pool->a_kind = a_kind;
    pool->elem = elem;
}

void bgi_pool_release(bg_scene *scene, bg_pool *pool)
{
    bgi_array_release(scene, &pool->items);
    bgi_array_release(scene, &pool->slots);
    bgi_array_release(scene, &pool->free_slots);
    pool->live = 0;
}

bg_status bgi_pool_reserve(bg_scene *scene, bg_pool *pool, const char *where)
{
    if (pool->free_slots.count > 0)
        return BG_OK;
    uint32_t n = pool->items.count;
    if (n >= BG_MAX_SLOTS)
        return bgi_scene_fail(scene, BG_ERR_LIMIT,
                             "%s: every one of the %u %s slots a handle can name is used or retired", where,
                             BG_MAX_SLOTS, pool->kind);
    bg_status st = bgi_array_reserve(scene, &pool->items, n + 1, pool->elem, where);
    if (st == BG_OK)
        st = bgi_array_reserve(scene, &pool->slots, n + 1, sizeof(bg_slot), where);
    if (st == BG_OK)
        st = bgi_array_reserve(scene, &pool->free_slots, n + 1, sizeof(uint32_t), where);
    return st;
}

bg_status bgi_pool_add(bg_scene *scene, bg_pool *pool, const char *where, const void *item, uint32_t *out_id)
{
    bg_status st = bgi_pool_reserve(scene, pool, where);
    if (st != BG_OK)
        return st;
    uint32_t slot;
    bg_slot *slots = pool->slots.data;
    if (pool->free_slots.count > 0) {
        slot = ((uint32_t *)pool->free_slots.data)[--pool->free_slots.count];
    } else {
        slot = pool->items.count++;
        pool->slots.count++;
        slots[slot].generation = 0;
    }
    slots[slot].state = BG_SLOT_LIVE;
    memcpy(bgi_pool_item(pool, slot), item, pool->elem);
    pool->live++;
    *out_id = bgi_pool_id(pool, slot);
    return BG_OK;
}

const char *bgi_handle_text(uint32_t id, char text[BG_HANDLE_TEXT_SIZE])
{
    snprintf(text, BG_HANDLE_TEXT_SIZE, generation_of(id) ? "0x%08X" : "%u", (unsigned)id);
    return text;
}

bg_status bgi_pool_lookup(bg_scene *scene, const bg_pool *pool, const char *where, const char *field, uint32_t id,
                         uint32_t *out_slot)
{
    char text[BG_HANDLE_TEXT_SIZE];
    uint32_t slot = bgi_handle_slot(id), generation = generation_of(id);
    if (slot < pool->slots.count) {
        const bg_slot *s = &((const bg_slot *)pool->slots.data)[slot];
        if (generation == s->generation && s->state == BG_SLOT_LIVE) {
            *out_slot = slot;
            return BG_OK;
        }
        if (generation < s->generation || (generation == s->generation && s->state == BG_SLOT_RETIRED))
            return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: %s = %s was removed", where, field,
                                 bgi_handle_text(id, text));
    }
    return bgi_scene_fail(scene, BG_ERR_INVALID_ARGUMENT, "%s: %s = %s is not %s of this scene (%u in use)", where,
                         field, bgi_handle_text(id, text), pool->a_kind, pool->live);
}

void bgi_pool_remove(bg_pool *pool, uint32_t slot)
{
    bg_slot *s = &((bg_slot *)pool->slots.data)[slot];
    pool->live--;
    if (s->generation == BG_HANDLE_LAST_GENERATION) {
        s->state = BG_SLOT_RETIRED;
        return;
    }
    s->generation++;
    s->state = BG_SLOT_FREE;
    /* free_slots holds room for every slot (bgi_pool_reserve). */
    ((uint32_t *)pool->free_slots.data)[pool->free_slots.count++] = slot;
}

uint32_t bgi_pool_slot_count(const bg_pool *pool)
{
    return pool->items.count;
}

bool bgi_pool_live(const bg_pool *pool, uint32_t slot)
{
    return ((const bg_slot *)pool->slots.data)[slot].state == BG_SLOT_LIVE;
}

void *bgi_pool_item(const bg_pool *pool, uint32_t slot)
{
    return (char *)pool->items.data + (size_t)slot * pool->elem;
}

uint32_t bgi_pool_id(const bg_pool *pool, uint32_t slot)
{
    return (slot + 1u) | ((uint32_t)((const bg_slot *)pool->slots.data)[slot].generation << BG_HANDLE_SLOT_BITS);
}
