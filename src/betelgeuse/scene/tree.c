/* The committed object tree. A commit that moves nothing (camera, lights, material values) keeps
 * the tree as it is; one that moves objects refits it, keeping its layout, so a renderer uploads
 * new boxes into the same texels; one that adds objects, or moves one into or out of the float
 * range, or removes one, rebuilds it. Refits keep the tree exact but may make it slower (overlapping boxes); a
 * later structural commit rebuilds it.
 *
 * Everything that can fail (growing the lists, building aside) happens in prepare, before commit
 * overwrites any committed value; install only swaps. */
#include <string.h>

#include "../common/alloc.h"
#include "scene_private.h"

enum { TREE_KEEP, TREE_REFIT, TREE_REBUILD };

static const char where_tree[] = "bg_scene_commit: object tree";

/* Grows both sides of each list, so that the swap at install leaves the next commit's side as
 * large as this one's: a commit of the same objects then allocates nothing. The committed
 * pointers follow storage that moved (realloc kept its contents). */
static bg_status reserve_lists(bg_scene *s, uint32_t n)
{
    bg_array *lists[3][2] = {{&s->p_boxes, &s->c_boxes},
                             {&s->p_tree_objects, &s->c_tree_objects},
                             {&s->p_always, &s->c_always}};
    const size_t elem[3] = {sizeof(bg_bvh_box), sizeof(uint32_t), sizeof(uint32_t)};
    for (int i = 0; i < 3; i++)
        for (int side = 0; side < 2; side++) {
            bg_status st = bgi_array_reserve(s, lists[i][side], n, elem[i], where_tree);
            if (st != BG_OK)
                return st;
        }
    s->state.tree_objects = s->c_tree_objects.data;
    s->state.always_objects = s->c_always.data;
    return BG_OK;
}

/* Sorts the objects the commit derived into the tree's (a box that fits floats) and the
 * always-tested, both by dense index. */
static void split_objects(bg_scene *s)
{
    const bg_object_data *objects = s->p_objects.data;
    bg_bvh_box *boxes = s->p_boxes.data;
    uint32_t *tree = s->p_tree_objects.data, *always = s->p_always.data;
    uint32_t nt = 0, na = 0;
    for (uint32_t i = 0; i < s->p_objects.count; i++) {
        bg_bvh_box b;
        memcpy(b.min, objects[i].bounds_min, sizeof b.min);
        memcpy(b.max, objects[i].bounds_max, sizeof b.max);
        if (objects[i].bounded && bgi_bvh_check_boxes(&b, 1, NULL) == BG_OK) {
            boxes[nt] = b;
            tree[nt++] = i;
        } else {
            always[na++] = i;
        }
    }
    s->p_boxes.count = s->p_tree_objects.count = nt;
    s->p_always.count = na;
}

static bool same_list(const bg_array *a, const bg_array *b, size_t elem)
{
    return a->count == b->count && (a->count == 0 || memcmp(a->data, b->data, a->count * elem) == 0);
}

bg_status bgi_scene_tree_prepare(bg_scene *s)
{
    bg_status st = reserve_lists(s, s->p_objects.count);
    if (st != BG_OK)
        return st;
    split_objects(s);
    bool same_members = s->committed && same_list(&s->p_tree_objects, &s->c_tree_objects, sizeof(uint32_t));
    if (same_members && same_list(&s->p_boxes, &s->c_boxes, sizeof(bg_bvh_box))) {
        s->tree_action = TREE_KEEP;
        return BG_OK;
    }
    if (same_members) {
        s->tree_action = TREE_REFIT;
        return BG_OK;
    }
    st = bgi_bvh_build(&s->allocator, s->p_boxes.data, s->p_boxes.count, &s->rebuilt);
    if (st == BG_ERR_OUT_OF_MEMORY)
        return bgi_scene_fail(s, st, "%s: out of memory building the tree of %u objects", where_tree,
                             s->p_boxes.count);
    if (st != BG_OK)
        return bgi_scene_fail(s, st, "%s: %s", where_tree, bg_status_string(st));
    s->tree_action = TREE_REBUILD;
    return BG_OK;
}

static void swap(bg_array *a, bg_array *b)
{
    bg_array t = *a;
    *a = *b;
    *b = t;
}

void bgi_scene_tree_install(bg_scene *s)
{
    swap(&s->c_boxes, &s->p_boxes);
    swap(&s->c_tree_objects, &s->p_tree_objects);
    swap(&s->c_always, &s->p_always);
    if (s->tree_action == TREE_REBUILD) {
        bgi_bvh_destroy(&s->tree);
        s->tree = s->rebuilt;
        memset(&s->rebuilt, 0, sizeof s->rebuilt);
        s->state.tree_builds++;
    } else if (s->tree_action == TREE_REFIT) {
        /* Same primitive count and boxes that passed bgi_bvh_check_boxes: refit cannot fail. */
        bgi_bvh_refit(&s->tree, s->c_boxes.data, s->c_boxes.count);
        s->state.tree_refits++;
    }
    s->state.tree = &s->tree;
    s->state.tree_objects = s->c_tree_objects.data;
    s->state.tree_count = s->c_tree_objects.count;
    s->state.always_objects = s->c_always.data;
    s->state.always_count = s->c_always.count;
}

void bgi_scene_tree_release(bg_scene *s)
{
    bgi_bvh_destroy(&s->tree);
    bgi_bvh_destroy(&s->rebuilt);
    bg_array *arrays[] = {&s->c_boxes, &s->p_boxes, &s->c_tree_objects, &s->p_tree_objects, &s->c_always,
                          &s->p_always};
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++)
        bgi_array_release(s, arrays[i]);
}
