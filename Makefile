# hairfur.h - build, test, examples, benchmarks, fuzzing.
#
# make (all) is make test; make build/<name> builds one program.
#
# Tests
#   make test          the unit tests in up to 10 builds (gcc and, where
#                      installed, clang; C99 and C++11; -O2, ASan+UBSan at
#                      -O1 and -O0; the scalar HF_NO_SIMD build; GNU C with
#                      -mavx2 -mfma), the C++ compile and C/C++ link
#                      checks, the header built under another name
#                      (HF_HEADER_FILENAME), the API doc, doc and examples
#                      checks, the quick start check,
#                      the CMake and pkg-config check, then the GL checks
#                      when headless EGL is there, the WebAssembly build of
#                      the suite and the web page in headless Chromium
#                      where emscripten and chromium are installed
#   make check         the fast loop: the unit tests built once (gcc -std=c99
#                      -O2), the API doc, doc and quick start checks;
#                      T="ropes_ grid_" runs only the tests whose names
#                      begin with one of the prefixes, "test_" left out
#                      (make test too; the binaries take the prefixes,
#                      and --list)
#   make check-build   build what make test runs, without running it
#   make quickstart    the README quick start check: README.md's Quick start
#                      program built with gcc, clang and g++, run, output
#                      checked
#   make api-doc-check tests/check_api_doc.sh (docs/api.md against hairfur.h)
#                      when that script exists
#   make doc-check     README.md and docs/*.md against the code
#                      (tests/check_docs.sh): every hf_/HF_ name in
#                      hairfur.h, struct listings as declared, every C
#                      block compiled, make targets and programs named,
#                      the stack figures, links
#   make examples-check  no function of examples/ over 150 lines but the
#                      exceptions tests/check_examples.sh lists
#   make grow-fur-check  grow_fur's options as a user meets them (bad counts,
#                      --help, --guides on the built-in head); skipped, with
#                      the reason, where grow_fur cannot be built
#   make curves-check  the examples' .hair, .tfx and OBJ curve readers and
#                      writers (tests/curves_check.c; part of make test)
#   make cmake-check   the library as other builds find it: a program built
#                      with CMake's find_package (after cmake --install),
#                      add_subdirectory and FetchContent, and with
#                      pkg-config (after cmake --install and make install),
#                      under build/cmake-check/ (tests/cmake_check.sh; part
#                      of make test; skipped, saying why, without cmake)
#   make valgrind      the test suite under memcheck
#   make soak          a million rope steps under random abuse (SOAK_FRAMES)
#   make fuzz          each libFuzzer target for FUZZ_SECONDS (60) s
#   make fuzz-smoke    each target for FUZZ_SMOKE_SECONDS (20) s (CI)
#   make fuzz-replay   replay corpus and regressions with gcc (no clang)
#   make fuzz-build    build the libFuzzer targets
#   make wasm-test     the unit tests built with emscripten (WebAssembly
#                      SIMD128, -O2) and run under node (part of make
#                      test; skipped, with the reason, without emscripten)
#   make msvc-check    the header's MSVC branches, parsed by clang as MSVC
#   make cross-test    the test suite for ARM64 (qemu), Windows x64 (wine)
#                      and 32-bit x86 (qemu-i386); each skipped, saying
#                      why, without its tools (part of make test)
#
# Web (Debian's emscripten, chromium for the checks)
#   make web           the page: build/web/index.html, index.js, index.wasm
#                      (examples/web/): fur grown, simulated and expanded
#                      in WebAssembly every frame, drawn with WebGL2
#   make web-serve     serve build/web on 127.0.0.1 (WEB_PORT, default 8000)
#   make web-check     the page in headless Chromium: 60 fixed steps, no
#                      console error, not blank, and the screenshot against
#                      gl_marschner's headless render (part of make test;
#                      skipped, with the reason, without emscripten or
#                      chromium)
#   make web-bench     the page's per-stage milliseconds in headless
#                      Chromium, in real time (WEB_BENCH_FRAMES, 20;
#                      WEB_BENCH_QUERY, e.g. simd=1 for the scalar level),
#                      and a screenshot of the page (build/web-check/page.png)
#
# GL (GLAD generated at build time, headless EGL, GLFW for windows)
#   make gl-check      say whether headless EGL + GL 3.3 core works here
#   make gl-test       the GL checks (skipped, with the reason, without GL)
#   make gl-fur-check  only the fur render check (gl_fur_check)
#   make viewer-check  the viewer on meshes: errors, an animated character,
#                      metres against centimetres
#   make gl-window-test  the window path (needs a display or xvfb-run)
#   make gl-examples   build the GL examples (gl_minimal, gl_marschner)
#   make gl-demo       headless renders of the swinging head into out/
#   make characters    fur on the walking Wuson, hair on the jumping human
#                      (assimp-testmodels), headless, into out/
#   make run           the interactive Marschner example (needs a display)
#   make run-minimal   the interactive minimal GL example
#
# Examples and benchmarks
#   make demo          grow, swing and render fur on the built-in head and
#                      on animated characters into out/ (installs or names
#                      the Debian packages it needs)
#   make examples      build every example into build/
#   make bench         per-stage speed against the memory-bandwidth limit
#                      (BENCH_CFLAGS, BENCH_ARGS)
#   make bench-peers   hairfur ropes against Bullet soft-body ropes
#                      (BENCH_PEERS_ARGS)
#   make bench-ab      this hairfur.h against the one of git revision BASE
#                      (default HEAD), stage by stage, in one program
#                      (BENCH_AB_ARGS: --frames, --strands, --points, --range)
#
# Housekeeping
#   make install       hairfur.h into $(PREFIX)/include and hairfur.pc into
#                      $(PREFIX)/share/pkgconfig (PREFIX=/usr/local,
#                      DESTDIR); for CMake's find_package, install with
#                      CMakeLists.txt: cmake -B B && cmake --install B
#   make deps          install every Debian package of mk/packages.txt (as
#                      root), or print the apt-get line
#   make clean         remove build/ and out/
#   make help          print this list
#
# Steps the targets above use: demo-deps (the demo's package check),
# gl-need (GL headers present), gl-test-or-skip (make test's GL step),
# check-bullet (Bullet headers present), FORCE.
#
# Helper files in mk/ (no make fragments: this Makefile is the whole build)
#   mk/packages.txt    the Debian packages, in groups (build, examples, gl,
#                      cross, fuzz, web, peers); the one list, also read by
#                      .ci/run
#   mk/packages.sh     prints the packages of the groups it is given
#   mk/quickstart.sh   extracts README.md's quick start program and checks
#                      its output
#
# CMakeLists.txt is not the project's build: it gives other CMake builds
# the target hairfur::hairfur (find_package, add_subdirectory,
# FetchContent) and installs the header with its CMake package and
# hairfur.pc (from hairfur.pc.in, as make install does).

BUILD  := build
OUT    := out
WARN   := -Wall -Wextra -Wpedantic -Werror
SAN    := -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined \
          -fno-sanitize-recover=all
# The same sanitizers on a debug build: nothing inlined, and every stack
# page probed as it is reached (as on Windows), so a frame that outgrows a
# thread's stack faults in the suite rather than in a user's debug build.
SAN_O0 := -O0 -g -fstack-clash-protection -fsanitize=address,undefined \
          -fno-sanitize-recover=all
HDR    := hairfur.h
TEST   := tests/test_hairfur.c

CLANG   := $(shell command -v clang 2>/dev/null)
CLANGXX := $(shell command -v clang++ 2>/dev/null)

.PHONY: all test check check-build quickstart api-doc-check doc-check examples-check \
        grow-fur-check demo demo-deps \
        examples deps clean help gl-test-or-skip bench bench-ab valgrind FORCE \
        cmake-check install

all: test

$(BUILD) $(OUT):
	mkdir -p $@

# ==== Debian packages ========================================================
# One list, mk/packages.txt; mk/packages.sh prints the packages of the
# groups it is given (all of them when given none). make deps installs
# every group; make demo checks the groups the demo uses.
PACKAGES      = $(shell sh mk/packages.sh)
DEMO_PACKAGES = $(shell sh mk/packages.sh build examples gl)

