# Betelgeuse and MACS: GPU ray tracing through OpenGL 2.1.
# Targets: all (libraries and the betelgeuse command), check, check-profile, check-profiles, check-symbols, check-examples, check-command, check-view,
# check-fuzz-corpus, check-runner, check-cluster, check-zink, examples, bench, stress, install, uninstall, clean; fuzz-build and
# fuzz (libFuzzer with clang: docs/fuzzing.md); device-pack (the device check for a GPU machine: docs/device_check.md).
# SANITIZE=1 builds everything with AddressSanitizer and UndefinedBehaviorSanitizer into build/san.

VERSION   := 0.1.0
SOVERSION := 0
PREFIX    ?= /usr/local
DESTDIR   ?=
LIBDIR    ?= $(PREFIX)/lib
INCDIR    ?= $(PREFIX)/include

CC      ?= cc
WARN    := -std=c99 -Wall -Wextra -Wpedantic -Werror
DEFS    := -D_POSIX_C_SOURCE=200809L
OPT     ?= -O2 -g
CFLAGS  ?=
LDFLAGS ?=

# BUILD may be set to keep several builds apart (default build/release, or build/san).
ifeq ($(SANITIZE),1)
BUILD   ?= build/san
SANFLAGS := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all
else
BUILD   ?= build/release
SANFLAGS :=
endif

ALL_CFLAGS := $(WARN) $(DEFS) $(OPT) $(SANFLAGS) -fPIC -Iinclude -Isrc -Iexamples -I$(BUILD)/gen $(CFLAGS)
ALL_LDFLAGS := $(SANFLAGS) $(LDFLAGS)
# Every compile also writes the headers it read to $@.d (-MMD; -MP adds an empty rule per header, so
# that a header removed later does not stop the build), and the .d files of earlier builds are read
# below: an edit to any header an object or program includes rebuilds it, and only it. A build made
# before this had no .d files: `make clean` once.
DEPFLAGS = -MMD -MP -MT $@ -MF $@.d

MACS_LIBS := -ldl -lm
BG_LIBS   := $(shell pkg-config --libs libpng 2>/dev/null || echo -lpng16) -lpthread -lm
# Every test program's cmocka_run_group_tests() goes through tests/util_suite.c first (--wrap): the
# runner's hooks (line-buffered output, BG_TEST_LIST, CMOCKA_TEST_FILTER on cmocka 1.1) in one place.
TEST_LIBS := $(shell pkg-config --libs cmocka 2>/dev/null || echo -lcmocka) -Wl,--wrap=_cmocka_run_group_tests

