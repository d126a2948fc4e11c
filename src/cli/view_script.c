/* The script's reader and runner (view_script.h). Every command is checked when the file is read, so
 * that a typo fails at once with its line, not minutes into a test; the runner then needs no checks. */
#include "view_script.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "numbers.h"
#include "view_input.h"

typedef enum step_kind {
    STEP_WAIT, STEP_DRAG, STEP_SCROLL, STEP_KEY, STEP_SCREENSHOT, STEP_WAIT_REST, STEP_WAIT_RELOAD,
    STEP_EXPECT_COMPILED, STEP_EXPECT_GL, STEP_EXPECT_ERROR, STEP_TOUCH, STEP_WRITE, STEP_QUIT
} step_kind;

/* One row per command: its name and how many words follow it (-1: the rest of the line is text). */
static const struct {
    const char *name;
    step_kind kind;
    int min_words, max_words;
    const char *usage;
} commands[] = {
    {"wait", STEP_WAIT, 1, 1, "wait MS"},
    {"drag", STEP_DRAG, 5, 6, "drag left|right|middle X0 Y0 X1 Y1 [STEPS]"},
    {"scroll", STEP_SCROLL, 1, 1, "scroll DY"},
    {"key", STEP_KEY, 1, 1, "key F|R|P|I|ESC"},
    {"screenshot", STEP_SCREENSHOT, 1, 1, "screenshot PATH"},
    {"wait-rest", STEP_WAIT_REST, 0, 0, "wait-rest"},
    {"wait-reload", STEP_WAIT_RELOAD, 0, 0, "wait-reload"},
    {"expect-compiled", STEP_EXPECT_COMPILED, 1, 1, "expect-compiled N|any"},
    {"expect-gl", STEP_EXPECT_GL, 1, 1, "expect-gl VERSION"},
    {"expect-error", STEP_EXPECT_ERROR, 1, -1, "expect-error TEXT|none"},
    {"touch", STEP_TOUCH, 1, 1, "touch FILE"},
    {"write", STEP_WRITE, 2, -1, "write FILE TEXT"},
    {"quit", STEP_QUIT, 0, 0, "quit"},
};

typedef struct step {
    step_kind kind;
    int line;
    double n[5];  /* wait's ms; drag's x0 y0 x1 y1; scroll's dy; expect-compiled's count */
    int count;    /* drag's steps, key's key, drag's button */
    int button;
    char *word;   /* a path, a version, or expect-error's text */
    char *text;   /* write's text */
} step;

struct view_script {
    char name[512];
    step *steps;
    int count;
    int next;            /* the step running or due */
    double started;      /* when it started (0: not yet) */
    int done_steps;      /* a drag's steps so far */
    int reloads_seen;    /* reloads when a wait-reload started */
};

static bool bad(char *why, size_t size, const char *name, int line, const char *format, const char *a, const char *b)
{
    int n = snprintf(why, size, "%s:%d: ", name, line);
    if (n >= 0 && (size_t)n < size)
        snprintf(why + n, size - (size_t)n, format, a, b);
    return false;
}