# ==== Unit tests =============================================================
# name: compiler and flags. Each builds tests/test_hairfur.c and runs it.
TEST_gcc_c99      := gcc -std=c99 -O2
TEST_gcc_cxx11    := g++ -std=c++11 -x c++ -O2
TEST_gcc_c99_san  := gcc -std=c99 $(SAN)
TEST_gcc_cxx11_san_O0 := g++ -std=c++11 -x c++ $(SAN_O0)
TEST_gcc_c99_scalar := gcc -std=c99 -O2 -DHF_NO_SIMD
TEST_NAMES := gcc_c99 gcc_cxx11 gcc_c99_san gcc_cxx11_san_O0 gcc_c99_scalar
# GNU C with FMA in the target, where gcc fuses a * b + c unless the
# header's pragma stops it: every kernel must still give the scalar
# reference's bytes. Run where the CPU has AVX2 and FMA.
ifneq ($(shell grep -qw fma /proc/cpuinfo 2>/dev/null && grep -qw avx2 /proc/cpuinfo 2>/dev/null && echo y),)
TEST_gcc_gnu11_fma := gcc -std=gnu11 -O2 -mavx2 -mfma
TEST_NAMES += gcc_gnu11_fma
endif
ifneq ($(CLANG),)
TEST_clang_c99      := clang -std=c99 -O2
TEST_clang_c99_san  := clang -std=c99 $(SAN)
TEST_NAMES += clang_c99 clang_c99_san
endif
ifneq ($(CLANGXX),)
TEST_clang_cxx11     := clang++ -std=c++11 -x c++ -O2
TEST_clang_cxx11_san_O0 := clang++ -std=c++11 -x c++ $(SAN_O0)
TEST_NAMES += clang_cxx11 clang_cxx11_san_O0
endif

TEST_BINS := $(addprefix $(BUILD)/test_,$(TEST_NAMES))

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
# The implementation under another file name, which HF_HEADER_FILENAME
# gives it (it includes itself once per SIMD width of its kernel texts):
# a copy in another directory, compiled as the translation unit.
$(BUILD)/renamed/hairfur_copy.o: $(HDR) | $(BUILD)
	@mkdir -p $(BUILD)/renamed
	cp $(HDR) $(BUILD)/renamed/hairfur_copy.h
	gcc -std=c99 -O1 $(WARN) -x c -DHAIRFUR_IMPLEMENTATION \
	  -DHF_HEADER_FILENAME='"hairfur_copy.h"' \
	  -c $(BUILD)/renamed/hairfur_copy.h -o $@

# the sanitizer builds at -O1 first: they take minutes where the others
# take seconds, and make -j starts the prerequisites in this order
check-build: $(filter %clang_c99_san,$(TEST_BINS)) $(filter %_san,$(TEST_BINS)) \
             $(TEST_BINS) $(BUILD)/cpp_compile $(BUILD)/link_check \
             $(BUILD)/renamed/hairfur_copy.o

# $(1) = test binaries to run, $(2) = the target's name. Prints each
# binary's last line (N passed, N failed), and the failures. Each runs on
# a stack of TEST_STACK_KB, a small worker thread's: the header promises
# its per-frame calls about 60 KiB at most (hf_fur_simulate at -O0).
TEST_STACK_KB ?= 256
define run_tests
	@fail=0; for t in $(1); do \
	  printf '%-28s ' "$$(basename $$t):"; \
	  (ulimit -s $(TEST_STACK_KB) && exec $$t $(T)) > $$t.log 2>&1; rc=$$?; \
	  tail -n 1 $$t.log; \
	  if [ $$rc -ne 0 ]; then fail=1; grep -v ' passed, ' $$t.log | head -n 40; fi; \
	done; \
	if [ $$fail -ne 0 ]; then echo "make $(2): FAILED"; exit 1; fi; \
	echo "make $(2): all builds passed"
endef

# The suite's builds are independent: built JOBS at a time (default: the
# machine's cores), one at a time they were half of make test's time.
JOBS ?= $(shell nproc 2>/dev/null || echo 2)

test:
	@$(MAKE) --no-print-directory -j$(JOBS) check-build
	@$(BUILD)/cpp_compile
	@$(BUILD)/link_check
	$(call run_tests,$(TEST_BINS),test)
	@$(MAKE) --no-print-directory api-doc-check
	@$(MAKE) --no-print-directory doc-check
	@$(MAKE) --no-print-directory examples-check
	@$(MAKE) --no-print-directory quickstart
	@$(MAKE) --no-print-directory grow-fur-check
	@$(MAKE) --no-print-directory curves-check
	@$(MAKE) --no-print-directory cmake-check
	@$(MAKE) --no-print-directory -j2 cross-test
	@sh tests/msvc_check.sh
	@$(MAKE) --no-print-directory gl-test-or-skip
	@$(MAKE) --no-print-directory wasm-test
	@$(MAKE) --no-print-directory web-check

# The edit-compile-test loop: one build of the suite, the doc checks.
check: $(BUILD)/test_gcc_c99
	$(call run_tests,$(BUILD)/test_gcc_c99,check)
	@$(MAKE) --no-print-directory api-doc-check
	@$(MAKE) --no-print-directory doc-check
	@$(MAKE) --no-print-directory quickstart

# grow_fur as a user meets it: tests/grow_fur_check.sh builds it itself.
grow-fur-check:
	@sh tests/grow_fur_check.sh

# The examples' curve files (examples/curves.h): tests/curves_check.c with
# ASan + UBSan and assimp (without assimp, the OBJ part is left out, with a
# note), and again as 32-bit x86 without the OBJ part (its lying headers
# are the ones that wrap 32-bit sizes) where gcc -m32 builds here: run
# natively, or under qemu-i386 where the kernel runs no 32-bit programs.
.PHONY: curves-check
CURVES_CHECK_DEPS := tests/curves_check.c examples/curves.h
CURVES_ASSIMP_H    = $(wildcard /usr/include/assimp/cimport.h)
$(BUILD)/curves_check: $(CURVES_CHECK_DEPS) | $(BUILD)
	gcc -std=c99 $(SAN) $(WARN) $(if $(CURVES_ASSIMP_H),,-DCURVES_NO_ASSIMP) \
	  -Iexamples $< -o $@ $(if $(CURVES_ASSIMP_H),-lassimp) -lm
$(BUILD)/curves_check_i686: $(CURVES_CHECK_DEPS) | $(BUILD)
	gcc -m32 -std=c99 -O2 $(WARN) -DCURVES_NO_ASSIMP -Iexamples $< -o $@ -lm

curves-check: $(BUILD)/curves_check
	@$(if $(CURVES_ASSIMP_H),:,echo "curves-check: the OBJ tests skipped: install libassimp-dev (make deps)")
	@if printf 'int main(void){return 0;}\n' | \
	    gcc -m32 -x c - -o $(BUILD)/m32_run_probe >/dev/null 2>&1; then \
	  $(MAKE) --no-print-directory $(BUILD)/curves_check_i686; \
	else rm -f $(BUILD)/curves_check_i686; \
	  echo "curves-check: 32-bit build skipped: gcc -m32 cannot build" \
	    "here (libc6-dev-i386, lib32gcc-12-dev)"; fi
	$(call run_tests,$(BUILD)/curves_check,curves-check)
	@# the 32-bit build runs natively where the kernel runs 32-bit
	@# programs, else under qemu-i386
	@if [ ! -x $(BUILD)/curves_check_i686 ]; then exit 0; \
	elif $(BUILD)/m32_run_probe >/dev/null 2>&1; then run=; \
	elif command -v qemu-i386 >/dev/null 2>&1; then run=qemu-i386; \
	else echo "curves-check: 32-bit run skipped: this kernel runs no" \
	  "32-bit programs and qemu-i386 is missing (qemu-user)"; exit 0; fi; \
	printf '%-28s ' "curves_check_i686$${run:+ ($$run)}:"; \
	$$run $(BUILD)/curves_check_i686 > $(BUILD)/curves_check_i686.log 2>&1; \
	rc=$$?; tail -n 1 $(BUILD)/curves_check_i686.log; \
	if [ $$rc -ne 0 ]; then grep -v ' passed, ' $(BUILD)/curves_check_i686.log | \
	  head -n 40; echo "make curves-check: FAILED"; exit 1; fi

