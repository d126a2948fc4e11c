/* BENCH_CASES: see bench_select.h. The variable is read once, at the first question, into a fixed
 * list: a benchmark asks about a few dozen cases at most, and a name longer than any case's is
 * nobody's. */
#include "bench_select.h"

#include <stdlib.h>
#include <string.h>

#define MAX_NAMES 32
#define MAX_NAME 64

static struct {
    bool read;
    int count;
    char names[MAX_NAMES][MAX_NAME];
    bool matched[MAX_NAMES];
    bool too_many; /* names past MAX_NAMES or longer than MAX_NAME: reported by bench_select_check */
} selection;

static void read_selection(void)
{
    if (selection.read)
        return;
    selection.read = true;
    const char *s = getenv("BENCH_CASES");
    while (s && *s) {
        size_t n = strcspn(s, ",");
        /* Spaces around a name are the shell's habit, not part of the name. */
        size_t start = 0, end = n;
        while (start < end && s[start] == ' ')
            start++;
        while (end > start && s[end - 1] == ' ')
            end--;
        if (end > start) {
            if (selection.count == MAX_NAMES || end - start >= MAX_NAME) {
                selection.too_many = true;
            } else {
                memcpy(selection.names[selection.count], s + start, end - start);
                selection.names[selection.count][end - start] = '\0';
                selection.count++;
            }
        }
        s += n;
        if (*s == ',')
            s++;
    }
}

bool bench_select_active(void)
{
    read_selection();
    return selection.count > 0 || selection.too_many;
}

bool bench_selected(const char *name, int size)
{
    read_selection();
    if (!bench_select_active())
        return true;
    char sized[MAX_NAME + 16];
    snprintf(sized, sizeof sized, "%s@%d", name, size);
    bool any = false;
    for (int i = 0; i < selection.count; i++)
        if (strcmp(selection.names[i], name) == 0 || (size > 0 && strcmp(selection.names[i], sized) == 0)) {
            selection.matched[i] = true;
            any = true;
        }
    return any;
}

bool bench_select_check(const char *program, const char *known)
{
    read_selection();
    bool ok = !selection.too_many;
    if (selection.too_many)
        fprintf(stderr, "%s: BENCH_CASES holds more than %d names or a name of %d characters or more\n", program,
                MAX_NAMES, MAX_NAME);
    for (int i = 0; i < selection.count; i++)
        if (!selection.matched[i]) {
            fprintf(stderr, "%s: BENCH_CASES: no case is named \"%s\"\n", program, selection.names[i]);
            ok = false;
        }
    if (!ok)
        fprintf(stderr, "%s: its cases (each also as name@size): %s\n", program, known);
    return ok;
}

void bench_select_print(FILE *f)
{
    read_selection();
    if (!bench_select_active())
        return;
    fprintf(f, "BENCH_CASES=");
    for (int i = 0; i < selection.count; i++)
        fprintf(f, "%s%s", i ? "," : "", selection.names[i]);
    fprintf(f, ": only these cases\n");
}