/* The words of one line into step s; false with the reason. */
static bool parse_line(char *line, int number, const char *name, step *s, char *why, size_t size)
{
    char *words[8];
    int count = 0;
    char *rest = NULL; /* the text of write and expect-error: the rest of the line, spaces kept */
    int text_at = -1;  /* the word where that text starts */
    char *p = line;
    while (count < 8) {
        while (*p == ' ' || *p == '\t')
            p++;
        if (!*p)
            break;
        if (count == text_at) {
            rest = p;
            words[count++] = p;
            break;
        }
        words[count++] = p;
        while (*p && *p != ' ' && *p != '\t')
            p++;
        if (*p)
            *p++ = '\0';
        if (count == 1)
            text_at = strcmp(words[0], "write") == 0 ? 2 : strcmp(words[0], "expect-error") == 0 ? 1 : -1;
    }
    int k = 0, n = (int)(sizeof commands / sizeof commands[0]);
    while (k < n && strcmp(words[0], commands[k].name) != 0)
        k++;
    if (k == n)
        return bad(why, size, name, number, "unknown command '%s'%s (wait, drag, scroll, key, screenshot, wait-rest, "
                   "wait-reload, expect-compiled, expect-gl, expect-error, touch, write, quit)", words[0], "");
    int args = count - 1;
    bool text = commands[k].max_words < 0;
    if (args < commands[k].min_words || (!text && args > commands[k].max_words))
        return bad(why, size, name, number, "%s: wants '%s'", words[0], commands[k].usage);
    s->kind = commands[k].kind;
    s->line = number;
    switch (s->kind) {
    case STEP_WAIT:
    case STEP_SCROLL:
    case STEP_EXPECT_COMPILED:
        /* expect-compiled any: only starts the count afresh. */
        if (s->kind == STEP_EXPECT_COMPILED && strcmp(words[1], "any") == 0) {
            s->n[0] = -1;
            break;
        }
        if (!cli_parse_doubles(words[1], '\0', 1, &s->n[0]) ||
            (s->kind != STEP_SCROLL && !(s->n[0] >= 0 && s->n[0] <= 1e7)))
            return bad(why, size, name, number, "%s: '%s' is not a number for it", words[0], words[1]);
        break;
    case STEP_DRAG:
        s->button = strcmp(words[1], "left") == 0    ? VIEW_BUTTON_LEFT
                    : strcmp(words[1], "right") == 0 ? VIEW_BUTTON_RIGHT
                    : strcmp(words[1], "middle") == 0 ? VIEW_BUTTON_MIDDLE
                                                      : -1;
        if (s->button < 0)
            return bad(why, size, name, number, "drag: '%s' is not left, right or middle%s", words[1], "");
        for (int i = 0; i < 4; i++)
            if (!cli_parse_doubles(words[2 + i], '\0', 1, &s->n[i]))
                return bad(why, size, name, number, "drag: '%s' is not a pixel position%s", words[2 + i], "");
        s->count = 10;
        if (args == 6 && !cli_parse_ints(words[6], '\0', 1, 1, 10000, &s->count))
            return bad(why, size, name, number, "drag: '%s' is not a number of steps, 1 .. 10000%s", words[6], "");
        break;
    case STEP_KEY:
        if (strcmp(words[1], "ESC") == 0 || strcmp(words[1], "Esc") == 0 || strcmp(words[1], "esc") == 0)
            s->count = VIEW_KEY_ESCAPE;
        else if (strlen(words[1]) == 1 && view_input_has_key((unsigned char)words[1][0]))
            s->count = words[1][0];
        else
            return bad(why, size, name, number, "key: '%s' is not F, R, P, I or ESC%s", words[1], "");
        break;
    case STEP_EXPECT_ERROR:
        s->word = strdup(rest ? rest : "");
        if (!s->word)
            return bad(why, size, name, number, "out of memory%s%s", "", "");
        break;
    case STEP_WRITE:
    case STEP_SCREENSHOT:
    case STEP_TOUCH:
    case STEP_EXPECT_GL:
        /* write's text is the rest of the line as written, spaces included. */
        s->word = strdup(words[1]);
        if (s->kind == STEP_WRITE)
            s->text = strdup(rest ? rest : "");
        if (!s->word || (s->kind == STEP_WRITE && !s->text))
            return bad(why, size, name, number, "out of memory%s%s", "", "");
        break;
    default:
        break;
    }
    return true;
}

bool view_script_load(const char *path, const char *text, view_script **out, char *why, size_t size)
{
    *out = NULL;
    char *owned = NULL;
    if (!text) {
        FILE *f = fopen(path, "rb");
        if (!f) {
            snprintf(why, size, "--script %s: %s", path, strerror(errno));
            return false;
        }
        size_t cap = 4096, len = 0;
        owned = malloc(cap);
        size_t got;
        while (owned && (got = fread(owned + len, 1, cap - len - 1, f)) > 0) {
            len += got;
            if (len + 1 == cap) {
                char *bigger = cap < ((size_t)1 << 24) ? realloc(owned, cap * 2) : NULL;
                if (!bigger) {
                    free(owned);
                    owned = NULL;
                    break;
                }
                owned = bigger;
                cap *= 2;
            }
        }
        fclose(f);
        if (!owned) {
            snprintf(why, size, "--script %s: out of memory, or larger than 16 MiB", path);
            return false;
        }
        owned[len] = '\0';
        text = owned;
    }
    view_script *s = calloc(1, sizeof *s);
    char *copy = strdup(text);
    free(owned);
    if (!s || !copy) {
        free(s);
        free(copy);
        snprintf(why, size, "--script: out of memory");
        return false;
    }
    snprintf(s->name, sizeof s->name, "%s", path);
    bool ok = true;
    int number = 0;
    for (char *line = copy; ok && line;) {
        char *end = strchr(line, '\n');
        if (end)
            *end = '\0';
        number++;
        char *hash = strchr(line, '#');
        if (hash)
            *hash = '\0';
        size_t n = strlen(line);
        while (n > 0 && (line[n - 1] == ' ' || line[n - 1] == '\t' || line[n - 1] == '\r'))
            line[--n] = '\0';
        if (strspn(line, " \t") < n) {
            step *grown = realloc(s->steps, (size_t)(s->count + 1) * sizeof *grown);
            if (!grown) {
                ok = bad(why, size, s->name, number, "out of memory%s%s", "", "");
                break;
            }
            s->steps = grown;
            memset(&s->steps[s->count], 0, sizeof s->steps[0]);
            ok = parse_line(line, number, s->name, &s->steps[s->count], why, size);
            s->count++;
        }
        line = end ? end + 1 : NULL;
    }
    free(copy);
    if (!ok) {
        view_script_free(s);
        return false;
    }
    *out = s;
    return true;
}

/* A failed expectation: said with its line, and the run's exit code becomes 1. */
static void expectation_failed(view_script *s, viewer *v, const step *st, const char *what)
{
    fprintf(stderr, "betelgeuse view: %s:%d: %s\n", s->name, st->line, what);
    v->exit_code = 1;
}

