# glex.mk - the GL examples of issue 7 (gl_minimal, gl_marschner) and their
# headless render test (gl_fur_check). For the lead to merge into the
# Makefile / gl.mk.
#
# Wiring, in the top-level Makefile:
#
#     GL_EXAMPLES := gl_minimal gl_marschner     # BEFORE `include gl.mk`:
#     include gl.mk                              # gl.mk expands it at once
#     include glex.mk
#
# then add `gl-demo` to `demo`, and `$(GL_FUR_CHECK_CMD)` to gl-test (below).
#
# gl.mk already builds $(BUILD)/<name> for every name in GL_EXAMPLES from
# examples/<name>.c with $(GL_CFLAGS) $(WARN) ... $(GLAD_O) $(GL_LIBS);
# these two also include examples/head_mesh.h, so say so:
$(BUILD)/gl_minimal $(BUILD)/gl_marschner: examples/head_mesh.h

# The render test includes examples/gl_marschner.c (with GLM_NO_MAIN).
$(BUILD)/gl_fur_check: tests/gl_fur_check.c examples/gl_marschner.c \
                       examples/head_mesh.h $(GL_COMMON) hairfur.h $(GLAD_O) \
                       | gl-need $(BUILD)
	$(CC) $(GL_CFLAGS) $(WARN) $< $(GLAD_O) -o $@ $(GL_LIBS)

# ---- make demo (GL part) -----------------------------------------------------
# Headless renders of the swinging head (EGL, no display needed). Run from
# the repository root: the GPU-expansion path reads
# examples/ribbon_expand.glsl. With no headless GL, say why and go on.
GLEX_RUN := env -u DISPLAY -u WAYLAND_DISPLAY $(BUILD)/gl_marschner --headless

.PHONY: gl-demo run run-minimal
gl-demo: $(BUILD)/gl_check $(BUILD)/gl_marschner $(BUILD)/gl_minimal | $(OUT)
	@if ! why=$$(env -u DISPLAY -u WAYLAND_DISPLAY $(BUILD)/gl_check); then \
	  echo "GL demo skipped: $$why"; exit 0; fi; \
	set -e; \
	$(GLEX_RUN) --frames 30  --out $(OUT)/fur_swing_030.png; \
	$(GLEX_RUN) --frames 60  --out $(OUT)/fur_swing_060.png; \
	$(GLEX_RUN) --frames 90  --out $(OUT)/fur_swing_090.png; \
	$(GLEX_RUN) --frames 90  --kajiya --out $(OUT)/fur_kajiya.png; \
	$(GLEX_RUN) --frames 90  --gpu-expand --color3d --out $(OUT)/fur_color3d_gpu.png; \
	env -u DISPLAY -u WAYLAND_DISPLAY $(BUILD)/gl_minimal --headless \
	  --frames 60 --out $(OUT)/fur_minimal.png; \
	echo "gl-demo: wrote $(OUT)/fur_swing_{030,060,090}.png, fur_kajiya.png," \
	     "fur_color3d_gpu.png, fur_minimal.png"
# (out/fur.obj is written by grow_fur in the existing demo recipe.)

# ---- make run ------------------------------------------------------------------
# The interactive window (needs a display).
run: $(BUILD)/gl_marschner
	@if [ -z "$$DISPLAY$$WAYLAND_DISPLAY" ]; then \
	  echo "make run: no display (DISPLAY/WAYLAND_DISPLAY unset); try" \
	       "'make gl-demo' for headless renders"; exit 1; fi
	$(BUILD)/gl_marschner
run-minimal: $(BUILD)/gl_minimal
	$(BUILD)/gl_minimal

# ---- the test, for gl-test -------------------------------------------------------
# Add $(BUILD)/gl_fur_check to GL_TESTS and this line to the gl-test recipe
# after the other checks (the recipe has already skipped, with the reason,
# when gl_check found no headless GL; gl_fur_check itself also exits 2 with
# "SKIP: reason" then):
#
#	env -u DISPLAY -u WAYLAND_DISPLAY $(BUILD)/gl_fur_check \
#	  > $(BUILD)/gl_fur_check.log 2>&1 || fail=1; \
#	  tail -n 1 $(BUILD)/gl_fur_check.log; \
#
# Standalone target, usable as it is:
.PHONY: gl-fur-check
gl-fur-check: $(BUILD)/gl_check $(BUILD)/gl_fur_check | $(OUT)
	@if ! why=$$(env -u DISPLAY -u WAYLAND_DISPLAY $(BUILD)/gl_check); then \
	  echo "gl_fur_check skipped: $$why"; exit 0; fi; \
	env -u DISPLAY -u WAYLAND_DISPLAY $(BUILD)/gl_fur_check --out-dir $(OUT)