# Shaders: glsl110/macs_* belong to MACS, every other file to Betelgeuse.
MACS_SHADERS := $(sort $(wildcard glsl110/macs_*))
BG_SHADERS   := $(sort $(filter-out $(MACS_SHADERS),$(wildcard glsl110/*)))

MACS_SRC := $(sort $(wildcard src/macs/*.c))
# Betelgeuse has one folder per part (docs/architecture.md): common, scene, cpu, gpu, io; gpu/ has
# rooms of its own (gpu/shared, gpu/fused, gpu/multipass).
BG_SRC   := $(sort $(wildcard src/betelgeuse/*/*.c src/betelgeuse/*/*/*.c))
# ar keeps members by file name, so two sources with one name would silently drop one object.
BG_DUP_NAMES := $(shell printf '%s\n' $(notdir $(BG_SRC)) | sort | uniq -d)
$(if $(BG_DUP_NAMES),$(error src/betelgeuse: file names used twice: $(BG_DUP_NAMES)))
# The scene-file library (include/betelgeuse_scenefile.h): JSON scenes and model files, on top of
# libbetelgeuse's public API, with cJSON and assimp as its own dependencies, and libpng and
# libjpeg-turbo's TurboJPEG for the images of model files (src/scenefile/image_decode.c).
SF_SRC   := $(sort $(wildcard src/scenefile/*.c))
MACS_OBJ := $(MACS_SRC:%.c=$(BUILD)/%.o) $(BUILD)/gen/macs_shaders.o
BG_OBJ   := $(BG_SRC:%.c=$(BUILD)/%.o) $(BUILD)/gen/bg_shaders.o
SF_OBJ   := $(SF_SRC:%.c=$(BUILD)/%.o)
SF_CFLAGS := $(shell pkg-config --cflags libcjson assimp libpng libturbojpeg stb 2>/dev/null || \
               echo -I/usr/include/cjson -I/usr/include/stb)
# stb_image is compiled in from its header (src/scenefile/hdr_decode.c), never linked as libstb.
SF_LIBS   := $(shell pkg-config --libs libcjson assimp libpng libturbojpeg 2>/dev/null || \
               echo -lcjson -lassimp -lpng16 -lturbojpeg)
# The command (src/cli, docs/command.md) on the three libraries.
CLI_SRC  := $(sort $(wildcard src/cli/*.c))
CLI_OBJ  := $(CLI_SRC:%.c=$(BUILD)/%.o)
CLI_BIN  := $(BUILD)/betelgeuse
# `betelgeuse view` (src/cli/view*.c) opens its window with GLFW 3.3 (docs/command.md says why); only
# the command links it, never the libraries (tests/check_symbols.sh, the .pc files).
GLFW_CFLAGS := $(shell pkg-config --cflags glfw3 2>/dev/null)
GLFW_LIBS   := $(shell pkg-config --libs glfw3 2>/dev/null || echo -lglfw)
VIEW_OBJ := $(filter $(BUILD)/src/cli/view%,$(CLI_OBJ))
BINDIR   ?= $(PREFIX)/bin

# Test helpers are tests/util_*.c; every tests/test_*.c is one cmocka suite.
TEST_UTIL_SRC := $(sort $(wildcard tests/util_*.c))
TEST_UTIL_OBJ := $(TEST_UTIL_SRC:%.c=$(BUILD)/%.o)
TEST_SRC := $(sort $(wildcard tests/test_*.c))
TEST_BIN := $(TEST_SRC:tests/%.c=$(BUILD)/tests/%)

# Shared scene builders used by tests, examples and benchmarks.
SCENES_SRC := $(sort $(wildcard examples/scenes/*.c))
SCENES_OBJ := $(SCENES_SRC:%.c=$(BUILD)/%.o)

EXAMPLE_SRC := $(sort $(wildcard examples/*.c))
EXAMPLE_BIN := $(EXAMPLE_SRC:examples/%.c=$(BUILD)/examples/%)

# Every bench/*.c is one program; bench/lib/*.c is code they share (timing, CSV, POV-Ray export, the
# BENCH_CASES selection), and
# they also link the counting allocator of the tests (tests/util_alloc.c).
# The Embree peer (bench/lib/embree_*.c) is built only where Embree 4 or 3 is installed, 4 first:
# pkg-config embree4 or embree3, else the headers under /usr/include (Debian's libembree-dev: Embree 3
# in Debian 12, without a pkg-config file, Embree 4 in testing). EMBREE_VERSION (4, 3, or empty for
# none) reaches the code as BENCH_EMBREE_VERSION, which picks the header (bench/lib/embree_internal.h);
# pkg-config's -I become -isystem, as Embree 4's headers are not -Wpedantic clean (an enumerator past
# INT_MAX). bench_embree needs the peer, bench_mesh links it (with BENCH_EMBREE defined) where it is
# and runs without its column elsewhere.
EMBREE_VERSION := $(shell if pkg-config --exists embree4 2>/dev/null; then echo 4; \
                    elif pkg-config --exists embree3 2>/dev/null; then echo 3; \
                    elif test -f /usr/include/embree4/rtcore.h; then echo 4; \
                    elif test -f /usr/include/embree3/rtcore.h; then echo 3; fi)
EMBREE_LIBS := $(if $(EMBREE_VERSION),$(shell pkg-config --libs embree$(EMBREE_VERSION) 2>/dev/null || \
                 echo -lembree$(EMBREE_VERSION)))
EMBREE_CFLAGS := $(if $(EMBREE_VERSION),-DBENCH_EMBREE_VERSION=$(EMBREE_VERSION) \
                   $(patsubst -I%,-isystem %,$(shell pkg-config --cflags embree$(EMBREE_VERSION) 2>/dev/null)))
EMBREE_PEER_SRC := $(sort $(wildcard bench/lib/embree_*.c))
EMBREE_PEER_OBJ := $(EMBREE_PEER_SRC:%.c=$(BUILD)/%.o)
EMBREE_SRC := bench/bench_embree.c $(EMBREE_PEER_SRC)
BENCH_SRC := $(sort $(filter-out $(EMBREE_SRC),$(wildcard bench/*.c)) $(if $(EMBREE_LIBS),bench/bench_embree.c))
BENCH_BIN := $(BENCH_SRC:bench/%.c=$(BUILD)/bench/%)
BENCH_LIB_SRC := $(sort $(filter-out $(EMBREE_SRC),$(wildcard bench/lib/*.c)))
BENCH_LIB_OBJ := $(BENCH_LIB_SRC:%.c=$(BUILD)/%.o) $(BUILD)/tests/util_alloc.o
EMBREE_BENCH_BIN := $(if $(EMBREE_LIBS),$(BUILD)/bench/bench_embree $(BUILD)/bench/bench_mesh)

MACS_A  := $(BUILD)/libmacs.a
BG_A    := $(BUILD)/libbetelgeuse.a
MACS_SO := $(BUILD)/libmacs.so.$(VERSION)
BG_SO   := $(BUILD)/libbetelgeuse.so.$(VERSION)
SF_A    := $(BUILD)/libbetelgeuse_scenefile.a
SF_SO   := $(BUILD)/libbetelgeuse_scenefile.so.$(VERSION)

STATIC_LINK := $(BG_A) $(MACS_A) $(BG_LIBS) $(MACS_LIBS)

# The libraries export exactly the functions their headers mark (MACS_API, BG_API); every other
# symbol is hidden from the shared libraries and carries the prefix macsi_ or bgi_ (bgi_sf_ in the
# scene-file library) in the archives
# (tests/check_symbols.sh holds both to it).
$(MACS_OBJ) $(BG_OBJ) $(SF_OBJ): ALL_CFLAGS += -fvisibility=hidden
$(SF_OBJ): ALL_CFLAGS += $(SF_CFLAGS)

.DEFAULT_GOAL := all
FORCE:
.PHONY: FORCE all check check-profile check-profiles check-zink check-runner device-pack check-symbols check-examples check-command check-view check-cluster check-no-osmesa test-programs examples bench bench-programs stress install uninstall clean glsl-check valgrind check-fuzz-corpus fuzz fuzz-build
# Keep generated sources and objects: they are intermediate files of pattern chains.
.SECONDARY:
all: $(MACS_A) $(BG_A) $(SF_A) $(MACS_SO) $(BG_SO) $(SF_SO) $(BUILD)/macs.pc $(BUILD)/betelgeuse.pc \
  $(BUILD)/betelgeuse_scenefile.pc $(CLI_BIN)

$(BUILD)/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(DEPFLAGS) -c $< -o $@

# Each shader becomes a C string in a table {name, source}; the library looks shaders up by file name.
$(BUILD)/gen/%_shaders.c: Makefile $(wildcard glsl110/*)
	@mkdir -p $(dir $@)
	@{ echo '/* Generated from glsl110/ by the Makefile: do not edit. */'; \
	   echo '#include <stddef.h>'; \
	   echo 'const char *const $*i_shader_table[][2] = {'; \
	   for f in $(if $(filter macs,$*),$(MACS_SHADERS),$(BG_SHADERS)); do \
	     printf '  {"%s",\n' "$$(basename $$f)"; \
	     sed -e 's/\\/\\\\/g' -e 's/"/\\"/g' -e 's/^/   "/' -e 's/$$/\\n"/' $$f; \
	     echo '  },'; \
	   done; \
	   echo '  {NULL, NULL}'; echo '};'; } > $@

$(BUILD)/gen/%_shaders.o: $(BUILD)/gen/%_shaders.c
	$(CC) $(ALL_CFLAGS) $(DEPFLAGS) -Wno-overlength-strings -c $< -o $@

$(MACS_A): $(MACS_OBJ)
	@rm -f $@
	ar rcs $@ $^
$(BG_A): $(BG_OBJ)
	@rm -f $@
	ar rcs $@ $^
$(SF_A): $(SF_OBJ)
	@rm -f $@
	ar rcs $@ $^
$(MACS_SO): $(MACS_OBJ)
	$(CC) -shared -Wl,-soname,libmacs.so.$(SOVERSION) $(ALL_LDFLAGS) -o $@ $^ $(MACS_LIBS)
	ln -sf libmacs.so.$(VERSION) $(BUILD)/libmacs.so.$(SOVERSION)
	ln -sf libmacs.so.$(SOVERSION) $(BUILD)/libmacs.so
$(BG_SO): $(BG_OBJ) $(MACS_SO)
	$(CC) -shared -Wl,-soname,libbetelgeuse.so.$(SOVERSION) $(ALL_LDFLAGS) -o $@ $(BG_OBJ) -L$(BUILD) -lmacs $(BG_LIBS)
	ln -sf libbetelgeuse.so.$(VERSION) $(BUILD)/libbetelgeuse.so.$(SOVERSION)
	ln -sf libbetelgeuse.so.$(SOVERSION) $(BUILD)/libbetelgeuse.so
$(SF_SO): $(SF_OBJ) $(BG_SO)
	$(CC) -shared -Wl,-soname,libbetelgeuse_scenefile.so.$(SOVERSION) $(ALL_LDFLAGS) -o $@ $(SF_OBJ) -L$(BUILD) \
	  -lbetelgeuse $(SF_LIBS)
	ln -sf libbetelgeuse_scenefile.so.$(VERSION) $(BUILD)/libbetelgeuse_scenefile.so.$(SOVERSION)
	ln -sf libbetelgeuse_scenefile.so.$(SOVERSION) $(BUILD)/libbetelgeuse_scenefile.so

# Always rewritten, so that the PREFIX of this make call (e.g. at install) is the one recorded.
$(BUILD)/%.pc: FORCE
	@mkdir -p $(dir $@)
	@{ echo 'prefix=$(PREFIX)'; echo 'libdir=$(LIBDIR)'; echo 'includedir=$(INCDIR)'; echo; \
	   if [ "$*" = macs ]; then \
	     echo 'Name: macs'; echo 'Description: GPGPU render passes over OpenGL 2.1'; \
	     echo 'Version: $(VERSION)'; echo 'Libs: -L$${libdir} -lmacs'; \
	     echo 'Libs.private: $(MACS_LIBS)'; \
	   elif [ "$*" = betelgeuse_scenefile ]; then \
	     echo 'Name: betelgeuse_scenefile'; echo 'Description: Betelgeuse scene files (JSON) and model files'; \
	     echo 'Version: $(VERSION)'; echo 'Requires: betelgeuse'; echo 'Libs: -L$${libdir} -lbetelgeuse_scenefile'; \
	     echo 'Libs.private: $(SF_LIBS)'; \
	   else \
	     echo 'Name: betelgeuse'; echo 'Description: Whitted ray tracing through OpenGL 2.1'; \
	     echo 'Version: $(VERSION)'; echo 'Requires: macs'; echo 'Libs: -L$${libdir} -lbetelgeuse'; \
	     echo 'Libs.private: $(BG_LIBS)'; \
	   fi; \
	   echo 'Cflags: -I$${includedir}'; } > $@

# The scene-file suites also link the scene-file library and its dependencies.
$(BUILD)/tests/test_scenefile%: tests/test_scenefile%.c $(TEST_UTIL_OBJ) $(SCENES_OBJ) $(SF_A) $(BG_A) $(MACS_A)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(DEPFLAGS) $(SF_CFLAGS) $(ALL_LDFLAGS) -o $@ $< $(TEST_UTIL_OBJ) $(SCENES_OBJ) $(SF_A) $(STATIC_LINK) $(SF_LIBS) \
	  $(TEST_LIBS)

# The viewer's pure rules are tested from their objects (no window needed).
$(BUILD)/tests/test_view_rules: tests/test_view_rules.c $(BUILD)/src/cli/view_resolution.o \
  $(BUILD)/src/cli/view_camera.o $(TEST_UTIL_OBJ) $(SCENES_OBJ) $(BG_A) $(MACS_A)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(DEPFLAGS) $(ALL_LDFLAGS) -o $@ $< $(filter %.o,$(wordlist 2,3,$^)) $(TEST_UTIL_OBJ) $(SCENES_OBJ) \
	  $(STATIC_LINK) $(TEST_LIBS)

$(CLI_OBJ): ALL_CFLAGS += -DBG_CLI_VERSION='"$(VERSION)"'
$(VIEW_OBJ): ALL_CFLAGS += $(GLFW_CFLAGS)
$(CLI_BIN): $(CLI_OBJ) $(SF_A) $(BG_A) $(MACS_A)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_LDFLAGS) -o $@ $(CLI_OBJ) $(SF_A) $(STATIC_LINK) $(SF_LIBS) $(GLFW_LIBS)

$(BUILD)/tests/%: tests/%.c $(TEST_UTIL_OBJ) $(SCENES_OBJ) $(BG_A) $(MACS_A)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(DEPFLAGS) $(ALL_LDFLAGS) -o $@ $< $(TEST_UTIL_OBJ) $(SCENES_OBJ) $(STATIC_LINK) $(TEST_LIBS)

$(BUILD)/examples/%: examples/%.c $(SCENES_OBJ) $(BG_A) $(MACS_A)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(DEPFLAGS) $(ALL_LDFLAGS) -o $@ $< $(SCENES_OBJ) $(STATIC_LINK)

# The window example links GLFW and the system's GL (for its quad); the libraries link neither.
$(BUILD)/examples/bg_window: examples/bg_window.c $(SCENES_OBJ) $(BG_A) $(MACS_A)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(DEPFLAGS) $(GLFW_CFLAGS) $(ALL_LDFLAGS) -o $@ $< $(SCENES_OBJ) $(STATIC_LINK) $(GLFW_LIBS) -lGL

$(BUILD)/bench/%: bench/%.c $(BENCH_LIB_OBJ) $(SCENES_OBJ) $(BG_A) $(MACS_A)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(DEPFLAGS) -Ibench $(ALL_LDFLAGS) -o $@ $< $(BENCH_LIB_OBJ) $(SCENES_OBJ) $(STATIC_LINK)

# bench_path reads the Cornell box scene files, so it links the scene-file library too.
$(BUILD)/bench/bench_path: bench/bench_path.c $(BENCH_LIB_OBJ) $(SCENES_OBJ) $(SF_A) $(BG_A) $(MACS_A)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(DEPFLAGS) -Ibench $(ALL_LDFLAGS) -o $@ $< $(BENCH_LIB_OBJ) $(SCENES_OBJ) $(SF_A) \
	  $(STATIC_LINK) $(SF_LIBS)

$(EMBREE_PEER_OBJ): ALL_CFLAGS += $(EMBREE_CFLAGS)
$(EMBREE_BENCH_BIN): $(BUILD)/bench/%: bench/%.c $(EMBREE_PEER_OBJ) $(BENCH_LIB_OBJ) $(SCENES_OBJ) $(BG_A) $(MACS_A)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(DEPFLAGS) $(EMBREE_CFLAGS) -DBENCH_EMBREE -Ibench $(ALL_LDFLAGS) -o $@ $< $(EMBREE_PEER_OBJ) \
	  $(BENCH_LIB_OBJ) $(SCENES_OBJ) $(STATIC_LINK) $(EMBREE_LIBS)

examples: all $(EXAMPLE_BIN)

# Every shader must compile as GLSL 1.10; library files are checked with the files they require.
glsl-check:
	@sh tests/glsl_check.sh glsl110

# The test environment (docs/architecture.md, "Tests"): GL 2.1 and GLSL 1.10 forced, no shader disk cache.
TEST_ENV := MESA_GL_VERSION_OVERRIDE=2.1 MESA_GLSL_VERSION_OVERRIDE=110 MESA_SHADER_CACHE_DISABLE=true
# Suites that also run on EGL surfaceless and on softpipe (smoke subset).
SMOKE_TESTS ?= $(filter $(BUILD)/tests/test_smoke%,$(TEST_BIN))

# The self-contained examples (examples/standalone_*.c, and bg_texture_view.c, which also includes
# the system's <GL/gl.h>) built as a user builds them: against a staged `make install` with
# `pkg-config betelgeuse` only (no -Iinclude, -Isrc or examples/scenes), linked to the staged shared
# libraries; then every example is run by tests/check_examples.sh (command line,
# and a PNG from each standalone one). The .pc files record PREFIX without DESTDIR, so
# PKG_CONFIG_SYSROOT_DIR puts the stage in front of their -I and -L paths. Under SANITIZE the
# programs also link the LSan hook of examples/scenes, as every other sanitized program does.
STAGE := $(abspath $(BUILD)/stage)
STAGE_PKG_CONFIG := PKG_CONFIG_PATH=$(STAGE)/usr/local/lib/pkgconfig PKG_CONFIG_SYSROOT_DIR=$(STAGE) pkg-config
STANDALONE_SRC := $(sort $(wildcard examples/standalone_*.c) examples/bg_texture_view.c)
check-examples: all $(EXAMPLE_BIN)
	@echo "== examples: standalone ones against a staged install (pkg-config betelgeuse), every one's command line"
	@rm -rf $(STAGE) $(BUILD)/installed && mkdir -p $(BUILD)/installed
	@$(MAKE) --no-print-directory -s install BUILD=$(BUILD) DESTDIR=$(STAGE) PREFIX=/usr/local \
	  LIBDIR=/usr/local/lib INCDIR=/usr/local/include >/dev/null
	@for s in $(STANDALONE_SRC); do \
	  flags=$$($(STAGE_PKG_CONFIG) --cflags --libs betelgeuse) || exit 1; \
	  cmd="$(CC) $(WARN) $(OPT) $(SANFLAGS) $(CFLAGS) -o $(BUILD)/installed/$$(basename $$s .c) $$s $(ALL_LDFLAGS) \
	    $(if $(SANFLAGS),examples/scenes/lsan_suppressions.c) $$flags"; \
	  echo $$cmd; $$cmd || exit 1; \
	done
	@LD_LIBRARY_PATH=$(STAGE)/usr/local/lib TEST_ENV="$(TEST_ENV)" sh tests/check_examples.sh \
	  "$(STANDALONE_SRC:examples/%.c=$(BUILD)/installed/%)" "$(EXAMPLE_BIN)"

check-symbols: all
	sh tests/check_symbols.sh $(BUILD)

# The command end to end: shipped scenes, broken files and options (exit codes and messages),
# tiles and crop windows against one render, assemble (tests/check_command.sh).
check-command: all
	@env $(TEST_ENV) sh tests/check_command.sh $(CLI_BIN)

# `betelgeuse view` in a real window on Xvfb with Mesa's GLX: scripted and xdotool input, the
# screenshot at rest against render, reload on edit, Esc (tests/check_view.sh; needs xvfb, xauth and
# xdotool, and says so, skipping, without them).
# Under SANITIZE, leaks are not looked for in the windowed runs: Mesa's GLX driver leaks about 5 KB
# (driver option strings) and is unloaded before LeakSanitizer runs at exit, so its frames have no
# module a suppression could name. ASan's memory errors and UBSan stay on.
check-view: all
	@env $(TEST_ENV) $(if $(SANFLAGS),ASAN_OPTIONS=detect_leaks=0) sh tests/check_view.sh $(CLI_BIN)

# A single-node Slurm cluster started and stopped by the test renders a shared scene as a job array
# of 4 tiles, assembles them and compares the frame with one render (tests/check_cluster.sh; needs
# the slurm-wlm and munge packages).
check-cluster: all
	@env $(TEST_ENV) bash tests/check_cluster.sh $(CLI_BIN)

# The project where Mesa has no OSMesa: every libOSMesa file hidden in a private mount namespace (needs
# root and unshare), the smoke suites and a GPU scene suite on EGL surfaceless, and the command
# (tests/check_no_osmesa.sh).
NO_OSMESA_TESTS := $(SMOKE_TESTS) $(BUILD)/tests/test_bg_gpu_scenes
check-no-osmesa: all $(NO_OSMESA_TESTS) $(BUILD)/tests/probe_headless
	@TEST_ENV="$(TEST_ENV)" sh tests/check_no_osmesa.sh $(BUILD) "$(NO_OSMESA_TESTS)" "$(SMOKE_TESTS)"

# make check-profile PROFILE=name: the GPU suites under one MACS limit profile (docs/profiles.md:
# geforce7, radeon_x1600, gma_x3100, gl21), MACS_TEST_PROFILE added to TEST_ENV. A test the renderer
# cannot run within the profile is skipped by name, with the limit it names.
# Leak checking is off under a profile: a skip jumps out of its test past the frees (tests/run_suites.sh).
PROFILE_TESTS ?= $(filter $(BUILD)/tests/test_bg_gpu% $(BUILD)/tests/test_smoke_bg_gpu,$(TEST_BIN))
# The GPU scene suites (images against the CPU reference on the shared scenes, every plan, meshes):
# make check runs them under the most constrained profile the renderer runs on, radeon_x1600 (no
# float filtering at all, 16-bit float blending only, EXT_framebuffer_object, 4 draw buffers, 4096
# texels), and under gl21, the GL 2.1 minimums, where most scenes are refused by name (BG_ERR_LIMIT,
# counted skipped); make check-profiles under every profile (CI).
PROFILE_SCENE_TESTS := $(filter $(BUILD)/tests/test_bg_gpu_scenes $(BUILD)/tests/test_smoke_bg_gpu \
                         $(BUILD)/tests/test_bg_gpu_plans $(BUILD)/tests/test_bg_gpu_mesh,$(TEST_BIN))
CHECK_PROFILES ?= radeon_x1600 gl21
ALL_PROFILES := geforce7 radeon_x1600 gma_x3100 gl21
# The profiles make check-profiles runs: every one unless told fewer (CI, which runs make check as
# well, names only those CHECK_PROFILES leaves out).
PROFILES_RUN ?= $(ALL_PROFILES)
check-profiles: all $(PROFILE_SCENE_TESTS) $(BUILD)/tests/probe_headless
	@TEST_ENV="$(TEST_ENV)" PROBE=$(BUILD)/tests/probe_headless PROFILES="$(PROFILES_RUN)" \
	  PROFILE_SUITES="$(PROFILE_SCENE_TESTS)" sh tests/run_suites.sh "" ""
check-profile: all $(PROFILE_TESTS) $(BUILD)/tests/probe_headless
	@test -n "$(PROFILE)" || { echo "make check-profile: PROFILE=name is required: geforce7, radeon_x1600, gma_x3100 or gl21"; exit 2; }
	@TEST_ENV="$(TEST_ENV) MACS_TEST_PROFILE=$(PROFILE) ASAN_OPTIONS=detect_leaks=0" PROBE=$(BUILD)/tests/probe_headless \
	  sh tests/run_suites.sh "$(PROFILE_TESTS)" ""

# The test programs built but not run, so that a parallel make can build them before make check.
test-programs: $(TEST_BIN) $(BUILD)/tests/probe_headless $(BUILD)/tests/device/crash_suite $(BUILD)/tests/device/device_info

# The runner's own handling of crashes and timeouts (tests/device/check_runner.sh): a suite that
# crashes on purpose (tests/device/crash_suite.c, not one of the suites) and one that hangs.
check-runner: $(BUILD)/tests/device/crash_suite
	@sh tests/device/check_runner.sh $(BUILD)/tests/device/crash_suite

# The device check (docs/device_check.md): a release build of every suite, the benchmarks the check
# runs and the command, packed with their libraries, data and glvnd's EGL packages into
# build/device/ (tests/device/pack.sh), to be sent to a GPU machine and run there with one command,
# `sh build/device/run.sh` (tests/device/run.sh).
DEVICE_PACK_BUILD := build/release
device-pack:
	@$(MAKE) --no-print-directory SANITIZE= BUILD=$(DEVICE_PACK_BUILD) all test-programs \
	  $(DEVICE_PACK_BUILD)/bench/bench_paper $(DEVICE_PACK_BUILD)/bench/bench_distribution
	@sh tests/device/pack.sh $(DEVICE_PACK_BUILD) build/device

# The suites run CHECK_JOBS at a time (default: one per processor); build/suite-times keeps each
# run's duration so that the next check, of any build, starts the longest first.
check: all glsl-check check-symbols check-examples check-command check-view check-fuzz-corpus check-runner $(TEST_BIN) \
  $(BUILD)/tests/probe_headless
	@TEST_ENV="$(TEST_ENV)" PROBE=$(BUILD)/tests/probe_headless TIMES=build/suite-times \
	  PROFILES="$(CHECK_PROFILES)" PROFILE_SUITES="$(PROFILE_SCENE_TESTS)" \
	  sh tests/run_suites.sh "$(TEST_BIN)" "$(SMOKE_TESTS)"

# Every suite that opens a GL context, on a second GL implementation: Mesa's zink (GL on Vulkan)
# over lavapipe, through EGL surfaceless (README, "Run the tests"; needs mesa-vulkan-drivers).
# tests/probe_stencil_clear.c runs first and says whether zink's masked stencil clear is still
# broken, the defect the suites' zink skips name. ZINK_SUITES may name fewer suites; ZINK_ICD is
# lavapipe's Vulkan driver manifest; XDG_RUNTIME_DIR is a private folder, as Mesa wants one.
GL_TEST_SRC := $(shell grep -lE 'util_gpu_group_setup|util_gpu_open|util_group_setup|util_headless' $(TEST_SRC))
ZINK_SUITES ?= $(GL_TEST_SRC:tests/%.c=$(BUILD)/tests/%)
ZINK_ICD ?= $(firstword $(wildcard /usr/share/vulkan/icd.d/lvp_icd.*.json))
ZINK_ENV := LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=zink VK_ICD_FILENAMES=$(ZINK_ICD) \
  XDG_RUNTIME_DIR=$(abspath $(BUILD))/zink-runtime
$(BUILD)/tests/probe_stencil_clear: tests/probe_stencil_clear.c $(MACS_A)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -o $@ $< $(ALL_LDFLAGS) $(MACS_A) $(MACS_LIBS)
test-programs: $(BUILD)/tests/probe_stencil_clear
check-zink: all $(ZINK_SUITES) $(BUILD)/tests/probe_stencil_clear $(BUILD)/tests/probe_headless
	@test -n "$(ZINK_ICD)" || { echo "no lavapipe (mesa-vulkan-drivers): set ZINK_ICD"; exit 1; }
	@mkdir -p $(BUILD)/zink-runtime && chmod 700 $(BUILD)/zink-runtime
	@echo "== zink's masked stencil clear (tests/probe_stencil_clear.c)"
	@env $(TEST_ENV) $(ZINK_ENV) EGL_PLATFORM=surfaceless $(BUILD)/tests/probe_stencil_clear egl; s=$$?; \
	  if [ $$s = 1 ]; then echo "the defect is there: the zink skips stand"; \
	  elif [ $$s = 0 ]; then echo "the defect is gone: lift the zink skips (tests/util_driver.c)"; \
	  else exit 1; fi
	@TEST_ENV="$(TEST_ENV) $(ZINK_ENV)" PROBE=$(BUILD)/tests/probe_headless TIMES=build/zink-times \
	  SUITE_BACKEND=surfaceless SUITE_DRIVER=zink sh tests/run_suites.sh "$(ZINK_SUITES)" ""

# ==== Fuzzing (docs/fuzzing.md) ===================================================================
# The scene-file loaders under libFuzzer, one target each (tests/fuzz/): json (JSON scene text,
# bg_scenefile_load_string) and ply, obj, stl (bg_scenefile_load_model on a file of that extension).
# Each target's seed corpus is tests/fuzz/corpus/<target>/, kept in the repository; the fuzzer never
# writes there.
#   make check-fuzz-corpus   every corpus file through its target, built with $(CC) and this build's
#                            flags (ASan + UBSan under SANITIZE=1): a regression test without clang
#   make fuzz-build          the libFuzzer binaries $(BUILD)/fuzz/fuzz_<target> (needs clang)
#   make fuzz FUZZ_TARGET=json|ply|obj|stl FUZZ_SECONDS=600 [FUZZ_ARGS=...]
#                            one target on $(BUILD)/fuzz/work-<target>, a copy of its seeds that keeps
#                            what the fuzzer finds from run to run; crashers go to
#                            $(BUILD)/fuzz/crashes-<target>/
FUZZ_TARGETS := json ply obj stl
FUZZ_MODELS  := ply obj stl
FUZZ_TARGET  ?= json
FUZZ_SECONDS ?= 600
FUZZ_ARGS    ?=
FUZZ_CC      ?= clang
FUZZ_DIR     := $(BUILD)/fuzz
FUZZ_HDR     := tests/fuzz/fuzz_target.h
# The JSON target resolves the seeds' texture and mesh paths against the shipped scenes' folder;
# an absolute path, so that the binaries run from any folder (BG_FUZZ_SCENE_DIR overrides it).
FUZZ_SCENE_DIR := -DFUZZ_SCENE_DIR='"$(abspath examples/scenes/json)"'
# assimp's own leaks on files it gives up on (tests/fuzz/assimp_leaks.supp says why).
FUZZ_LSAN := LSAN_OPTIONS=suppressions=$(abspath tests/fuzz/assimp_leaks.supp)

# The replay programs: the targets with tests/fuzz/replay_main.c for a main, on this build's archives.
FUZZ_REPLAY_DIR := $(BUILD)/tests/fuzz
FUZZ_REPLAY_BIN := $(FUZZ_TARGETS:%=$(FUZZ_REPLAY_DIR)/replay_%)
$(FUZZ_REPLAY_DIR)/replay_main.o $(FUZZ_REPLAY_DIR)/fuzz_common.o: $(FUZZ_HDR)
$(FUZZ_REPLAY_DIR)/target_json.o: tests/fuzz/fuzz_scene_json.c $(FUZZ_HDR) $(wildcard include/*.h)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(DEPFLAGS) $(FUZZ_SCENE_DIR) -c $< -o $@
$(FUZZ_MODELS:%=$(FUZZ_REPLAY_DIR)/target_%.o): $(FUZZ_REPLAY_DIR)/target_%.o: tests/fuzz/fuzz_model.c $(FUZZ_HDR) \
  $(wildcard include/*.h)
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(DEPFLAGS) -DFUZZ_EXTENSION='".$*"' -c $< -o $@
# Under SANITIZE the LSan hook of examples/scenes comes along, as in every other sanitized program.
$(FUZZ_REPLAY_DIR)/replay_%: $(FUZZ_REPLAY_DIR)/target_%.o $(FUZZ_REPLAY_DIR)/replay_main.o \
  $(FUZZ_REPLAY_DIR)/fuzz_common.o $(if $(SANFLAGS),$(BUILD)/examples/scenes/lsan_suppressions.o) $(SF_A) $(BG_A) \
  $(MACS_A)
	$(CC) $(ALL_LDFLAGS) -o $@ $(filter %.o,$^) $(SF_A) $(STATIC_LINK) $(SF_LIBS)

# Built with the other test programs, so that a parallel make builds them before make check.
test-programs: $(FUZZ_REPLAY_BIN)

# Every target's corpus, each input in a process of its own; every failing input is named, then the
# check fails. Standard input is /dev/null, as under make fuzz.
check-fuzz-corpus: $(FUZZ_REPLAY_BIN)
	@echo "== fuzz corpus replay (tests/fuzz/corpus)"
	@status=0; for t in $(FUZZ_TARGETS); do \
	  $(FUZZ_LSAN) $(FUZZ_REPLAY_DIR)/replay_$$t tests/fuzz/corpus/$$t </dev/null || status=1; \
	done; exit $$status

# The libFuzzer build: the three libraries compiled again from the same sources with $(FUZZ_CC) and
# coverage instrumentation (-fsanitize=fuzzer-no-link) under ASan and UBSan, in $(BUILD)/fuzz/obj.
# cJSON, assimp and libpng are the system's, not instrumented: the fuzzer sees coverage of this
# project's code only, and ASan still checks their heap through its malloc and new. The library
# objects leave out -Werror: this compiler's warnings are not the project's gate (the $(CC) build
# is), and a clang-only warning should not stop a fuzzing run; the fuzz targets keep it.
FUZZ_OBJ_DIR := $(FUZZ_DIR)/obj
FUZZ_SAN     := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
FUZZ_WARN    := $(filter-out -Werror,$(WARN))
FUZZ_CFLAGS  := $(DEFS) -O1 -g $(FUZZ_SAN) -fsanitize=fuzzer-no-link -Iinclude -Isrc $(SF_CFLAGS)
FUZZ_LIB_OBJ := $(MACS_SRC:%.c=$(FUZZ_OBJ_DIR)/%.o) $(BG_SRC:%.c=$(FUZZ_OBJ_DIR)/%.o) \
  $(FUZZ_OBJ_DIR)/gen/macs_shaders.o $(FUZZ_OBJ_DIR)/gen/bg_shaders.o
FUZZ_SF_OBJ  := $(SF_SRC:%.c=$(FUZZ_OBJ_DIR)/%.o)
# Archives, so that the link takes only the members the loaders reach, as a user's static link does.
FUZZ_A       := $(FUZZ_OBJ_DIR)/libbetelgeuse_scenefile.a $(FUZZ_OBJ_DIR)/libbetelgeuse.a $(FUZZ_OBJ_DIR)/libmacs.a
FUZZ_BIN     := $(FUZZ_TARGETS:%=$(FUZZ_DIR)/fuzz_%)

$(FUZZ_OBJ_DIR)/%.o: %.c
	@mkdir -p $(dir $@)
	$(FUZZ_CC) $(DEPFLAGS) $(FUZZ_WARN) $(FUZZ_CFLAGS) -c $< -o $@
$(FUZZ_OBJ_DIR)/gen/%_shaders.o: $(BUILD)/gen/%_shaders.c
	@mkdir -p $(dir $@)
	$(FUZZ_CC) $(DEPFLAGS) $(FUZZ_WARN) -Wno-overlength-strings $(FUZZ_CFLAGS) -c $< -o $@
$(FUZZ_OBJ_DIR)/libmacs.a: $(filter $(FUZZ_OBJ_DIR)/src/macs/%,$(FUZZ_LIB_OBJ)) $(FUZZ_OBJ_DIR)/gen/macs_shaders.o
	@rm -f $@
	ar rcs $@ $^
$(FUZZ_OBJ_DIR)/libbetelgeuse.a: $(filter $(FUZZ_OBJ_DIR)/src/betelgeuse/%,$(FUZZ_LIB_OBJ)) $(FUZZ_OBJ_DIR)/gen/bg_shaders.o
	@rm -f $@
	ar rcs $@ $^
$(FUZZ_OBJ_DIR)/libbetelgeuse_scenefile.a: $(FUZZ_SF_OBJ)
	@rm -f $@
	ar rcs $@ $^
$(FUZZ_OBJ_DIR)/target_json.o: tests/fuzz/fuzz_scene_json.c $(FUZZ_HDR) $(wildcard include/*.h)
	@mkdir -p $(dir $@)
	$(FUZZ_CC) $(DEPFLAGS) $(WARN) $(FUZZ_CFLAGS) $(FUZZ_SCENE_DIR) -c $< -o $@
$(FUZZ_MODELS:%=$(FUZZ_OBJ_DIR)/target_%.o): $(FUZZ_OBJ_DIR)/target_%.o: tests/fuzz/fuzz_model.c $(FUZZ_HDR) \
  $(wildcard include/*.h)
	@mkdir -p $(dir $@)
	$(FUZZ_CC) $(DEPFLAGS) $(WARN) $(FUZZ_CFLAGS) -DFUZZ_EXTENSION='".$*"' -c $< -o $@
$(FUZZ_OBJ_DIR)/fuzz_common.o: tests/fuzz/fuzz_common.c $(FUZZ_HDR)
	@mkdir -p $(dir $@)
	$(FUZZ_CC) $(DEPFLAGS) $(WARN) $(FUZZ_CFLAGS) -c $< -o $@
$(FUZZ_DIR)/fuzz_%: $(FUZZ_OBJ_DIR)/target_%.o $(FUZZ_OBJ_DIR)/fuzz_common.o $(FUZZ_A)
	$(FUZZ_CC) $(FUZZ_SAN) -fsanitize=fuzzer $(LDFLAGS) -o $@ $(filter %.o,$^) $(FUZZ_A) $(SF_LIBS) $(BG_LIBS) \
	  $(MACS_LIBS)

fuzz-build: $(FUZZ_BIN)

# libFuzzer's options go after the corpus folder. It adds what it finds to the first (here the only)
# folder, the work copy; -timeout makes a hang a finding, -rss_limit_mb (which also caps any one
# malloc at that size) makes a runaway allocation one. Standard input is /dev/null, so that a file
# named /dev/stdin in an input cannot stall the run.
ifneq ($(filter fuzz,$(MAKECMDGOALS)),)
$(if $(filter $(FUZZ_TARGETS),$(FUZZ_TARGET)),,$(error FUZZ_TARGET must be one of: $(FUZZ_TARGETS) (got "$(FUZZ_TARGET)")))
endif
fuzz: $(FUZZ_DIR)/fuzz_$(FUZZ_TARGET)
	@mkdir -p $(FUZZ_DIR)/work-$(FUZZ_TARGET) $(FUZZ_DIR)/crashes-$(FUZZ_TARGET)
	@cp tests/fuzz/corpus/$(FUZZ_TARGET)/* $(FUZZ_DIR)/work-$(FUZZ_TARGET)/
	$(FUZZ_LSAN) $(FUZZ_DIR)/fuzz_$(FUZZ_TARGET) $(FUZZ_DIR)/work-$(FUZZ_TARGET) -max_total_time=$(FUZZ_SECONDS) \
	  -rss_limit_mb=2048 -timeout=10 -dict=tests/fuzz/dict/$(FUZZ_TARGET).dict \
	  -artifact_prefix=$(FUZZ_DIR)/crashes-$(FUZZ_TARGET)/ -print_final_stats=1 $(FUZZ_ARGS) </dev/null
# ==== End of fuzzing ==============================================================================

# valgrind over the MACS suites and the GPU renderer's error and smoke suites (renderer create/destroy
# cycles, failure paths, the paper scenes), leaks as errors, two at a time; tests/valgrind.supp holds
# only reports from inside Mesa, LLVM and the loader. No shader cache here: Mesa checks the blobs it
# writes to its cache with valgrind's own client requests, and they hold uninitialised padding.
VALGRIND_TESTS ?= $(filter $(BUILD)/tests/test_macs% $(BUILD)/tests/test_bg_gpu_errors $(BUILD)/tests/test_smoke_bg_gpu,$(TEST_BIN))
VALGRIND := valgrind --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite,indirect \
  --show-leak-kinds=definite,indirect --suppressions=tests/valgrind.supp -q
valgrind: $(VALGRIND_TESTS) $(BUILD)/tests/probe_headless
	@TEST_ENV="$(TEST_ENV) MACS_TEST_QUICK=1" PROBE=$(BUILD)/tests/probe_headless TIMES=build/valgrind-times \
	  RUN_WITH="$(VALGRIND)" SHADER_CACHE=no sh tests/run_suites.sh "$(VALGRIND_TESTS)" ""

# Benchmarks and stress run under the test environment's GL 2.1 / GLSL 1.10, so
# they measure what the tests check. QUICK=1 makes them short. Results: tables on stdout, CSV and (with
# gnuplot) PNG plots in BENCH_OUT, where each program's table is also kept as <program>.txt; progress
# on stderr.
BENCH_OUT ?= bench/out
BENCH_ENV := $(TEST_ENV) QUICK=$(QUICK)
BENCH_PROGRAMS := bench_paper bench_frame_cost bench_scaling bench_tradeoffs bench_phases bench_recommit bench_mesh bench_primary bench_walk_floor bench_distribution bench_progressive bench_path $(if $(EMBREE_LIBS),bench_embree)
# The benchmark programs built but not run: CI checks that they still compile.
bench-programs: all $(BENCH_BIN)

bench: all $(BENCH_BIN)
	@mkdir -p $(BENCH_OUT)
	@$(if $(EMBREE_LIBS),:,echo "Embree (4 or 3, libembree-dev) is not installed: no bench_embree")
	@for b in $(BENCH_PROGRAMS); do \
	  { env $(BENCH_ENV) $(BUILD)/bench/$$b $(BENCH_OUT); echo $$? > $(BENCH_OUT)/$$b.status; } | tee $(BENCH_OUT)/$$b.txt; \
	  [ "$$(cat $(BENCH_OUT)/$$b.status)" = 0 ] || exit 1; echo; done
	@if command -v gnuplot >/dev/null 2>&1; then gnuplot -e "dir='$(BENCH_OUT)'" bench/plots.gp && \
	  echo "plots: $(BENCH_OUT)/*.png"; else echo "gnuplot is not installed: no plots"; fi
stress: all $(BENCH_BIN)
	@mkdir -p $(BENCH_OUT)
	@{ env $(BENCH_ENV) $(BUILD)/bench/stress $(BENCH_OUT); echo $$? > $(BENCH_OUT)/stress.status; } | tee $(BENCH_OUT)/stress.txt; \
	  [ "$$(cat $(BENCH_OUT)/stress.status)" = 0 ]

install: all
	install -d $(DESTDIR)$(LIBDIR) $(DESTDIR)$(INCDIR) $(DESTDIR)$(LIBDIR)/pkgconfig $(DESTDIR)$(BINDIR)
	install -m 755 $(CLI_BIN) $(DESTDIR)$(BINDIR)/
	install -m 644 include/macs.h include/betelgeuse.h include/betelgeuse_scenefile.h $(DESTDIR)$(INCDIR)/
	install -m 644 $(MACS_A) $(BG_A) $(SF_A) $(DESTDIR)$(LIBDIR)/
	install -m 755 $(MACS_SO) $(BG_SO) $(SF_SO) $(DESTDIR)$(LIBDIR)/
	ln -sf libmacs.so.$(VERSION) $(DESTDIR)$(LIBDIR)/libmacs.so.$(SOVERSION)
	ln -sf libmacs.so.$(SOVERSION) $(DESTDIR)$(LIBDIR)/libmacs.so
	ln -sf libbetelgeuse.so.$(VERSION) $(DESTDIR)$(LIBDIR)/libbetelgeuse.so.$(SOVERSION)
	ln -sf libbetelgeuse.so.$(SOVERSION) $(DESTDIR)$(LIBDIR)/libbetelgeuse.so
	ln -sf libbetelgeuse_scenefile.so.$(VERSION) $(DESTDIR)$(LIBDIR)/libbetelgeuse_scenefile.so.$(SOVERSION)
	ln -sf libbetelgeuse_scenefile.so.$(SOVERSION) $(DESTDIR)$(LIBDIR)/libbetelgeuse_scenefile.so
	install -m 644 $(BUILD)/macs.pc $(BUILD)/betelgeuse.pc $(BUILD)/betelgeuse_scenefile.pc $(DESTDIR)$(LIBDIR)/pkgconfig/

# The pkgconfig folder goes too when nothing else is left in it (install made it where it was
# missing); lib and include stay: they are the prefix's own (Debian ships /usr/local/include empty).
uninstall:
	rm -f $(DESTDIR)$(BINDIR)/betelgeuse
	rm -f $(DESTDIR)$(INCDIR)/macs.h $(DESTDIR)$(INCDIR)/betelgeuse.h $(DESTDIR)$(INCDIR)/betelgeuse_scenefile.h
	rm -f $(DESTDIR)$(LIBDIR)/libmacs.* $(DESTDIR)$(LIBDIR)/libbetelgeuse.* $(DESTDIR)$(LIBDIR)/libbetelgeuse_scenefile.*
	rm -f $(DESTDIR)$(LIBDIR)/pkgconfig/macs.pc $(DESTDIR)$(LIBDIR)/pkgconfig/betelgeuse.pc
	rm -f $(DESTDIR)$(LIBDIR)/pkgconfig/betelgeuse_scenefile.pc
	rmdir $(DESTDIR)$(LIBDIR)/pkgconfig 2>/dev/null || true

clean:
	rm -rf build

# The headers each object and program was built from (DEPFLAGS above).
-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)
