/* The viewer's resolution rule while the camera moves (view_resolution.c): each side is divided by
 * 1, 2, 3 or 4, chosen after every moving frame so that the next one holds the frame-time target. */
#ifndef CLI_VIEW_RESOLUTION_H
#define CLI_VIEW_RESOLUTION_H

enum { VIEW_MAX_DIVISOR = 4, VIEW_PROBE_FRAMES = 15 };

/* What the rule has seen: the last frame time at each divisor (0: none yet). Zero is the start. */
typedef struct view_resolution {
    double measured[VIEW_MAX_DIVISOR + 1];
    int frames_since_probe;
} view_resolution;

/* Records a frame of frame_ms at divisor and returns the divisor of the next moving frame: the finest
 * whose time is within the target, a finer one only within 80% of it, so that noise does not flip
 * the resolution every frame. A divisor's time is its last measured one; one never measured is the
 * measured frame's scaled by its pixels (the full frame would take time x divisor^2). A frame has a
 * cost that does not scale with its pixels (showing it, the passes' set-up), so that rule overstates
 * a finer frame from a coarse one: after VIEW_PROBE_FRAMES frames at one divisor above 1, the next is
 * one step finer, to measure it instead. */
int view_resolution_next(view_resolution *r, int divisor, double frame_ms, double target_ms);
/* A side divided by the divisor, rounded up so that no side becomes 0. */
int view_resolution_side(int side, int divisor);

#endif
