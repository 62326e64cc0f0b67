# The two commands a new user needs: `make demo` and `make test`. Both install what is missing,
# configure and build first. `make bench` runs the benchmarks, `make fuzz FUZZ_SECONDS=N` the fuzzers,
# `make docs` builds the manual (docs/) as a site in $(BUILD)/site.
BUILD ?= build
SANITIZE_BUILD ?= build-sanitize
TSAN_BUILD ?= build-tsan
LINT_BUILD ?= build-lint
FUZZ_BUILD ?= build-fuzz
# `make fuzz`: seconds per target, and which targets (empty: all of fuzz/CMakeLists.txt).
FUZZ_SECONDS ?= 60
FUZZ_TARGETS ?=
# ... and at most this many executions each (empty: no cap).
FUZZ_RUNS ?=
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=
# The project's own trees treat warnings as errors (a plain CMake build does not: AVAR_WERROR).
WERROR = -DAVAR_WERROR=ON
BENCH ?= OFF
AVAR = $(BUILD)/apps/avar
# The avar binary whose --help the docs' command reference is generated from (`make docs` builds it).
DOCS_AVAR ?= $(AVAR)
# Line tables only (-g1): stack traces keep file:line while CI's three builds stay short.
RELEASE_FLAGS = -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG"

.PHONY: all deps configure build demo demo-talking docs docs-site test-docs lint test test-fast test-sanitize test-tsan bench fuzz package clean

all: build

deps:
	@scripts/install-deps.sh $(EXTRA_DEPS)

configure: deps
	@cmake -S . -B $(BUILD) -G Ninja $(WERROR) $(RELEASE_FLAGS) -DAVAR_BUILD_BENCH=$(BENCH) $(CMAKE_FLAGS) >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# The demo builds the avar binary and what it needs, no test suite, plays the show, then builds
# the studio's page where it can (it needs node, npm and emscripten, and npm's registry the first
# time; without them the demo has played all the same).
demo: configure
	@cmake --build $(BUILD) -j $(JOBS) --target avar
	$(AVAR) play examples/shows/hello-head.yaml --rig examples/rigs/hello-head.yaml \
	  --plot $(BUILD)/hello-head.svg --trace $(BUILD)/hello-head.csv
	@cmake --build $(BUILD) -j $(JOBS) --target avar_studio_page >/dev/null 2>&1 \
	  && echo "demo: the studio is ready: $(AVAR) studio examples/shows/hello-head.yaml --rig examples/rigs/hello-head.yaml --sim" \
	  || echo "demo: the studio's page was not built (it needs node, npm and emscripten, and npm's registry the first time)"

# The talking skull: its voice is made here with espeak-ng (a build product, not committed); the
# show's jaw follows it, its lips follow the mouth shapes of examples/shows/talking-skull.tsv.
TALKING_VOICE = examples/shows/talking-skull.wav
$(TALKING_VOICE):
	espeak-ng -s 140 -w $@ "Good evening. Welcome to my haunted house."

demo-talking: configure $(TALKING_VOICE)
	@cmake --build $(BUILD) -j $(JOBS) --target avar
	$(AVAR) play examples/shows/talking-skull.yaml --rig examples/rigs/talking-skull.yaml --plot $(BUILD)/talking-skull.svg

# Every test under AddressSanitizer + UndefinedBehaviorSanitizer, then the suites whose code runs
# threads (I/O threads and mailboxes, the simulators' pty hosts, the serial link, the studio's server, a figure's
# assembled links) under ThreadSanitizer; the limiter's tests are left out there (it runs on the
# caller's thread only, and its property family is the suite's longest test). `make test-fast` runs every test on the
# optimised build instead. The sanitizer builds use -O1, as the sanitizers' authors advise: at
# -O0 the Eigen-heavy tests ran 5x slower.
TSAN_SUITES = control sim firmware_iface inputs assembly session studio
TSAN_EXCLUDE = ^Limiter\.
test: lint test-sanitize test-docs test-tsan