# The library as other builds find it (CMakeLists.txt, hairfur.pc.in,
# make install): tests/cmake_check.sh builds tests/cmake_consumer with
# CMake three ways and with pkg-config, all under build/cmake-check/.
# Skipped, with the reason, where cmake is missing.
cmake-check:
	@sh tests/cmake_check.sh

# docs/api.md against hairfur.h: the script prints the drift and fails.
# Skipped, silently, where the script is absent.
api-doc-check:
	@if [ -f tests/check_api_doc.sh ]; then sh tests/check_api_doc.sh; fi

# README.md and docs/*.md against the code (tests/check_docs.sh: names,
# struct listings, C blocks compiled into $(BUILD)/doc_blocks.c, make
# targets, stack figures, links); about 2 s.
doc-check: | $(BUILD)
	@BUILD=$(BUILD) sh tests/check_docs.sh

# Functions of examples/ a user can read in one go: at most 150 lines,
# but the exceptions the script lists by name.
examples-check:
	@sh tests/check_examples.sh

# ==== README quick start check ===============================================
# The first ```c block under "## Quick start" in README.md is a complete
# program: extracted into build/quickstart.c (with a #line directive, so
# compiler messages name README.md), built as C99 with gcc and clang (where
# installed) and as C++11 with g++, strict warnings, then run: each must
# exit 0 and print "quickstart: <V> vertices, <I> indices, mean ribbon
# width <W>" with V, I, W > 0. -O1: the flow-based warnings are on, and it
# builds in a third of -O2's time (the suite covers -O2).
# QUICKSTART_MD names another markdown file.
QUICKSTART_MD ?= README.md
QS_gcc_c99   := gcc -std=c99 -O1
QS_gxx_cxx11 := g++ -x c++ -std=c++11 -O1
QS_NAMES     := gcc_c99 gxx_cxx11
ifneq ($(CLANG),)
QS_clang_c99 := clang -std=c99 -O1
QS_NAMES     += clang_c99
endif
QS_BINS := $(addprefix $(BUILD)/quickstart_,$(QS_NAMES))

# Extracted on every run (QUICKSTART_MD may name another file), rewritten
# only when the program changed.
$(BUILD)/quickstart.c: $(QUICKSTART_MD) mk/quickstart.sh FORCE | $(BUILD)
	@sh mk/quickstart.sh extract $(QUICKSTART_MD) $@
FORCE:

$(BUILD)/quickstart_%: $(BUILD)/quickstart.c $(HDR) | $(BUILD)
	@echo "$(QS_$*) $(WARN) -I. $< -o $@ -lm"
	@$(QS_$*) $(WARN) -I. $< -o $@ -lm || { \
	  echo "make quickstart: the Quick start program of $(QUICKSTART_MD)" \
	       "($<) does not build with $(QS_$*)"; exit 1; }

quickstart: $(QS_BINS)
	@sh mk/quickstart.sh run $(QS_BINS) || { \
	  echo "make quickstart: FAILED (the program is the Quick start of" \
	       "$(QUICKSTART_MD), extracted into $(BUILD)/quickstart.c)"; exit 1; }

# ==== Other platforms ========================================================
# The test suite cross-built with the strict warnings as errors and run
# where this machine can run it: ARM64 (ISO and GNU C, where gcc fuses
# a * b + c unless the header stops it) under qemu-aarch64, Windows x64 (C
# and C++) under wine, 32-bit x86 (SSE2 math) under qemu-i386. A step whose
# tools are missing says which packages to install and is skipped; so is
# one whose emulator cannot start here (the reason is printed).
CROSS_WARN := -O2 -Wall -Wextra -Wpedantic -Werror
WINE_ENV   := WINEDEBUG=-all WINEPREFIX=$(abspath $(BUILD))/wineprefix
# Debian's wine64 package installs its loader outside PATH (the wine
# package adds /usr/bin/wine); either will do.
WINE       := $(firstword $(shell command -v wine 2>/dev/null) $(wildcard /usr/lib/wine/wine64))
.PHONY: cross-test cross-arm64 cross-win64 cross-i686 msvc-check
msvc-check:
	@sh tests/msvc_check.sh
cross-test: cross-arm64 cross-win64 cross-i686

# $(call cross_run,NAME,RUN COMMAND): run, print the summary line, and fail
# only on failed tests (an emulator that cannot start is a skip).
define cross_run
	@$(2) > $(BUILD)/$(1).log 2>&1; \
	if grep -q "passed, 0 failed" $(BUILD)/$(1).log; then \
	  printf '%-28s %s\n' "$(1):" "$$(grep 'passed, ' $(BUILD)/$(1).log | tail -n 1)"; \
	elif grep -q "passed, " $(BUILD)/$(1).log; then \
	  printf '%-28s %s\n' "$(1):" "$$(grep 'passed, ' $(BUILD)/$(1).log | tail -n 1)"; \
	  echo "cross-test: $(1) FAILED (log: $(BUILD)/$(1).log)"; exit 1; \
	else \
	  echo "cross-test: $(1) skipped: the emulator did not run it: $$(tail -n 1 $(BUILD)/$(1).log)"; \
	fi
endef

cross-arm64: | $(BUILD)
	@if ! command -v aarch64-linux-gnu-gcc >/dev/null 2>&1 || \
	    ! command -v qemu-aarch64 >/dev/null 2>&1; then \
	  echo "cross-test: ARM64 skipped: install gcc-aarch64-linux-gnu," \
	       "libc6-dev-arm64-cross, qemu-user (make deps)"; exit 0; fi; \
	aarch64-linux-gnu-gcc -std=c99 $(CROSS_WARN) tests/test_hairfur.c \
	  -o $(BUILD)/test_arm64 -lm && \
	aarch64-linux-gnu-gcc -std=gnu11 $(CROSS_WARN) tests/test_hairfur.c \
	  -o $(BUILD)/test_arm64_gnu -lm
	@if command -v qemu-aarch64 >/dev/null 2>&1 && [ -x $(BUILD)/test_arm64 ]; then :; else exit 0; fi
	$(call cross_run,test_arm64_qemu,QEMU_LD_PREFIX=/usr/aarch64-linux-gnu qemu-aarch64 $(BUILD)/test_arm64)
	@if [ -x $(BUILD)/test_arm64_gnu ]; then :; else exit 0; fi
	$(call cross_run,test_arm64_gnu_qemu,QEMU_LD_PREFIX=/usr/aarch64-linux-gnu qemu-aarch64 $(BUILD)/test_arm64_gnu)

cross-win64: | $(BUILD)
	@if ! command -v x86_64-w64-mingw32-gcc >/dev/null 2>&1 || \
	    ! command -v x86_64-w64-mingw32-g++ >/dev/null 2>&1 || \
	    [ -z "$(WINE)" ]; then \
	  echo "cross-test: Windows x64 skipped: install mingw-w64," \
	       "g++-mingw-w64-x86-64, wine64 (make deps)"; exit 0; fi; \
	x86_64-w64-mingw32-gcc -std=c99 $(CROSS_WARN) tests/test_hairfur.c \
	  -o $(BUILD)/test_win64.exe -lm && \
	x86_64-w64-mingw32-g++ -std=c++11 -x c++ $(CROSS_WARN) tests/test_hairfur.c \
	  -o $(BUILD)/test_win64_cxx.exe -lm
	@if [ -n "$(WINE)" ] && [ -f $(BUILD)/test_win64.exe ]; then :; else exit 0; fi
	$(call cross_run,test_win64_wine,$(WINE_ENV) $(WINE) $(BUILD)/test_win64.exe)
	@if [ -n "$(WINE)" ] && [ -f $(BUILD)/test_win64_cxx.exe ]; then :; else exit 0; fi
	$(call cross_run,test_win64_cxx_wine,$(WINE_ENV) $(WINE) $(BUILD)/test_win64_cxx.exe)

