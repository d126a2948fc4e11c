/* The viewer's mouse and keys, mapped to actions in one place (view_input.c). The window's GLFW
 * callbacks and the lines of a --script call the same functions, so that a script drives exactly
 * what a user's hand does. */
#ifndef CLI_VIEW_INPUT_H
#define CLI_VIEW_INPUT_H

#include <stdbool.h>

#include "view.h"

/* Keys by their letter ('F', 'R', 'P', 'I'), or these. */
enum { VIEW_KEY_ESCAPE = 27 };

/* A button pressed or released at (x, y) window pixels. */
void view_input_button(viewer *v, view_button b, bool pressed, double x, double y);
/* The pointer at (x, y): left drag orbits, right or middle drag pans. */
void view_input_move(viewer *v, double x, double y);
/* The wheel: dy notches, positive away from the user (towards the scene). */
void view_input_scroll(viewer *v, double dy);
/* A key pressed; false for a key that does nothing. */
bool view_input_key(viewer *v, int key);
/* Whether key (a letter in either case, or VIEW_KEY_ESCAPE) does something: the script's check. */
bool view_input_has_key(int key);

/* The lines of --help that list the controls (the same table the mapping reads). */
extern const char view_input_help[];

/* Connects the GLFW window's callbacks to the functions above (v lives as long as the window). */
void view_input_attach(viewer *v);

#endif
