# hairfur.h - build, test, examples.
#
#   make test      the unit tests: C99 and C++11, -O2 and ASan+UBSan,
#                  with gcc and (where installed) clang, and the scalar
#                  (HF_NO_SIMD) build; strict warnings; GL checks when
#                  EGL is present
#   make bench     per-stage speed against the memory-bandwidth limit
#   make bench-peers  hairfur ropes against Bullet soft-body ropes
#   make fuzz      libFuzzer targets (FUZZ_SECONDS each); fuzz-smoke for CI,
#                  fuzz-replay replays corpus and regressions with gcc
#   make soak      a million rope steps under random abuse
#   make valgrind  the test suite under memcheck
#   make demo      grows, swings and renders fur on the built-in head into
#                  out/ (installs or names the Debian packages it needs)
#   make run       the interactive Marschner example (needs a display)
#   make examples  build every example into build/
#   make deps      install the Debian packages the examples need (as root),
#                  or print the apt-get line
#   make clean

BUILD  := build
OUT    := out
WARN   := -Wall -Wextra -Wpedantic -Werror
SAN    := -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined \
          -fno-sanitize-recover=all
HDR    := hairfur.h
TEST   := tests/test_hairfur.c

# Debian packages for the examples (the library itself needs none).
DEPS_PKGS := build-essential clang libstb-dev libassimp-dev

CLANG   := $(shell command -v clang 2>/dev/null)
CLANGXX := $(shell command -v clang++ 2>/dev/null)

# name: compiler and flags. Each builds tests/test_hairfur.c and runs it.
TEST_gcc_c99      := gcc -std=c99 -O2
TEST_gcc_cxx11    := g++ -std=c++11 -x c++ -O2
TEST_gcc_c99_san  := gcc -std=c99 $(SAN)
TEST_gcc_cxx11_san:= g++ -std=c++11 -x c++ $(SAN)
TEST_gcc_c99_scalar := gcc -std=c99 -O2 -DHF_NO_SIMD
TEST_NAMES := gcc_c99 gcc_cxx11 gcc_c99_san gcc_cxx11_san gcc_c99_scalar
ifneq ($(CLANG),)
TEST_clang_c99      := clang -std=c99 -O2
TEST_clang_c99_san  := clang -std=c99 $(SAN)
TEST_NAMES += clang_c99 clang_c99_san
endif
ifneq ($(CLANGXX),)
TEST_clang_cxx11     := clang++ -std=c++11 -x c++ -O2
TEST_clang_cxx11_san := clang++ -std=c++11 -x c++ $(SAN)
TEST_NAMES += clang_cxx11 clang_cxx11_san
endif

TEST_BINS := $(addprefix $(BUILD)/test_,$(TEST_NAMES))

EX_CFLAGS := -std=c99 -O2 -Wall -Wextra -Wpedantic
EXAMPLES  := $(BUILD)/bake_luts $(BUILD)/grow_pictures $(BUILD)/plot_ropes \
             $(BUILD)/grow_fur

.PHONY: all test check-build demo demo-deps examples deps clean gl-test-or-skip bench valgrind

all: test

$(BUILD) $(OUT):
	mkdir -p $@

$(BUILD)/test_%: $(TEST) $(HDR) | $(BUILD)
	$(TEST_$*) $(WARN) $(TEST) -o $@ -lm

# The implementation as C++ with every override macro set; and a C
# implementation called from C++.
$(BUILD)/cpp_compile: tests/test_cpp_compile.cpp $(HDR) | $(BUILD)
	g++ -std=c++11 -O1 $(WARN) $< -o $@
$(BUILD)/link_impl.o: tests/link_impl.c $(HDR) | $(BUILD)
	gcc -std=c99 -O1 $(WARN) -c $< -o $@
$(BUILD)/link_check: tests/link_main.cpp $(BUILD)/link_impl.o $(HDR) | $(BUILD)
	g++ -std=c++11 -O1 $(WARN) $< $(BUILD)/link_impl.o -o $@ -lm

check-build: $(TEST_BINS) $(BUILD)/cpp_compile $(BUILD)/link_check

test: check-build
	@$(BUILD)/cpp_compile
	@$(BUILD)/link_check
	@fail=0; for t in $(TEST_BINS); do \
	  printf '%-28s ' "$$(basename $$t):"; \
	  $$t > $$t.log 2>&1; rc=$$?; tail -n 1 $$t.log; \
	  if [ $$rc -ne 0 ]; then fail=1; grep -v ' passed, ' $$t.log | head -n 40; fi; \
	done; \
	if [ $$fail -ne 0 ]; then echo "make test: FAILED"; exit 1; fi; \
	echo "make test: all builds passed"
	@$(MAKE) --no-print-directory gl-test-or-skip

# stb_image_write.h comes from Debian's libstb-dev (/usr/include/stb).
STB_H := /usr/include/stb/stb_image_write.h
$(STB_H):
	@echo "missing $@: run 'make deps' (Debian package libstb-dev)"; exit 1

