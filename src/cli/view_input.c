/* Mouse and keys to viewer actions (view_input.h). */
#include "view_input.h"

#include <ctype.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

const char view_input_help[] = "  left drag              orbit about the point looked at\n"
                               "  right or middle drag   pan\n"
                               "  wheel                  dolly towards (up) or away from the point looked at (an orthographic\n"
                               "                         camera: narrow or widen the view)\n"
                               "  F                      frame the scene's bounds, looking the same way\n"
                               "  R                      reset to the camera the file gave\n"
                               "  P                      save the shown frame as betelgeuse-view-N.png (the\n"
                               "                         first N free, in the current folder)\n"
                               "  I                      switch between the Whitted and the path integrator\n"
                               "                         (docs/shading.md 13); the samples start again\n"
                               "  Esc, closing the window  quit (exit 0)\n";

void view_input_button(viewer *v, view_button b, bool pressed, double x, double y)
{
    view_pointer *p = &v->pointer;
    p->held[b] = pressed;
    p->x = x;
    p->y = y;
}

void view_input_move(viewer *v, double x, double y)
{
    view_pointer *p = &v->pointer;
    double dx = x - p->x, dy = y - p->y;
    p->x = x;
    p->y = y;
    if (dx == 0 && dy == 0)
        return;
    if (p->held[VIEW_BUTTON_LEFT])
        view_act(v, &(view_action){VIEW_ORBIT, dx, dy, NULL});
    else if (p->held[VIEW_BUTTON_RIGHT] || p->held[VIEW_BUTTON_MIDDLE])
        view_act(v, &(view_action){VIEW_PAN, dx, dy, NULL});
}

void view_input_scroll(viewer *v, double dy)
{
    if (dy != 0)
        view_act(v, &(view_action){VIEW_DOLLY, 0, dy, NULL});
}

/* The keys and their actions: the mapping and the script's check read this one table. */
static const struct {
    int key;
    view_action_kind kind;
} keys[] = {
    {VIEW_KEY_ESCAPE, VIEW_QUIT}, {'F', VIEW_FRAME}, {'R', VIEW_RESET}, {'P', VIEW_SCREENSHOT}, {'I', VIEW_INTEGRATOR},
};

static int key_row(int key)
{
    int k = key == VIEW_KEY_ESCAPE ? key : toupper(key);
    for (int i = 0; i < (int)(sizeof keys / sizeof keys[0]); i++)
        if (keys[i].key == k)
            return i;
    return -1;
}

bool view_input_has_key(int key)
{
    return key_row(key) >= 0;
}

bool view_input_key(viewer *v, int key)
{
    int row = key_row(key);
    if (row < 0)
        return false;
    view_act(v, &(view_action){keys[row].kind, 0, 0, NULL});
    return true;
}

/* ---- GLFW's callbacks, translated ---- */

static viewer *of(GLFWwindow *w)
{
    return glfwGetWindowUserPointer(w);
}

static void on_button(GLFWwindow *w, int button, int action, int mods)
{
    (void)mods;
    view_button b = button == GLFW_MOUSE_BUTTON_LEFT    ? VIEW_BUTTON_LEFT
                    : button == GLFW_MOUSE_BUTTON_RIGHT ? VIEW_BUTTON_RIGHT
                    : button == GLFW_MOUSE_BUTTON_MIDDLE ? VIEW_BUTTON_MIDDLE
                                                         : VIEW_BUTTON_COUNT_;
    if (b == VIEW_BUTTON_COUNT_)
        return;
    double x, y;
    glfwGetCursorPos(w, &x, &y);
    view_input_button(of(w), b, action == GLFW_PRESS, x, y);
}

static void on_move(GLFWwindow *w, double x, double y)
{
    view_input_move(of(w), x, y);
}

static void on_scroll(GLFWwindow *w, double dx, double dy)
{
    (void)dx;
    view_input_scroll(of(w), dy);
}

static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    (void)scancode;
    (void)mods;
    if (action != GLFW_PRESS)
        return;
    if (key == GLFW_KEY_ESCAPE)
        view_input_key(of(w), VIEW_KEY_ESCAPE);
    else if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z)
        view_input_key(of(w), 'A' + (key - GLFW_KEY_A));
}

static void on_close(GLFWwindow *w)
{
    view_act(of(w), &(view_action){VIEW_QUIT, 0, 0, NULL});
}

static void on_refresh(GLFWwindow *w)
{
    of(w)->redraw = true;
}

void view_input_attach(viewer *v)
{
    GLFWwindow *w = v->window;
    glfwSetWindowUserPointer(w, v);
    glfwSetMouseButtonCallback(w, on_button);
    glfwSetCursorPosCallback(w, on_move);
    glfwSetScrollCallback(w, on_scroll);
    glfwSetKeyCallback(w, on_key);
    glfwSetWindowCloseCallback(w, on_close);
    glfwSetWindowRefreshCallback(w, on_refresh);
}