# 32-bit x86 with SSE2 math: with x87 math (no -mfpmath=sse) 11 tests
# fail, range splits included (x87 keeps 80-bit intermediates and rounds
# where it spills), so the header needs SSE2 floating point there.
cross-i686: | $(BUILD)
	@if ! printf '#include <stdio.h>\nint main(void){return 0;}\n' | \
	    gcc -m32 -x c - -o $(BUILD)/m32_probe >/dev/null 2>&1 || \
	    ! command -v qemu-i386 >/dev/null 2>&1; then \
	  echo "cross-test: 32-bit x86 skipped: install libc6-dev-i386," \
	       "lib32gcc-12-dev, qemu-user (make deps)"; exit 0; fi; \
	gcc -m32 -msse2 -mfpmath=sse -std=c99 $(CROSS_WARN) tests/test_hairfur.c \
	  -o $(BUILD)/test_i686 -lm
	@if command -v qemu-i386 >/dev/null 2>&1 && [ -x $(BUILD)/test_i686 ]; then :; else exit 0; fi
	$(call cross_run,test_i686_qemu,qemu-i386 $(BUILD)/test_i686)

# ==== WebAssembly ============================================================
# Debian's emscripten (3.1.6): the suite and the page with WebAssembly
# SIMD128, where -msse2 has emscripten compile the header's SSE2 kernels
# into SIMD128 (the level HF_SIMD_WASM128). Its tools run under the node
# on PATH, which finds Debian's acorn only through NODE_PATH when it is
# not Debian's own node.
EMCC      := $(shell command -v emcc 2>/dev/null)
EM_ENV    := NODE_PATH=/usr/share/nodejs$(if $(NODE_PATH),:$(NODE_PATH))
WASM_SIMD := -msimd128 -msse2
.PHONY: wasm-test web web-serve web-check web-bench
# $(call web_make,TARGETS): build them, silent when they are up to date
web_make = { $(MAKE) -q --no-print-directory $(1) 2>/dev/null || \
             $(MAKE) --no-print-directory $(1); }

# The suite, once, at -O2, as one .js file (the wasm inside: emscripten
# 3.1.6's loader tries fetch() on a file path under node 18 and later);
# the stack of the native builds (TEST_STACK_KB), every stack move checked;
# it must run at the SIMD128 level (HF_TEST_SIMD_LEVEL), and compares that
# level with the scalar references as every build does.
$(BUILD)/test_wasm.js: $(TEST) $(HDR) | $(BUILD)
	$(EM_ENV) emcc -std=c99 -O2 $(WASM_SIMD) $(WARN) \
	  -DHF_TEST_SIMD_LEVEL=HF_SIMD_WASM128 -sSINGLE_FILE=1 \
	  -sALLOW_MEMORY_GROWTH=1 -sTOTAL_STACK=$$(($(TEST_STACK_KB) * 1024)) \
	  -sSTACK_OVERFLOW_CHECK=2 $(TEST) -o $@

wasm-test:
	@if [ -z "$(EMCC)" ]; then \
	  echo "wasm-test skipped: no emcc: install emscripten (make deps)"; exit 0; fi; \
	if ! command -v node >/dev/null 2>&1; then \
	  echo "wasm-test skipped: no node to run it: install nodejs (make deps)"; exit 0; fi; \
	$(call web_make,$(BUILD)/test_wasm.js) || exit 1; \
	printf '%-28s ' "test_wasm.js (node):"; \
	node $(BUILD)/test_wasm.js > $(BUILD)/test_wasm.log 2>&1; rc=$$?; \
	tail -n 1 $(BUILD)/test_wasm.log; \
	if [ $$rc -ne 0 ]; then grep -v ' passed, ' $(BUILD)/test_wasm.log | head -n 40; \
	  echo "make wasm-test: FAILED"; exit 1; fi

# The page: examples/web/hairfur_web.c (the library, examples/head_mesh.h,
# WebGL2 through emscripten's GLES3) in examples/web/shell.html.
WEB_DIR   := $(BUILD)/web
WEB_FLAGS := -std=c99 -O2 $(WASM_SIMD) $(WARN) -Iexamples -I. \
             -sMIN_WEBGL_VERSION=2 -sMAX_WEBGL_VERSION=2 \
             -sALLOW_MEMORY_GROWTH=1 -sENVIRONMENT=web -sMINIFY_HTML=0 \
             -sEXPORTED_RUNTIME_METHODS=UTF8ToString
WEB_PORT  ?= 8000
WEB_BENCH_FRAMES ?= 20
WEB_BENCH_QUERY  ?=

$(WEB_DIR)/index.html: examples/web/hairfur_web.c examples/web/shell.html \
                       examples/head_mesh.h $(HDR) \
                       $(WEB_DIR)/hair_shading_glsl.h
	@mkdir -p $(WEB_DIR)
	$(EM_ENV) emcc $(WEB_FLAGS) -I$(WEB_DIR) \
	  --shell-file examples/web/shell.html examples/web/hairfur_web.c -o $@

# The hair's shading, examples/hair_shading.glsl (gl_marschner reads it
# at run time), as a C array for the page: hw_hair_shading_glsl, the
# file's bytes and a 0 (an array, as C99 compilers need only take 4095
# bytes a string literal).
$(WEB_DIR)/hair_shading_glsl.h: examples/hair_shading.glsl
	@mkdir -p $(WEB_DIR)
	{ echo '/* generated by make from examples/hair_shading.glsl */'; \
	  echo 'static const char hw_hair_shading_glsl[] = {'; \
	  od -An -v -tu1 $< | sed 's/[0-9][0-9]*/&,/g'; \
	  echo '0};'; } > $@.tmp && mv $@.tmp $@

web:
	@if [ -z "$(EMCC)" ]; then \
	  echo "make web: no emcc: install emscripten (make deps)"; exit 1; fi
	@$(call web_make,$(WEB_DIR)/index.html)
	@echo "web: wrote $(WEB_DIR)/index.html, index.js and index.wasm;" \
	     "serve them (make web-serve) and open the page"

web-serve: web
	@echo "web-serve: Ctrl-C stops it"
	python3 tests/web_serve.py $(WEB_DIR) $(WEB_PORT)

# The page in headless Chromium (tests/web_check.sh). gl_marschner (its
# render is the reference) where the GL packages are there.
WEB_NEED = $(if $(EMCC),,emcc (emscripten))$(shell \
  command -v chromium >/dev/null 2>&1 || echo ' chromium'; \
  command -v python3 >/dev/null 2>&1 || echo ' python3'; \
  test -f $(STB_H) || echo ' libstb-dev')
web-check:
	@if [ -n "$(strip $(WEB_NEED))" ]; then \
	  echo "web-check skipped: missing $(strip $(WEB_NEED)) (make deps)"; exit 0; fi; \
	$(call web_make,$(WEB_DIR)/index.html) && \
	  $(call web_make,$(BUILD)/png_diff) || exit 1; \
	if command -v glad >/dev/null 2>&1 && \
	   printf '#include <EGL/egl.h>\n#include <GLFW/glfw3.h>\n#include <assimp/cimport.h>\n' | \
	   $(CC) -E -x c - >/dev/null 2>&1; then \
	  $(MAKE) -s --no-print-directory $(BUILD)/gl_marschner $(BUILD)/gl_check \
	    || exit 1; fi; \
	BUILD=$(BUILD) sh tests/web_check.sh

web-bench:
	@if [ -n "$(strip $(WEB_NEED))" ]; then \
	  echo "web-bench: missing $(strip $(WEB_NEED)) (make deps)"; exit 1; fi
	@$(call web_make,$(WEB_DIR)/index.html)
	@BUILD=$(BUILD) sh tests/web_check.sh bench $(WEB_BENCH_FRAMES) "$(WEB_BENCH_QUERY)"

