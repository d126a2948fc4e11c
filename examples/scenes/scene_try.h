/* TRY(call): return the call's bg_status from the enclosing builder unless it is BG_OK. Private to
 * the scene builders of examples/scenes (scenes.c, stress_cases.c), which chain dozens of calls. */
#ifndef SCENE_TRY_H
#define SCENE_TRY_H

#define TRY(call)                   \
    do {                            \
        bg_status st_ = (call);     \
        if (st_ != BG_OK)           \
            return st_;             \
    } while (0)

#endif