/* touch and write: the script edits the scene as a user's editor would. */
static void edit_file(view_script *s, viewer *v, const step *st)
{
    bool ok;
    if (st->kind == STEP_TOUCH) {
        FILE *f = NULL;
        ok = utimensat(AT_FDCWD, st->word, NULL, 0) == 0 || (errno == ENOENT && (f = fopen(st->word, "ab")) && fclose(f) == 0);
    } else {
        FILE *f = fopen(st->word, "wb");
        ok = f && fputs(st->text, f) >= 0 && fputc('\n', f) != EOF;
        ok = (f && fclose(f) == 0) && ok;
    }
    v->check_files = true;
    if (!ok) {
        char what[1200];
        snprintf(what, sizeof what, "%s %s: %s", st->kind == STEP_TOUCH ? "touch" : "write", st->word, strerror(errno));
        expectation_failed(s, v, st, what);
    }
}

/* Runs step st; false while it is not finished (a wait, a drag's next steps). */
static bool run_step(view_script *s, viewer *v, step *st, double now, double *wait)
{
    char what[1400];
    switch (st->kind) {
    case STEP_WAIT: {
        double left = s->started + st->n[0] / 1000.0 - now;
        if (left > 0) {
            *wait = left;
            return false;
        }
        return true;
    }
    case STEP_DRAG: {
        /* One pointer move a frame, so that the drag is seen as a user's is: a moving frame each. */
        view_button b = (view_button)st->button;
        if (s->done_steps == 0)
            view_input_button(v, b, true, st->n[0], st->n[1]);
        s->done_steps++;
        double t = (double)s->done_steps / st->count;
        view_input_move(v, st->n[0] + t * (st->n[2] - st->n[0]), st->n[1] + t * (st->n[3] - st->n[1]));
        if (s->done_steps < st->count) {
            *wait = 0;
            return false;
        }
        view_input_button(v, b, false, st->n[2], st->n[3]);
        return true;
    }
    case STEP_SCROLL:
        view_input_scroll(v, st->n[0]);
        return true;
    case STEP_KEY:
        view_input_key(v, st->count);
        return true;
    case STEP_SCREENSHOT:
        view_act(v, &(view_action){VIEW_SCREENSHOT, 0, 0, st->word});
        return true;
    case STEP_WAIT_REST:
        if (!view_at_rest_done(v, now)) {
            *wait = -1;
            return false;
        }
        return true;
    case STEP_WAIT_RELOAD:
        if (v->reloads + v->reload_errors == s->reloads_seen) {
            *wait = -1;
            return false;
        }
        return true;
    case STEP_EXPECT_COMPILED: {
        uint64_t now_compiled = macs_context_programs_compiled(v->frames.context);
        uint64_t compiled = now_compiled - v->compiled_mark;
        v->compiled_mark = now_compiled;
        if (st->n[0] >= 0 && (double)compiled != st->n[0]) {
            snprintf(what, sizeof what, "expect-compiled %g: %llu programs were compiled", st->n[0],
                     (unsigned long long)compiled);
            expectation_failed(s, v, st, what);
        }
        return true;
    }
    case STEP_EXPECT_GL: {
        macs_gl_info info;
        macs_context_get_gl_info(v->frames.context, &info);
        const char *version = info.version ? info.version : "";
        if (strncmp(version, st->word, strlen(st->word)) != 0) {
            snprintf(what, sizeof what, "expect-gl %s: the context is OpenGL %s", st->word, version);
            expectation_failed(s, v, st, what);
        }
        return true;
    }
    case STEP_EXPECT_ERROR: {
        bool none = strcmp(st->word, "none") == 0;
        if (none ? v->error[0] != '\0' : strstr(v->error, st->word) == NULL) {
            snprintf(what, sizeof what, "expect-error %s: the error is '%s'", st->word, v->error);
            expectation_failed(s, v, st, what);
        }
        return true;
    }
    case STEP_TOUCH:
    case STEP_WRITE:
        edit_file(s, v, st);
        return true;
    case STEP_QUIT:
        view_act(v, &(view_action){VIEW_QUIT, 0, 0, NULL});
        return true;
    }
    return true;
}

double view_script_run(view_script *s, viewer *v, double now)
{
    double wait = 0;
    while (s->next < s->count && !v->quit) {
        step *st = &s->steps[s->next];
        if (s->started == 0) {
            s->started = now;
            s->done_steps = 0;
            s->reloads_seen = v->reloads + v->reload_errors;
        }
        wait = 0;
        if (!run_step(s, v, st, now, &wait))
            return wait;
        s->next++;
        s->started = 0;
        /* A command that changed the view lets the next frame show it before the next command. */
        if (st->kind == STEP_SCROLL || st->kind == STEP_KEY || st->kind == STEP_SCREENSHOT)
            return 0;
    }
    return 0;
}

bool view_script_done(const view_script *s)
{
    return s->next >= s->count;
}

void view_script_free(view_script *s)
{
    if (!s)
        return;
    for (int i = 0; i < s->count; i++) {
        free(s->steps[i].word);
        free(s->steps[i].text);
    }
    free(s->steps);
    free(s);
}