# ==== Examples ===============================================================
EX_CFLAGS := -std=c99 -O2 -Wall -Wextra -Wpedantic
EXAMPLES  := $(BUILD)/bake_luts $(BUILD)/grow_pictures $(BUILD)/plot_ropes \
             $(BUILD)/grow_fur $(BUILD)/paint_density $(BUILD)/make_hairstyle

# stb_image_write.h comes from Debian's libstb-dev (/usr/include/stb).
STB_H := /usr/include/stb/stb_image_write.h
$(STB_H):
	@echo "missing $@: run 'make deps' (Debian package libstb-dev)"; exit 1

$(BUILD)/%: examples/%.c $(HDR) $(STB_H) | $(BUILD)
	gcc $(EX_CFLAGS) $< -o $@ -lm

# grow_fur loads meshes with assimp (Debian's libassimp-dev), through
# examples/character.h.
$(BUILD)/grow_fur: examples/grow_fur.c examples/head_mesh.h examples/curves.h \
        examples/character.h $(HDR) $(STB_H) | $(BUILD)
	@printf '#include <assimp/cimport.h>\n' | gcc -E -x c - >/dev/null 2>&1 || \
	  { echo "grow_fur needs assimp: run 'make deps' (Debian package libassimp-dev)"; exit 1; }
	gcc $(EX_CFLAGS) $< -o $@ -lassimp -lm

# paint_density and make_hairstyle read meshes through examples/character.h
# (assimp); make_hairstyle writes curves with examples/curves.h.
$(BUILD)/paint_density $(BUILD)/make_hairstyle: $(BUILD)/%: examples/%.c \
        examples/character.h examples/curves.h $(HDR) $(STB_H) | $(BUILD)
	@printf '#include <assimp/cimport.h>\n' | gcc -E -x c - >/dev/null 2>&1 || \
	  { echo "$* needs assimp: run 'make deps' (Debian package libassimp-dev)"; exit 1; }
	gcc $(EX_CFLAGS) $< -o $@ -lassimp -lm

examples: $(EXAMPLES) gl-examples

# ==== GL: loader, flags, examples, checks ====================================
# GLAD (glad 2.x, Debian python3-glad 2.0.2): --reproducible uses the gl.xml
# packaged with glad (no network, no date in the output), so the generated
# loader is the same on every machine.
GLAD_DIR   := $(BUILD)/glad
GLAD_STAMP := $(GLAD_DIR)/.generated
GLAD_O     := $(GLAD_DIR)/gl.o
GLAD_CMD   := glad --api gl:core=3.3 --reproducible --out-path $(GLAD_DIR) c

$(GLAD_STAMP):
	@command -v glad >/dev/null 2>&1 || { \
	  echo "GL build: the 'glad' command is missing: install python3-glad" \
	       "(sudo apt-get install python3-glad, or make deps)"; exit 1; }
	@if glad --help 2>/dev/null | grep -q -- '--generator'; then \
	  echo "GL build: this glad is glad 0.1.x (--generator/--profile command" \
	       "line); the build needs glad 2.x: install python3-glad >= 2.0"; \
	  exit 1; fi
	rm -rf $(GLAD_DIR)
	$(GLAD_CMD)
	@test -f $(GLAD_DIR)/src/gl.c && test -f $(GLAD_DIR)/include/glad/gl.h
	touch $@

# Generated code: compiled once, without -Werror (it is not ours).
$(GLAD_O): $(GLAD_STAMP)
	$(CC) -std=c99 -O2 -I$(GLAD_DIR)/include -c $(GLAD_DIR)/src/gl.c -o $@

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
	         "stb/stb_image_write.h libstb-dev" \
	         "assimp/cimport.h libassimp-dev"; do \
	  set -- $$h; \
	  printf '#include <%s>\n' "$$1" | $(CC) $(GL_PC_CFLAGS) -E -x c - \
	    >/dev/null 2>&1 || miss="$$miss $$2"; \
	done; \
	if [ -n "$$miss" ]; then \
	  echo "GL build: missing headers: install$$miss (or make deps)"; exit 1; \
	fi

GL_COMMON := examples/gl_common.h

# The GL examples: $(BUILD)/<name> from examples/<name>.c. They include
# gl_common.h (one of them per program defines GLC_IMPLEMENTATION),
# hairfur.h and head_mesh.h; they get GLFW for the window mode but run
# headless without a display (headless mode never calls glfwInit).
# gl_marschner, the viewer for any mesh, also loads meshes and their
# animations with assimp (examples/character.h).
GL_EXAMPLES     := gl_minimal gl_marschner
GL_EXAMPLE_BINS := $(addprefix $(BUILD)/,$(GL_EXAMPLES))

$(BUILD)/gl_minimal: examples/gl_minimal.c $(GL_COMMON) hairfur.h \
                     examples/head_mesh.h $(GLAD_O) | gl-need $(BUILD)
	$(CC) $(GL_CFLAGS) $(WARN) $< $(GLAD_O) -o $@ $(GL_LIBS)

$(BUILD)/gl_marschner: examples/gl_marschner.c examples/character.h examples/curves.h \
                       $(GL_COMMON) hairfur.h examples/head_mesh.h $(GLAD_O) \
                       | gl-need $(BUILD)
	$(CC) $(GL_CFLAGS) $(WARN) $< $(GLAD_O) -o $@ $(GL_LIBS) -lassimp

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

# The fur render check includes examples/gl_marschner.c (with GLM_NO_MAIN).
$(BUILD)/gl_fur_check: tests/gl_fur_check.c examples/gl_marschner.c \
                       examples/character.h examples/curves.h examples/head_mesh.h $(GL_COMMON) \
                       hairfur.h $(GLAD_O) | gl-need $(BUILD)
	$(CC) $(GL_CFLAGS) $(WARN) $< $(GLAD_O) -o $@ $(GL_LIBS) -lassimp

.PHONY: gl-check gl-test gl-examples gl-window-test gl-fur-check gl-demo characters \
        viewer-check \
        run run-minimal
gl-examples: $(GL_EXAMPLE_BINS)

# Exit 0 either way: a missing GPU stack is not a build failure (the
# program prints "SKIP: <what is missing>").
gl-check: $(BUILD)/gl_check
	@$(BUILD)/gl_check || true

# GL checks need glad, EGL and GLFW headers: without them, say what is
# missing and skip (CI installs them, so CI runs the checks).
gl-test-or-skip:
	@if command -v glad >/dev/null 2>&1 && \
	   printf '#include <EGL/egl.h>\n#include <GLFW/glfw3.h>\n#include <stb/stb_image_write.h>\n#include <assimp/cimport.h>\n' | \
	   $(CC) -E -x c - >/dev/null 2>&1; then \
	  $(MAKE) --no-print-directory -j$(JOBS) gl-test; \
	else \
	  echo "GL tests skipped: need python3-glad, libegl-dev, libglfw3-dev, libstb-dev, libassimp-dev (make deps)"; \
	fi

# DISPLAY is unset so the checks prove the headless path needs no display.
# gl_check runs first; without headless GL the recipe says why and passes
# (gl_fur_check itself also exits 2 with "SKIP: reason" then).
GL_TESTS := $(BUILD)/gl_smoke $(BUILD)/gl_misc_test $(BUILD)/gl_ribbon_check \
            $(BUILD)/gl_fur_check $(BUILD)/gl_marschner $(BUILD)/png_diff \
            $(BUILD)/make_hairstyle
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
	BUILD=$(BUILD) OUT=$(OUT) sh tests/viewer_check.sh \
	  > $(BUILD)/gl_viewer_check.log 2>&1 || fail=1; \
	  tail -n 1 $(BUILD)/gl_viewer_check.log; \
	if [ $$fail -ne 0 ]; then echo "make gl-test: FAILED (logs in $(BUILD)/gl_*.log)"; exit 1; fi; \
	echo "make gl-test: all GL checks passed"

# png_diff: how much two renders differ (for tests/viewer_check.sh).
$(BUILD)/png_diff: tests/png_diff.c | $(BUILD)
	$(CC) -std=c99 -O2 -Wall -Wextra -Wpedantic $< -o $@ -lm