$(BUILD)/%: examples/%.c $(HDR) $(STB_H) | $(BUILD)
	gcc $(EX_CFLAGS) $< -o $@ -lm

# grow_fur loads meshes with assimp (Debian's libassimp-dev).
$(BUILD)/grow_fur: examples/grow_fur.c examples/head_mesh.h $(HDR) $(STB_H) | $(BUILD)
	@printf '#include <assimp/cimport.h>\n' | gcc -E -x c - >/dev/null 2>&1 || \
	  { echo "grow_fur needs assimp: run 'make deps' (Debian package libassimp-dev)"; exit 1; }
	gcc $(EX_CFLAGS) $< -o $@ -lassimp -lm

examples: $(EXAMPLES) gl-examples

# The benchmark: per-stage figures against the store-loop bandwidth limit.
# BENCH_CFLAGS picks the optimisation level (a plain -O2, as users build).
BENCH_CFLAGS ?= -O2
$(BUILD)/bench: bench/bench.c examples/head_mesh.h $(HDR) | $(BUILD)
	gcc -std=c99 $(BENCH_CFLAGS) -Wall -Wextra -Wpedantic $< -o $@ -lpthread -lm

bench: $(BUILD)/bench
	$(BUILD)/bench $(BENCH_ARGS)

# The main job: grow fur on the built-in head, swing it, export the ribbons
# (out/fur.obj), bake the LUTs and render headless Marschner frames.
demo: demo-deps $(EXAMPLES) | $(OUT)
	$(BUILD)/bake_luts --out $(OUT)
	$(BUILD)/grow_pictures $(OUT)
	$(BUILD)/grow_fur --frames 120 --out $(OUT)/fur.obj
	@$(MAKE) --no-print-directory gl-demo
	@echo "demo: wrote $(OUT)/fur.obj (the swung head's fur as ribbons: opens in Blender),"
	@echo "      $(OUT)/fur_swing_030.png ... fur_swing_090.png, fur_kajiya.png,"
	@echo "      fur_color3d_gpu.png, fur_minimal.png (headless GL renders),"
	@echo "      $(OUT)/marschner_m.png, marschner_n.png, marschner_scales.txt (LUTs)"
	@echo "      and the growth pictures $(OUT)/grow_*.png"

# Make sure the Debian packages are there: install them as root, or say
# exactly what to install.
demo-deps:
	@miss=""; for p in $(DEPS_PKGS); do \
	  dpkg -s $$p >/dev/null 2>&1 || miss="$$miss $$p"; done; \
	if [ -n "$$miss" ]; then \
	  if [ "$$(id -u)" = 0 ]; then \
	    apt-get update && apt-get install -y$$miss; \
	  else \
	    echo "make demo needs:$$miss"; \
	    echo "  sudo apt-get install -y$$miss   (or: sudo make deps)"; exit 1; \
	  fi; \
	fi

# GL checks need glad, EGL and GLFW headers: without them, say what is
# missing and skip (CI installs them, so CI runs the checks).
gl-test-or-skip:
	@if command -v glad >/dev/null 2>&1 && \
	   printf '#include <EGL/egl.h>\n#include <GLFW/glfw3.h>\n#include <stb/stb_image_write.h>\n' | \
	   $(CC) -E -x c - >/dev/null 2>&1; then \
	  $(MAKE) --no-print-directory gl-test; \
	else \
	  echo "GL tests skipped: need python3-glad, libegl-dev, libglfw3-dev, libstb-dev (make deps)"; \
	fi

# The OpenGL examples and checks (GLAD at build time, EGL headless, GLFW).
GL_EXAMPLES := gl_minimal gl_marschner
include gl.mk
include glex.mk
# make bench-peers: hairfur's ropes against Bullet's (libbullet-dev).
include peers.mk
# make fuzz, fuzz-smoke, fuzz-replay, soak.
include fuzz.mk

# The test suite under valgrind's memcheck: no error, no leak.
$(BUILD)/test_valgrind: $(TEST) $(HDR) | $(BUILD)
	gcc -std=c99 -O1 -g $(WARN) $(TEST) -o $@ -lm
valgrind: $(BUILD)/test_valgrind
	@valgrind --leak-check=full --error-exitcode=1 $(BUILD)/test_valgrind \
	  > $(BUILD)/valgrind.log 2>&1; rc=$$?; \
	  grep -E "passed|ERROR SUMMARY|definitely lost|All heap blocks" $(BUILD)/valgrind.log; \
	  exit $$rc

deps:
	@if [ "$$(id -u)" = 0 ]; then \
	  apt-get update && apt-get install -y $(DEPS_PKGS); \
	else \
	  echo "Run as root, or install by hand:"; \
	  echo "  sudo apt-get install -y $(DEPS_PKGS)"; \
	fi

clean:
	rm -rf $(BUILD) $(OUT)
