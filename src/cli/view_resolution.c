/* The resolution rule (view_resolution.h). */
#include "view_resolution.h"

int view_resolution_next(int divisor, double frame_ms, double target_ms)
{
    /* A frame at divisor d has 1/d^2 of the pixels: the full frame would take frame_ms d^2. */
    double full = frame_ms * divisor * divisor;
    for (int d = 1; d <= VIEW_MAX_DIVISOR; d++) {
        double estimate = full / ((double)d * d);
        double allowed = d < divisor ? 0.8 * target_ms : target_ms;
        if (estimate <= allowed)
            return d;
    }
    return VIEW_MAX_DIVISOR;
}

int view_resolution_side(int side, int divisor)
{
    return (side + divisor - 1) / divisor;
}