# The viewer as a user meets it (tests/viewer_check.sh): --help, errors,
# the walking Wuson, the same picture in metres and centimetres.
viewer-check: $(BUILD)/gl_check $(BUILD)/gl_marschner $(BUILD)/png_diff \
              $(BUILD)/make_hairstyle | $(OUT)
	@if ! why=$$(env -u DISPLAY -u WAYLAND_DISPLAY $(BUILD)/gl_check); then \
	  echo "viewer_check skipped: $$why"; exit 0; fi; \
	BUILD=$(BUILD) OUT=$(OUT) sh tests/viewer_check.sh

# The fur render check alone, writing its images into out/.
gl-fur-check: $(BUILD)/gl_check $(BUILD)/gl_fur_check | $(OUT)
	@if ! why=$$(env -u DISPLAY -u WAYLAND_DISPLAY $(BUILD)/gl_check); then \
	  echo "gl_fur_check skipped: $$why"; exit 0; fi; \
	env -u DISPLAY -u WAYLAND_DISPLAY $(BUILD)/gl_fur_check --out-dir $(OUT)

# The window path needs a display: under xvfb-run (package xvfb) when
# there is none. Not part of gl-test.
gl-window-test: $(BUILD)/gl_window_test | $(OUT)
	@if [ -n "$$DISPLAY" ]; then $(BUILD)/gl_window_test; \
	elif command -v xvfb-run >/dev/null 2>&1; then \
	  xvfb-run -a -s "-screen 0 640x480x24" $(BUILD)/gl_window_test; \
	else echo "gl-window-test skipped: no DISPLAY and no xvfb-run" \
	          "(install xvfb)"; fi

# Headless renders of the swinging head (EGL, no display needed). Run from
# the repository root: the GPU-expansion path reads
# examples/ribbon_expand.glsl. With no headless GL, say why and go on.
GLEX_RUN := env -u DISPLAY -u WAYLAND_DISPLAY $(BUILD)/gl_marschner --headless

gl-demo: $(BUILD)/gl_check $(BUILD)/gl_marschner $(BUILD)/gl_minimal | $(OUT)
	@if ! why=$$(env -u DISPLAY -u WAYLAND_DISPLAY $(BUILD)/gl_check); then \
	  echo "GL demo skipped: $$why"; exit 0; fi; \
	set -e; \
	$(GLEX_RUN) --frames 90 --save-every 30 --out $(OUT)/fur_swing_%03d.png; \
	$(GLEX_RUN) --frames 90  --kajiya --out $(OUT)/fur_kajiya.png; \
	$(GLEX_RUN) --frames 90  --gpu-expand --color3d --out $(OUT)/fur_color3d_gpu.png; \
	env -u DISPLAY -u WAYLAND_DISPLAY $(BUILD)/gl_minimal --headless \
	  --frames 60 --out $(OUT)/fur_minimal.png; \
	echo "gl-demo: wrote $(OUT)/fur_swing_{030,060,090}.png, fur_kajiya.png," \
	     "fur_color3d_gpu.png, fur_minimal.png"

# Fur and hair on real characters: Debian's assimp-testmodels creatures,
# skinned and animated on the CPU (examples/character.h), capsules on their
# bones, self-shadowed. The Wuson walks with fur; the human jumps with hair
# on its Head mesh, on a scalp painted by paint_density (a plane through
# the hairline, from the forehead down to the nape). Frames go to
# out/fur_wuson_NNN.png and out/hair_human_NNN.png, a still of each to
# out/fur_wuson.png and out/hair_human.png. Then an authored hairstyle:
# curves made by make_hairstyle, saved as .hair and read back as the
# guides of the human's hair (out/hair_styled.png).
MODELS   := /usr/share/assimp/models/X
WUSON    := $(MODELS)/Testwuson.X
HUMAN    := $(MODELS)/BCN_Epileptic.X
CHAR_RUN := env -u DISPLAY -u WAYLAND_DISPLAY $(BUILD)/gl_marschner --headless --orbit 0

characters: $(BUILD)/gl_check $(BUILD)/gl_marschner $(BUILD)/paint_density \
            $(BUILD)/make_hairstyle | $(OUT)
	@if ! why=$$(env -u DISPLAY -u WAYLAND_DISPLAY $(BUILD)/gl_check); then \
	  echo "characters skipped: $$why"; exit 0; fi; \
	if [ ! -f $(WUSON) ] || [ ! -f $(HUMAN) ]; then \
	  echo "characters: $(MODELS) has no Testwuson.X / BCN_Epileptic.X:" \
	       "install the Debian package assimp-testmodels (make deps)"; exit 1; fi; \
	set -e; \
	$(CHAR_RUN) --mesh $(WUSON) --anim Wuson_Walk --hair-length 0.08 \
	  --comb 0,-0.6,-1 --stiffness 0.4 --hair-color 0.62,0.48,0.33 \
	  --settle 0.5 --frames 120 --save-every 12 --out $(OUT)/fur_wuson_%03d.png; \
	cp $(OUT)/fur_wuson_120.png $(OUT)/fur_wuson.png; \
	$(BUILD)/paint_density --mesh $(HUMAN) --part Head \
	  --plane 0,1,-0.53,0.717 --out $(OUT)/hair_human_scalp.png; \
	$(BUILD)/paint_density --mesh $(HUMAN) --part Head \
	  --plane 0,0,-1,0.045 --soft 0.05 --out $(OUT)/hair_human_length.png; \
	$(CHAR_RUN) --mesh $(HUMAN) --grow-on Head --density $(OUT)/hair_human_scalp.png \
	  --length $(OUT)/hair_human_length.png --hair-length 0.25 \
	  --comb 0,-0.5,-3 --stiffness 0.3 --rest-from-gravity 1.5 \
	  --frames 198 --save-every 18 --out $(OUT)/hair_human_%03d.png; \
	cp $(OUT)/hair_human_090.png $(OUT)/hair_human.png; \
	$(CHAR_RUN) --mesh $(HUMAN) --grow-on Head --density $(OUT)/hair_human_scalp.png \
	  --length $(OUT)/hair_human_length.png --hair-length 0.25 \
	  --comb 0,-0.5,-3 --stiffness 0.3 --rest-from-gravity 1.5 \
	  --volume 0 --friction 0 --frames 90 --out $(OUT)/hair_human_flat.png; \
	$(BUILD)/make_hairstyle --mesh $(HUMAN) --part Head \
	  --plane 0,1,-0.53,0.717 --out $(OUT)/hair_styled.hair; \
	$(CHAR_RUN) --mesh $(HUMAN) --grow-on Head --density $(OUT)/hair_human_scalp.png \
	  --guides $(OUT)/hair_styled.hair --stiffness 0.3 --color-variation 0.25 \
	  --settle 1 --frames 60 --still --out $(OUT)/hair_styled.png; \
	echo "characters: wrote $(OUT)/fur_wuson_012.png ... fur_wuson_120.png," \
	     "fur_wuson.png, hair_human_018.png ... hair_human_198.png," \
	     "hair_human.png, hair_human_flat.png (no hair-hair interaction)," \
	     "hair_styled.hair (authored curves), hair_styled.png"

# The interactive windows (need a display).
run: $(BUILD)/gl_marschner
	@if [ -z "$$DISPLAY$$WAYLAND_DISPLAY" ]; then \
	  echo "make run: no display (DISPLAY/WAYLAND_DISPLAY unset); try" \
	       "'make gl-demo' for headless renders"; exit 1; fi
	$(BUILD)/gl_marschner
run-minimal: $(BUILD)/gl_minimal
	$(BUILD)/gl_minimal

