# peers.mk - benchmarks against other libraries (peers). Needs Debian's
# libbullet-dev for the Bullet soft-body ropes.
#
# Meant to be included by the top-level Makefile after BUILD and DEPS_PKGS
# are set (include peers.mk), or run alone: make -f peers.mk bench-peers
#
#   make bench-peers   build bench/bench_peers.cpp and run it: hairfur.h
#                      ropes against Bullet soft-body ropes (367, 1,000,
#                      5,000 ropes); prints a table and `bench ...` lines

BUILD ?= build
HDR   ?= hairfur.h

# Debian package for the peers (headers, libs and bullet.pc).
PEERS_DEPS_PKGS := libbullet-dev pkg-config
DEPS_PKGS += $(filter-out $(DEPS_PKGS),$(PEERS_DEPS_PKGS))

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
