# The two commands a new user needs: `make demo` and `make test`. Both install what is missing,
# configure and build first. `make bench` runs the benchmarks.
BUILD ?= build
SANITIZE_BUILD ?= build-sanitize
TSAN_BUILD ?= build-tsan
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=
AVAR = $(BUILD)/apps/avar

.PHONY: all deps configure build demo test test-fast test-sanitize test-tsan bench clean

all: build

deps:
	@scripts/install-deps.sh $(EXTRA_DEPS)

configure: deps
	@cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo $(CMAKE_FLAGS) >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

demo: build
	$(AVAR) play examples/shows/hello-head.yaml --rig examples/rigs/hello-head.yaml \
	  --plot $(BUILD)/hello-head.svg --trace $(BUILD)/hello-head.csv

# Every test on the normal build, then again under AddressSanitizer + UndefinedBehaviorSanitizer,
# then under ThreadSanitizer (the simulator's host thread, signals, the serial link).
test: test-fast test-sanitize test-tsan

test-fast: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

test-sanitize: deps
	@cmake -S . -B $(SANITIZE_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Debug -DAVAR_SANITIZE=ON -DAVAR_BUILD_BENCH=OFF >/dev/null
	@cmake --build $(SANITIZE_BUILD) -j $(JOBS)
	ctest --test-dir $(SANITIZE_BUILD) --output-on-failure -j $(JOBS)

test-tsan: deps
	@cmake -S . -B $(TSAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DAVAR_TSAN=ON -DAVAR_BUILD_BENCH=OFF >/dev/null
	@cmake --build $(TSAN_BUILD) -j $(JOBS)
	ctest --test-dir $(TSAN_BUILD) --output-on-failure -j $(JOBS)

# KDL is the IK benchmark's peer; installing it before configuring lets avar-bench-ik find it.
bench: EXTRA_DEPS = liborocos-kdl-dev
bench: build
	@set -e; for b in $(BUILD)/bench/avar-bench-*; do echo "== $$b"; $$b; done

clean:
	rm -rf $(BUILD) $(SANITIZE_BUILD) $(TSAN_BUILD)
