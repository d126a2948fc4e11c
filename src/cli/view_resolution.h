/* The viewer's resolution rule while the camera moves (view_resolution.c): each side is divided by
 * 1, 2, 3 or 4, chosen after every moving frame so that the next one holds the frame-time target. */
#ifndef CLI_VIEW_RESOLUTION_H
#define CLI_VIEW_RESOLUTION_H

enum { VIEW_MAX_DIVISOR = 4 };

/* The divisor for the next moving frame, given the last one's divisor and its time. A frame's cost is
 * taken as proportional to its pixels (the full frame would take time x divisor^2): the finest divisor
 * whose estimate is within the target, and a finer one only when its estimate is within 80% of it,
 * so that noise in the times does not flip the resolution every frame. */
int view_resolution_next(int divisor, double frame_ms, double target_ms);

/* A side divided by the divisor, rounded up so that no side becomes 0. */
int view_resolution_side(int side, int divisor);

#endif
