# mk/bench.mk - the benchmark suite: celscan against cairo, FreeType and AGG.
#
#   make bench         generate the scenes, run every section, write bench/results/*.txt
#                      and regenerate the tables of BENCHMARKS.md (under a minute)
#   make bench-smoke   the bench binary on one small scene, one run (part of `make test`)
#   make bench-scenes  redraw scenes/bench/*.json from bench/gen_scenes.py
#
# BENCH_ARGS adds options to the main run (e.g. BENCH_ARGS="--repeat 3").
# The bench binary links the core library, the scene loader, the test
# suite's reference (tests/ref, for accuracy), cairo, FreeType and AGG.

BENCH_PKGS := cairo freetype2 libcjson libagg
BENCH_SRC := bench/bench.c bench/outline.c bench/peer_cairo.c bench/peer_ft.c bench/anim.c \
        bench/accuracy.c host-sim/scene_json.c host-sim/paint_json.c host-sim/bands.c tests/ref/ref.c \
        tools/cli_num.c
# AGG is C++: its peer alone is compiled as C++ (the program links with $(CXX)).
BENCH_CXX_SRC := bench/peer_agg.cpp
BENCH_OBJ := $(patsubst %.c,$(HOST)/bench-obj/%.o,$(BENCH_SRC)) \
        $(patsubst %.cpp,$(HOST)/bench-obj/%.o,$(BENCH_CXX_SRC))
BENCH_BIN := $(HOST)/bench
BENCH_SCENES := scenes/bench/blobs.json scenes/bench/thin.json scenes/bench/rational.json \
        scenes/bench/anim.json
BENCH_RESULTS := bench/results
BENCH_ARGS ?=

$(eval $(call flags_record,bench-obj,$(CC) $(HOST_CFLAGS) $(shell pkg-config --cflags $(BENCH_PKGS))))
$(HOST)/bench-obj/%.o: %.c $(FLAGS_DIR)/bench-obj
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(HOST_CFLAGS) -Itests -Ibench $(shell pkg-config --cflags $(BENCH_PKGS)) -c $< -o $@

BENCH_CXXFLAGS = -std=c++11 $(OPT) -g $(FP_FLAGS) -Wall -Wextra -MMD -MP -Ibench \
        $(shell pkg-config --cflags libagg)
$(eval $(call flags_record,bench-cxx,$(CXX) $(BENCH_CXXFLAGS)))
$(HOST)/bench-obj/%.o: %.cpp $(FLAGS_DIR)/bench-cxx
	@mkdir -p $(dir $@)
	$(Q)$(CXX) $(BENCH_CXXFLAGS) -c $< -o $@

$(BENCH_BIN): $(BENCH_OBJ) $(HOST)/libcelscan_host.a
	$(Q)$(CXX) -o $@ $(BENCH_OBJ) $(HOST)/libcelscan_host.a $(shell pkg-config --libs $(BENCH_PKGS)) -lm -pthread

# The scenes are committed, so that every checkout measures the same bytes
# (a Python with another random module could draw them differently);
# `make bench-scenes` redraws them after bench/gen_scenes.py changes.
.PHONY: bench-scenes
bench-scenes:
	$(Q)python3 bench/gen_scenes.py scenes/bench

HOST_PROGRAMS += $(BENCH_BIN)

.PHONY: bench bench-smoke
bench: $(BENCH_BIN) $(BENCH_SCENES) $(HOST)/celsim
	@mkdir -p $(BENCH_RESULTS) $(BUILD)/bench
	$(Q)tools/bench_run.sh $(BENCH_BIN) $(HOST)/celsim $(BENCH_RESULTS) $(BUILD)/bench $(BENCH_ARGS)
	$(Q)python3 tools/bench_md.py $(BENCH_RESULTS) BENCHMARKS.md

# So that the benchmark does not rot: outline conversion checked against
# tests/ref, and every section once on a small frame.
bench-smoke: $(BENCH_BIN) $(BENCH_SCENES)
	$(Q)$(BENCH_BIN) --selftest
	$(Q)$(BENCH_BIN) --quick --size 480x272 --scenes signage,anim >/dev/null && \
		echo "bench-smoke: 1 passed, 0 failed"

TEST_TARGETS += bench-smoke
