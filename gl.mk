# gl.mk - the OpenGL part of the hairfur.h build: GLAD generated at build
# time, the shared examples/gl_common.h, the GL examples and GL checks.
#
# Meant to be included by the top-level Makefile after BUILD, OUT, WARN and
# DEPS_PKGS are set:
#
#     include gl.mk          (or paste this in)
#
# Targets:
#   make gl-check     say whether headless EGL + GL 3.3 core works here
#                     (exit 0), or print "SKIP: <what is missing>" (exit 0
#                     too: a missing GPU stack is not a build failure)
#   make gl-test      gl_check, then the GL smoke/ribbon tests when it
#                     passed; prints the skip reason otherwise
#   make gl-examples  build every examples/*.c GL example into $(BUILD)/
#
# Everything GL lives behind these targets: `make test` (the library tests)
# needs none of it.

BUILD ?= build
OUT   ?= out
WARN  ?= -Wall -Wextra -Wpedantic -Werror

# Debian packages for the GL examples: build (GLFW, EGL and stb headers,
# the glad generator) and run (Mesa's EGL vendor and llvmpipe driver).
GL_DEPS_PKGS := libglfw3-dev libegl-dev libegl-mesa0 libgl1-mesa-dri \
                python3-glad libstb-dev pkg-config
DEPS_PKGS += $(filter-out $(DEPS_PKGS),$(GL_DEPS_PKGS))

# ---- GLAD (glad 2.x, Debian python3-glad 2.0.2) ---------------------------
# --reproducible uses the gl.xml packaged with glad (no network, no date in
# the output), so the generated loader is the same on every machine.
GLAD_DIR   := $(BUILD)/glad
GLAD_STAMP := $(GLAD_DIR)/.generated
GLAD_O     := $(GLAD_DIR)/gl.o
GLAD_CMD   := glad --api gl:core=3.3 --reproducible --out-path $(GLAD_DIR) c

$(GLAD_STAMP):
	@command -v glad >/dev/null 2>&1 || { \
	  echo "gl.mk: the 'glad' command is missing: install python3-glad" \
	       "(sudo apt-get install python3-glad, or make deps)"; exit 1; }
	@if glad --help 2>/dev/null | grep -q -- '--generator'; then \
	  echo "gl.mk: this glad is glad 0.1.x (--generator/--profile command" \
	       "line); the build needs glad 2.x: install python3-glad >= 2.0"; \
	  exit 1; fi
	rm -rf $(GLAD_DIR)
	$(GLAD_CMD)
	@test -f $(GLAD_DIR)/src/gl.c && test -f $(GLAD_DIR)/include/glad/gl.h
	touch $@

# Generated code: compiled once, without -Werror (it is not ours).
$(GLAD_O): $(GLAD_STAMP)
	$(CC) -std=c99 -O2 -I$(GLAD_DIR)/include -c $(GLAD_DIR)/src/gl.c -o $@

# ---- flags -----------------------------------------------------------------
# pkg-config where it knows the packages; plain -l flags otherwise.
GL_PC_CFLAGS := $(shell pkg-config --cflags glfw3 egl 2>/dev/null)
GL_PC_LIBS   := $(shell pkg-config --libs glfw3 egl 2>/dev/null)
EGL_PC_LIBS  := $(shell pkg-config --libs egl 2>/dev/null)
GL_CFLAGS    := -std=c99 -O2 -I$(GLAD_DIR)/include -Iexamples -I. $(GL_PC_CFLAGS)
GL_LIBS      := $(if $(GL_PC_LIBS),$(GL_PC_LIBS),-lglfw -lEGL) -lm
EGL_LIBS     := $(if $(EGL_PC_LIBS),$(EGL_PC_LIBS),-lEGL) -lm

# Build-time headers, checked with a message naming the package.
.PHONY: gl-need
gl-need:
	@miss=""; \
	for h in "GLFW/glfw3.h libglfw3-dev" "EGL/egl.h libegl-dev" \
	         "stb/stb_image_write.h libstb-dev"; do \
	  set -- $$h; \
	  printf '#include <%s>\n' "$$1" | $(CC) $(GL_PC_CFLAGS) -E -x c - \
	    >/dev/null 2>&1 || miss="$$miss $$2"; \
	done; \
	if [ -n "$$miss" ]; then \
	  echo "gl.mk: missing headers: install$$miss (or make deps)"; exit 1; \
	fi

GL_COMMON := examples/gl_common.h

# ---- examples --------------------------------------------------------------
# The GL examples (GL_EXAMPLES, names in examples/, set by the Makefile):
# $(BUILD)/<name>. They include gl_common.h (one of them per program defines
# GLC_IMPLEMENTATION) and hairfur.h; they get GLFW for the window mode but
# run headless without a display (headless mode never calls glfwInit).
GL_EXAMPLE_BINS := $(addprefix $(BUILD)/,$(GL_EXAMPLES))

