/* LeakSanitizer suppressions for every program built with make SANITIZE=1: tests, examples and
 * benchmarks all link examples/scenes, so the hook lives here once. LSan reads it at exit.
 *
 * The leaks are the Mesa-internal ones that tests/valgrind.supp documents: OSMesa's process-wide
 * state-tracker manager and its framebuffer list, which OSMesaDestroyContext does not free. LSan's
 * fast unwinder stops inside libOSMesa (built without frame pointers), so the entry points are not
 * always visible and the library name is the anchor: OSMesa never calls back into MACS or these
 * programs, so no allocation of ours has it on its stack. */
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void)
{
    return "leak:OSMesaCreateContextAttribs\n"
           "leak:OSMesaMakeCurrent\n"
           "leak:libOSMesa.so\n";
}