# ==== Demo ===================================================================
# Grow fur on the built-in head, swing it, export the ribbons (out/fur.obj),
# bake the LUTs and render headless Marschner frames.
demo: demo-deps $(EXAMPLES) | $(OUT)
	$(BUILD)/bake_luts --out $(OUT)
	$(BUILD)/grow_pictures $(OUT)
	$(BUILD)/grow_fur --frames 120 --out $(OUT)/fur.obj
	@$(MAKE) --no-print-directory gl-demo
	@$(MAKE) --no-print-directory characters
	@echo "demo: wrote $(OUT)/fur.obj (the swung head's fur as ribbons: opens in Blender),"
	@echo "      $(OUT)/fur_swing_030.png ... fur_swing_090.png, fur_kajiya.png,"
	@echo "      fur_color3d_gpu.png, fur_minimal.png (headless GL renders),"
	@echo "      $(OUT)/fur_wuson.png, hair_human.png and their frames (animated"
	@echo "      characters from assimp-testmodels), hair_styled.png (an authored"
	@echo "      hairstyle, out/hair_styled.hair),"
	@echo "      $(OUT)/marschner_m.png, marschner_n.png, marschner_scales.txt (LUTs)"
	@echo "      and the growth pictures $(OUT)/grow_*.png"

# Make sure the Debian packages of the demo are there (groups build,
# examples and gl of mk/packages.txt): install them as root, or say exactly
# what to install.
demo-deps:
	@miss=""; for p in $(DEMO_PACKAGES); do \
	  dpkg -s $$p >/dev/null 2>&1 || miss="$$miss $$p"; done; \
	if [ -n "$$miss" ]; then \
	  if [ "$$(id -u)" = 0 ]; then \
	    apt-get update && apt-get install -y$$miss; \
	  else \
	    echo "make demo needs:$$miss"; \
	    echo "  sudo apt-get install -y$$miss   (or: sudo make deps)"; exit 1; \
	  fi; \
	fi

# ==== Benchmarks =============================================================
# The benchmark: per-stage figures against the store-loop bandwidth limit.
# BENCH_CFLAGS picks the optimisation level (a plain -O2, as users build).
BENCH_CFLAGS ?= -O2
$(BUILD)/bench: bench/bench.c bench/bench_fur.h bench/bench_time.h examples/head_mesh.h \
    $(HDR) | $(BUILD)
	gcc -std=c99 $(BENCH_CFLAGS) -Wall -Wextra -Wpedantic $< -o $@ -lpthread -lm

bench: $(BUILD)/bench
	$(BUILD)/bench $(BENCH_ARGS)

# Two versions of the header in one program (bench/bench_ab.c): each stage
# on scene L, the hairfur.h of git revision BASE (default HEAD; WORKTREE:
# the working tree's own, to see the method's noise) against the working
# tree's, call by call. Both built with BENCH_CFLAGS. The base copy is
# named hairfur_base.h, which HF_HEADER_FILENAME tells it (the header
# includes itself by its name).
BASE ?= HEAD
BENCH_AB_ARGS ?=
AB_CC := gcc -std=c99 $(BENCH_CFLAGS) -Wall -Wextra -Wpedantic
bench-ab: bench/bench_ab.c bench/ab_side.c bench/bench_ab.h bench/bench_fur.h \
    bench/bench_time.h \
    examples/head_mesh.h $(HDR) | $(BUILD)
	@mkdir -p $(BUILD)/ab
	@if [ "$(BASE)" = WORKTREE ]; then cp $(HDR) $(BUILD)/ab/hairfur_base.h; \
	elif ! git show "$(BASE):hairfur.h" > $(BUILD)/ab/hairfur_base.h; then \
	  echo "bench-ab: no hairfur.h at revision '$(BASE)' (BASE=REV or WORKTREE)"; \
	  exit 1; fi
	$(AB_CC) -I$(BUILD)/ab -DAB_HEADER='"hairfur_base.h"' -DAB_SIDE=ab_base \
	  -DHF_HEADER_FILENAME='"hairfur_base.h"' \
	  -c bench/ab_side.c -o $(BUILD)/ab/base.o
	$(AB_CC) -I. -DAB_HEADER='"hairfur.h"' -DAB_SIDE=ab_new \
	  -c bench/ab_side.c -o $(BUILD)/ab/new.o
	$(AB_CC) bench/bench_ab.c $(BUILD)/ab/base.o $(BUILD)/ab/new.o \
	  -o $(BUILD)/bench_ab -lm
	$(BUILD)/bench_ab $(BENCH_AB_ARGS)

# Against other libraries: hairfur.h ropes against Bullet soft-body ropes
# (367, 1,000, 5,000 ropes); prints a table and `bench ...` lines. Needs
# Debian's libbullet-dev (group peers of mk/packages.txt).
BULLET_H      := /usr/include/bullet/btBulletDynamicsCommon.h
BULLET_CFLAGS := $(shell pkg-config --cflags bullet 2>/dev/null || echo -I/usr/include/bullet)
BULLET_LIBS   := $(shell pkg-config --libs bullet 2>/dev/null || \
                   echo -lBulletSoftBody -lBulletDynamics -lBulletCollision -lLinearMath)
BENCH_PEERS_ARGS ?=

.PHONY: bench-peers check-bullet

check-bullet:
	@test -f $(BULLET_H) || { echo "bench-peers: Bullet headers missing ($(BULLET_H)): install libbullet-dev (make deps)"; exit 1; }

$(BUILD)/bench_peers: bench/bench_peers.cpp $(HDR) | check-bullet
	@mkdir -p $(BUILD)
	g++ -O2 -std=c++11 -I. $(BULLET_CFLAGS) $< -o $@ $(BULLET_LIBS) -lm

bench-peers: check-bullet $(BUILD)/bench_peers
	@echo "machine: $$(nproc) cores, $$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //')"
	$(BUILD)/bench_peers $(BENCH_PEERS_ARGS)

# ==== Fuzzing and soak =======================================================
# libFuzzer targets built with Debian's clang (ASan + UBSan); fuzz prints
# executions, exec/s and coverage per target. The repository corpus
# (tests/fuzz/corpus/<target>/) is only read: each run's new inputs go to
# $(BUILD)/fuzz-corpus/<target>/, which persists between runs; crashes go to
# $(BUILD)/fuzz-artifacts/. To grow the seed corpus, use libFuzzer's merge
# mode: build/fuzz_<t> -merge=1 tests/fuzz/corpus/<t> build/fuzz-corpus/<t>.
# fuzz-replay builds each target with gcc and tests/fuzz/fuzz_main.c
# instead, and replays the seed corpus and tests/fuzz/regressions/.
FUZZ_TARGETS       := grow ropes ribbons lut fur curves obj
FUZZ_SECONDS       ?= 60
FUZZ_SMOKE_SECONDS ?= 20
FUZZ_DIR           := tests/fuzz
FUZZ_FLAGS         := -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
                      -print_final_stats=1
FUZZ_SAN    := -fsanitize=address,undefined -fno-sanitize-recover=all
FUZZ_CLANG  := $(if $(CLANG),$(CLANG),clang) -std=c99 -g -O1
FUZZ_CC     := $(FUZZ_CLANG) -fsanitize=fuzzer $(FUZZ_SAN)
REPLAY_CC   := gcc -std=c99 -O1 -g -Wall -Wextra -Wpedantic -Werror $(FUZZ_SAN)
FUZZ_DEPS   := $(FUZZ_DIR)/fuzz_common.h $(HDR)
# leaks inside assimp itself are not ours (see the file)
FUZZ_ENV    := LSAN_OPTIONS=suppressions=$(abspath $(FUZZ_DIR)/lsan.supp)

.PHONY: fuzz fuzz-smoke fuzz-replay fuzz-build soak

$(BUILD)/fuzz_%: $(FUZZ_DIR)/fuzz_%.c $(FUZZ_DEPS) | $(BUILD)
	$(FUZZ_CC) $< $(filter %.o,$^) -o $@ -lm

$(BUILD)/replay_%: $(FUZZ_DIR)/fuzz_%.c $(FUZZ_DIR)/fuzz_main.c $(FUZZ_DEPS) | $(BUILD)
	$(REPLAY_CC) $(FUZZ_DIR)/fuzz_main.c $< $(filter %.o,$^) -o $@ -lm

