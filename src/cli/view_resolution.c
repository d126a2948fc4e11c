/* The resolution rule (view_resolution.h). */
#include "view_resolution.h"

int view_resolution_next(view_resolution *r, int divisor, double frame_ms, double target_ms)
{
    r->measured[divisor] = frame_ms;
    int next = VIEW_MAX_DIVISOR;
    for (int d = 1; d <= VIEW_MAX_DIVISOR; d++) {
        /* A frame at divisor d has 1/d^2 of the pixels. */
        double estimate = r->measured[d] > 0.0 ? r->measured[d] : frame_ms * divisor * divisor / ((double)d * d);
        double allowed = d < divisor ? 0.8 * target_ms : target_ms;
        if (estimate <= allowed) {
            next = d;
            break;
        }
    }
    if (next != divisor || divisor == 1) {
        r->frames_since_probe = 0;
        return next;
    }
    if (++r->frames_since_probe < VIEW_PROBE_FRAMES)
        return next;
    r->frames_since_probe = 0;
    return divisor - 1;
}

int view_resolution_side(int side, int divisor)
{
    return (side + divisor - 1) / divisor;
}