$(GL_EXAMPLE_BINS): $(BUILD)/%: examples/%.c $(GL_COMMON) hairfur.h \
                    $(GLAD_O) | gl-need $(BUILD)
	$(CC) $(GL_CFLAGS) $(WARN) $< $(GLAD_O) -o $@ $(GL_LIBS)

# ---- checks ----------------------------------------------------------------
# gl_check needs no GLFW: only libEGL (and Mesa at run time).
$(BUILD)/gl_check: tests/gl_check.c $(GL_COMMON) $(GLAD_O) | gl-need $(BUILD)
	$(CC) $(GL_CFLAGS) $(WARN) $< $(GLAD_O) -o $@ $(EGL_LIBS)

$(BUILD)/gl_smoke: tests/gl_smoke.c $(GL_COMMON) $(GLAD_O) | gl-need $(BUILD)
	$(CC) $(GL_CFLAGS) $(WARN) $< $(GLAD_O) -o $@ $(GL_LIBS)

$(BUILD)/gl_ribbon_check: tests/gl_ribbon_check.c $(GL_COMMON) hairfur.h \
                          $(GLAD_O) | gl-need $(BUILD)
	$(CC) $(GL_CFLAGS) $(WARN) $< $(GLAD_O) -o $@ $(GL_LIBS)

$(BUILD)/gl_misc_test: tests/gl_misc_test.c $(GL_COMMON) $(GLAD_O) \
                       | gl-need $(BUILD)
	$(CC) $(GL_CFLAGS) $(WARN) $< $(GLAD_O) -o $@ $(GL_LIBS)

$(BUILD)/gl_window_test: tests/gl_window_test.c $(GL_COMMON) $(GLAD_O) \
                         | gl-need $(BUILD)
	$(CC) $(GL_CFLAGS) $(WARN) $< $(GLAD_O) -o $@ $(GL_LIBS)

.PHONY: gl-check gl-test gl-examples gl-window-test
gl-examples: $(GL_EXAMPLE_BINS)

gl-check: $(BUILD)/gl_check
	@$(BUILD)/gl_check || true

# DISPLAY is unset so the checks prove the headless path needs no display.
GL_TESTS := $(BUILD)/gl_smoke $(BUILD)/gl_misc_test $(BUILD)/gl_ribbon_check \
            $(BUILD)/gl_fur_check
gl-test: $(BUILD)/gl_check $(GL_TESTS) | $(OUT)
	@if ! why=$$(env -u DISPLAY -u WAYLAND_DISPLAY $(BUILD)/gl_check); then \
	  echo "GL tests skipped: $$why"; exit 0; \
	fi; \
	echo "$$why"; fail=0; \
	env -u DISPLAY -u WAYLAND_DISPLAY $(BUILD)/gl_smoke $(OUT)/smoke.png \
	  > $(BUILD)/gl_smoke.log 2>&1 || fail=1; tail -n 1 $(BUILD)/gl_smoke.log; \
	env -u DISPLAY -u WAYLAND_DISPLAY $(BUILD)/gl_misc_test \
	  > $(BUILD)/gl_misc_test.log 2>&1 || fail=1; tail -n 1 $(BUILD)/gl_misc_test.log; \
	env -u DISPLAY -u WAYLAND_DISPLAY $(BUILD)/gl_ribbon_check \
	  examples/ribbon_expand.glsl $(OUT)/ribbons.png \
	  > $(BUILD)/gl_ribbon_check.log 2>&1 || fail=1; \
	  tail -n 1 $(BUILD)/gl_ribbon_check.log; \
	env -u DISPLAY -u WAYLAND_DISPLAY $(BUILD)/gl_fur_check \
	  > $(BUILD)/gl_fur_check.log 2>&1 || fail=1; \
	  tail -n 1 $(BUILD)/gl_fur_check.log; \
	if [ $$fail -ne 0 ]; then echo "make gl-test: FAILED (logs in $(BUILD)/gl_*.log)"; exit 1; fi; \
	echo "make gl-test: all GL checks passed"

# The window path needs a display: under xvfb-run (package xvfb) when
# there is none. Not part of gl-test.
gl-window-test: $(BUILD)/gl_window_test | $(OUT)
	@if [ -n "$$DISPLAY" ]; then $(BUILD)/gl_window_test; \
	elif command -v xvfb-run >/dev/null 2>&1; then \
	  xvfb-run -a -s "-screen 0 640x480x24" $(BUILD)/gl_window_test; \
	else echo "gl-window-test skipped: no DISPLAY and no xvfb-run" \
	          "(install xvfb)"; fi