# The library's targets link its implementation (fuzz_impl.c), compiled
# once for them all (with the fuzzer's coverage, not its main): each
# compiling it again took most of the fuzz build's time. fuzz_ropes
# compiles its own: it reads the ropes' internal layout.
FUZZ_LIB := grow ribbons lut fur
$(BUILD)/fuzz_impl.o: $(FUZZ_DIR)/fuzz_impl.c $(HDR) | $(BUILD)
	$(FUZZ_CLANG) -fsanitize=fuzzer-no-link $(FUZZ_SAN) -c $< -o $@
$(BUILD)/replay_impl.o: $(FUZZ_DIR)/fuzz_impl.c $(HDR) | $(BUILD)
	$(REPLAY_CC) -c $< -o $@
$(addprefix $(BUILD)/fuzz_,$(FUZZ_LIB)): $(BUILD)/fuzz_impl.o
$(addprefix $(BUILD)/replay_,$(FUZZ_LIB)): $(BUILD)/replay_impl.o

# fuzz_curves reads the examples' curve files (examples/curves.h).
$(BUILD)/fuzz_curves $(BUILD)/replay_curves: examples/curves.h \
    $(FUZZ_DIR)/fuzz_curves_contract.h
# fuzz_obj reads OBJ polylines with the same header, through assimp
# (Debian's libassimp-dev).
$(BUILD)/fuzz_obj: $(FUZZ_DIR)/fuzz_obj.c examples/curves.h \
    $(FUZZ_DIR)/fuzz_curves_contract.h | $(BUILD)
	$(FUZZ_CC) $< -o $@ -lassimp -lm
$(BUILD)/replay_obj: $(FUZZ_DIR)/fuzz_obj.c $(FUZZ_DIR)/fuzz_main.c examples/curves.h \
    $(FUZZ_DIR)/fuzz_curves_contract.h | $(BUILD)
	$(REPLAY_CC) $(FUZZ_DIR)/fuzz_main.c $< -o $@ -lassimp -lm

fuzz-build: $(addprefix $(BUILD)/fuzz_,$(FUZZ_TARGETS))

# $(1) = seconds per target; JOBS targets at a time, each on a core of its
# own, then their lines in the order of FUZZ_TARGETS
define fuzz_run
	@command -v $(if $(CLANG),$(CLANG),clang) >/dev/null 2>&1 || \
	  { echo "make fuzz needs clang with libFuzzer (Debian: clang, libclang-rt-14-dev)"; exit 1; }
	@mkdir -p $(BUILD)/fuzz-artifacts
	@rm -f $(BUILD)/fuzz-*.rc; i=0; for t in $(FUZZ_TARGETS); do \
	  mkdir -p $(BUILD)/fuzz-corpus/$$t; \
	  ( $(FUZZ_ENV) $(BUILD)/fuzz_$$t $(FUZZ_FLAGS) -max_total_time=$(1) \
	    -artifact_prefix=$(BUILD)/fuzz-artifacts/$$t- \
	    $(BUILD)/fuzz-corpus/$$t $(FUZZ_DIR)/corpus/$$t \
	    > $(BUILD)/fuzz-$$t.log 2>&1; echo $$? > $(BUILD)/fuzz-$$t.rc ) & \
	  i=$$((i + 1)); if [ $$((i % $(JOBS))) -eq 0 ]; then wait; fi; \
	done; wait; \
	fail=0; for t in $(FUZZ_TARGETS); do \
	  log=$(BUILD)/fuzz-$$t.log; \
	  rc=$$(cat $(BUILD)/fuzz-$$t.rc 2>/dev/null || echo 1); \
	  done_line=$$(grep -E '^#[0-9]+[[:space:]]+DONE' $$log | tail -n 1); \
	  printf '%-8s %s\n' "$$t:" "$${done_line:-(no DONE line: see $$log)}"; \
	  if [ $$rc -ne 0 ]; then fail=1; \
	    grep -E 'contract violated|runtime error|ERROR: |Test unit written' $$log | head -n 5; fi; \
	done; \
	if [ $$fail -ne 0 ]; then echo "fuzz: FOUND SOMETHING (inputs in $(BUILD)/fuzz-artifacts/)"; exit 1; fi; \
	echo "fuzz: $(words $(FUZZ_TARGETS)) targets x $(1) s, nothing found"
endef

fuzz: fuzz-build
	$(call fuzz_run,$(FUZZ_SECONDS))

fuzz-smoke:
	@$(MAKE) --no-print-directory -j$(JOBS) fuzz-build
	$(call fuzz_run,$(FUZZ_SMOKE_SECONDS))

fuzz-replay: $(addprefix $(BUILD)/replay_,$(FUZZ_TARGETS))
	@fail=0; for t in $(FUZZ_TARGETS); do \
	  regs=$$(ls $(FUZZ_DIR)/regressions/$$t-* 2>/dev/null); \
	  printf '%-8s ' "$$t:"; \
	  $(FUZZ_ENV) $(BUILD)/replay_$$t $(FUZZ_DIR)/corpus/$$t $$regs || fail=1; \
	done; \
	if [ $$fail -ne 0 ]; then echo "fuzz-replay: FAILED"; exit 1; fi

# tests/soak.c: a million rope steps under abuse.
$(BUILD)/soak: tests/soak.c $(HDR) | $(BUILD)
	gcc -std=c99 -O2 $(WARN) $< -o $@ -lm

soak: $(BUILD)/soak
	$(BUILD)/soak $(SOAK_FRAMES)

# ==== valgrind ===============================================================
# The test suite under valgrind's memcheck: no error, no leak.
$(BUILD)/test_valgrind: $(TEST) $(HDR) | $(BUILD)
	gcc -std=c99 -O1 -g $(WARN) $(TEST) -o $@ -lm
valgrind: $(BUILD)/test_valgrind
	@valgrind --leak-check=full --error-exitcode=1 $(BUILD)/test_valgrind \
	  > $(BUILD)/valgrind.log 2>&1; rc=$$?; \
	  grep -E "passed|ERROR SUMMARY|definitely lost|All heap blocks" $(BUILD)/valgrind.log; \
	  exit $$rc

# ==== Housekeeping ===========================================================
# Every package of mk/packages.txt: installed as root, else the line to run.
deps:
	@if [ "$$(id -u)" = 0 ]; then \
	  apt-get update && apt-get install -y $(PACKAGES); \
	else \
	  echo "Run as root, or install by hand:"; \
	  echo "  sudo apt-get install -y $(PACKAGES)"; \
	fi

clean:
	rm -rf $(BUILD) $(OUT)

# The header and hairfur.pc (hairfur.pc.in, as CMakeLists.txt writes it,
# naming PREFIX made absolute) under $(DESTDIR)$(PREFIX). The CMake
# package (find_package) comes with cmake --install.
PREFIX  ?= /usr/local
HAIRFUR_VERSION = $(shell sed -n 's/^\#define HAIRFUR_VERSION_STRING "\([0-9.]*\)"$$/\1/p' $(HDR))
install: $(HDR) hairfur.pc.in
	@test -n "$(HAIRFUR_VERSION)" || { echo "make install: no HAIRFUR_VERSION_STRING in $(HDR)"; exit 1; }
	install -d $(DESTDIR)$(abspath $(PREFIX))/include \
	  $(DESTDIR)$(abspath $(PREFIX))/share/pkgconfig
	install -m 644 $(HDR) $(DESTDIR)$(abspath $(PREFIX))/include/hairfur.h
	sed -e 's|@HAIRFUR_PC_PREFIX@|$(abspath $(PREFIX))|' \
	    -e 's|@HAIRFUR_PC_INCLUDEDIR@|$${prefix}/include|' \
	    -e 's|@HAIRFUR_VERSION@|$(HAIRFUR_VERSION)|' hairfur.pc.in \
	  > $(DESTDIR)$(abspath $(PREFIX))/share/pkgconfig/hairfur.pc
	@echo "make install: hairfur.h $(HAIRFUR_VERSION) and hairfur.pc under $(DESTDIR)$(abspath $(PREFIX))"

# The comment block at the top of this file.
help:
	@sed -n '1,/^$$/{/^#/s/^# \{0,1\}//p;}' Makefile