# The manual as a site: the command reference generated from the avar binary's own --help into
# docs/reference/commands/ (not committed), then MkDocs in strict mode, so that a broken link or a
# page missing from mkdocs.yml's nav fails. `make docs` builds the optimised avar for it; `make test`
# uses the sanitizer tree's binary, built already, rather than a third build.
docs: configure
	@cmake --build $(BUILD) -j $(JOBS) --target avar
	@$(MAKE) --no-print-directory docs-site DOCS_AVAR=$(AVAR)

test-docs: test-sanitize
	@$(MAKE) --no-print-directory docs-site DOCS_AVAR=$(SANITIZE_BUILD)/apps/avar

docs-site: deps
	@scripts/gen-cli-reference.py $(DOCS_AVAR) docs/reference/commands mkdocs.yml
	PYTHONWARNINGS=ignore::DeprecationWarning mkdocs build --strict --site-dir $(BUILD)/site
	@echo "docs: $(BUILD)/site/index.html"

# clang-format and clang-tidy on what changed since .ci/lint-base (or LINT_BASE=<commit>). clang-tidy
# reads the compile database of a configured-only tree: the sanitizer trees compile eight files to
# a unit, so their databases name no source file.
lint: deps
	@cmake -S . -B $(LINT_BUILD) -G Ninja $(WERROR) -DCMAKE_BUILD_TYPE=Debug -DCMAKE_UNITY_BUILD=OFF -DAVAR_BUILD_TESTS=OFF \
	  -DAVAR_BUILD_BENCH=ON >/dev/null
	@LINT_BUILD=$(LINT_BUILD) scripts/lint-changed.sh $(LINT_BASE)

test-fast: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

test-sanitize: deps
	@cmake -S . -B $(SANITIZE_BUILD) -G Ninja $(WERROR) -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" -DAVAR_SANITIZE=ON \
	  -DAVAR_BUILD_BENCH=OFF >/dev/null
	@cmake --build $(SANITIZE_BUILD) -j $(JOBS)
	ctest --test-dir $(SANITIZE_BUILD) --output-on-failure -j $(JOBS)

test-tsan: deps
	@cmake -S . -B $(TSAN_BUILD) -G Ninja $(WERROR) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
	  -DAVAR_TSAN=ON -DAVAR_BUILD_BENCH=OFF -DAVAR_TEST_MODULES="$(TSAN_SUITES)" >/dev/null
	@cmake --build $(TSAN_BUILD) -j $(JOBS) --target $(patsubst %,avar_%_tests,$(TSAN_SUITES))
	ctest --test-dir $(TSAN_BUILD) --output-on-failure -j $(JOBS) -E '$(TSAN_EXCLUDE)'

# KDL is the IK benchmark's peer; installing it before configuring lets avar-bench-ik find it.
bench: EXTRA_DEPS = liborocos-kdl-dev
bench: BENCH = ON
bench: build
	@set -e; for b in $(BUILD)/bench/avar-bench-*; do echo "== $$b"; $$b; done

# Every fuzz target (fuzz/) under libFuzzer with ASan+UBSan for FUZZ_SECONDS each, one after the
# other, in a clang tree whose libraries carry the fuzzer's instrumentation; one line of execs and
# coverage per target; fails on any crash, leak or hang (inputs in $(FUZZ_BUILD)/artifacts/).
# `make test` replays the seed corpora only (CTest fuzz_replay.*). No -Werror: clang warns where GCC does not.
fuzz: deps
	@cmake -S . -B $(FUZZ_BUILD) -G Ninja -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DAVAR_LIBFUZZER=ON -DAVAR_BUILD_TESTS=OFF -DAVAR_BUILD_BENCH=OFF $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(FUZZ_BUILD) -j $(JOBS) --target avar_fuzz_all
	@FUZZ_RUNS=$(FUZZ_RUNS) scripts/fuzz.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) $(FUZZ_TARGETS)

# A Debian package of the optimised build (the avar binary, the libraries, headers and CMake
# package under /usr): $(BUILD)/avar_<version>_<arch>.deb.
package: build
	@cd $(BUILD) && cpack -G DEB
	@dpkg-deb -I $(BUILD)/avar_*.deb | sed -n '/Package:/p;/Version:/p;/Depends:/p'

clean:
	rm -rf $(BUILD) $(SANITIZE_BUILD) $(TSAN_BUILD) $(LINT_BUILD) $(FUZZ_BUILD) docs/reference/commands
