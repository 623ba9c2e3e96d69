# fuzz.mk - fuzzing and soak targets; `include fuzz.mk` from the Makefile
# (after BUILD, HDR and CLANG are defined).
#
#   make fuzz         each libFuzzer target for FUZZ_SECONDS (default 60) s
#                     with Debian's clang (ASan + UBSan); prints executions,
#                     exec/s and coverage per target
#   make fuzz-smoke   CI: every target FUZZ_SMOKE_SECONDS (20) s, ~80 s total
#   make fuzz-replay  gcc + tests/fuzz/fuzz_main.c over the seed corpus and
#                     tests/fuzz/regressions/ (no clang needed)
#   make soak         tests/soak.c: a million rope steps under abuse
#
# The repository corpus (tests/fuzz/corpus/<target>/) is only read: each
# run's new inputs go to $(BUILD)/fuzz-corpus/<target>/, which persists
# between runs; crashes go to $(BUILD)/fuzz-artifacts/. To grow the seed
# corpus, merge by hand: fuzz_<t> -merge=1 tests/fuzz/corpus/<t> build/fuzz-corpus/<t>.

FUZZ_TARGETS       := grow ropes ribbons lut
FUZZ_SECONDS       ?= 60
FUZZ_SMOKE_SECONDS ?= 20
FUZZ_DIR           := tests/fuzz
FUZZ_FLAGS         := -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
                      -print_final_stats=1
FUZZ_CC     := $(if $(CLANG),$(CLANG),clang) -std=c99 -g -O1 \
               -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all
REPLAY_CC   := gcc -std=c99 -O1 -g -Wall -Wextra -Wpedantic -Werror \
               -fsanitize=address,undefined -fno-sanitize-recover=all
FUZZ_DEPS   := $(FUZZ_DIR)/fuzz_common.h $(HDR)

.PHONY: fuzz fuzz-smoke fuzz-replay fuzz-build soak

$(BUILD)/fuzz_%: $(FUZZ_DIR)/fuzz_%.c $(FUZZ_DEPS) | $(BUILD)
	$(FUZZ_CC) $< -o $@ -lm

$(BUILD)/replay_%: $(FUZZ_DIR)/fuzz_%.c $(FUZZ_DIR)/fuzz_main.c $(FUZZ_DEPS) | $(BUILD)
	$(REPLAY_CC) $(FUZZ_DIR)/fuzz_main.c $< -o $@ -lm

fuzz-build: $(addprefix $(BUILD)/fuzz_,$(FUZZ_TARGETS))

# $(1) = seconds per target
define fuzz_run
	@command -v $(if $(CLANG),$(CLANG),clang) >/dev/null 2>&1 || \
	  { echo "make fuzz needs clang with libFuzzer (Debian: clang, libclang-rt-14-dev)"; exit 1; }
	@mkdir -p $(BUILD)/fuzz-artifacts
	@fail=0; for t in $(FUZZ_TARGETS); do \
	  mkdir -p $(BUILD)/fuzz-corpus/$$t; \
	  log=$(BUILD)/fuzz-$$t.log; \
	  $(BUILD)/fuzz_$$t $(FUZZ_FLAGS) -max_total_time=$(1) \
	    -artifact_prefix=$(BUILD)/fuzz-artifacts/$$t- \
	    $(BUILD)/fuzz-corpus/$$t $(FUZZ_DIR)/corpus/$$t > $$log 2>&1; rc=$$?; \
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

fuzz-smoke: fuzz-build
	$(call fuzz_run,$(FUZZ_SMOKE_SECONDS))

fuzz-replay: $(addprefix $(BUILD)/replay_,$(FUZZ_TARGETS))
	@fail=0; for t in $(FUZZ_TARGETS); do \
	  regs=$$(ls $(FUZZ_DIR)/regressions/$$t-* 2>/dev/null); \
	  printf '%-8s ' "$$t:"; \
	  $(BUILD)/replay_$$t $(FUZZ_DIR)/corpus/$$t $$regs || fail=1; \
	done; \
	if [ $$fail -ne 0 ]; then echo "fuzz-replay: FAILED"; exit 1; fi

$(BUILD)/soak: tests/soak.c $(HDR) | $(BUILD)
	gcc -std=c99 -O2 $(WARN) $< -o $@ -lm

soak: $(BUILD)/soak
	$(BUILD)/soak $(SOAK_FRAMES)
