# Two commands do everything on a fresh Debian machine:
#   make demo   set up, build, and run the demo
#   make test   set up, build, and run every test
# `make demo` (and make, make build, make python) installs only what building and running need
# (scripts/setup) and configures $(BUILD_DIR) without the tests and benchmark programs; `make test`,
# test-asan*, fuzz* and bench install what the tests need too (scripts/setup --test) and configure
# with them. Both use the same $(BUILD_DIR): switching reconfigures it, the library is not rebuilt.
# docs/install.md lists the packages.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)

.PHONY: all setup setup-test setup-web web web-page configure configure-test build build-test python blender-addon test test-fast asan-build test-asan test-asan-ci fuzz-build fuzz fuzz-replay demo bench clean

all: build

setup:
	@bash scripts/setup

setup-test:
	@bash scripts/setup --test

setup-web:
	@bash scripts/setup --web

CONFIGURE = cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release

# The library, CLI, viewer and Python module: no GoogleTest, Google Benchmark or assimp needed.
configure: setup
	@$(CONFIGURE) -DMYO_BUILD_TESTS=OFF -DMYO_BUILD_BENCH=OFF > /dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

# The same and the tests and benchmark programs (tests/, bench/).
configure-test: setup-test
	@$(CONFIGURE) -DMYO_BUILD_TESTS=ON -DMYO_BUILD_BENCH=ON > /dev/null

build-test: configure-test
	@cmake --build $(BUILD_DIR) -j $(JOBS)

# The web page (docs/web.md) into web/dist: the face data written by the native build
# (myoshell-web-data), the page's layers compiled to WebAssembly by emscripten in build-web, the
# page's files. Serve it with `python3 -m http.server -d web/dist`. Debian's emscripten finds
# Debian's acorn only through NODE_PATH when node comes from elsewhere (docs/web.md).
WEB_BUILD_DIR ?= build-web
WEB_ENV = NODE_PATH=$${NODE_PATH:-/usr/share/nodejs}
web: setup-web configure
	@$(MAKE) --no-print-directory web-page

# The page from $(BUILD_DIR) as it is configured (`make test` builds it after the tests' build, so
# its browser test has the page: the README's test command passes alone on a fresh machine).
web-page:
	@cmake --build $(BUILD_DIR) -j $(JOBS) --target myoshell-web-data
	@$(WEB_ENV) emcmake cmake -S web/wasm -B $(WEB_BUILD_DIR) -DCMAKE_BUILD_TYPE=Release > /dev/null
	@$(WEB_ENV) cmake --build $(WEB_BUILD_DIR) -j $(JOBS)
	@mkdir -p web/dist
	@cp web/index.html web/app.js web/favicon.svg $(WEB_BUILD_DIR)/myoshell_web.js $(WEB_BUILD_DIR)/myoshell_web.wasm web/dist/
	@$(BUILD_DIR)/bin/myoshell-web-data web/dist/face.myoweb --take scenes/demo.json

# The Python module alone, into $(BUILD_DIR)/python/myoshell (docs/python.md); `make test` runs its tests.
python: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS) --target _myoshell

# The Blender add-on's zip, $(BUILD_DIR)/myoshell-blender.zip: blender/ and the Python module built
# for the system's Python 3.11 (docs/blender.md).
blender-addon: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS) --target blender-addon

test: build-test
	@$(MAKE) --no-print-directory web-page
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

# The tests but those labelled slow (ctest -L slow: blender.ict, the Blender add-on on ICT, about
# 50 s): for a quick run while working. `make test`, which CI runs (.ci/run), runs them all once.
test-fast: build-test
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS) -LE slow

# Every test under AddressSanitizer and UndefinedBehaviorSanitizer, in its own build folder, but
# the GL and viewer tests (ctest labels gl, viewer): Mesa's llvmpipe/EGL and GLFW leak inside the
# driver (docs/RELIABILITY.md). CLI tests that render may still reach Mesa through the shared
# painter: leaks whose stack passes through the driver libraries are suppressed (.ci/lsan.supp).
ASAN_ENV = ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$(CURDIR)/.ci/lsan.supp \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ASAN_EXCLUDE = -LE '^(gl|viewer)$$'
# -O1 -g1 (line tables: stack traces keep file:line): the shell's Eigen code under ASan takes 3x as
# long to compile at -O2 -g (docs/RELIABILITY.md, "Status").
ASAN_CMAKE = cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" -DMYO_SANITIZE=ON -DMYO_BUILD_BENCH=OFF > /dev/null
asan-build: setup-test
	@$(ASAN_CMAKE)
	@cmake --build build-asan -j $(JOBS)

test-asan: asan-build
	@cd build-asan && $(ASAN_ENV) ctest --output-on-failure -j $(JOBS) $(ASAN_EXCLUDE)

# The part of test-asan that CI runs (.ci/run): the parser and I/O layers and the CLI's bad-input
# catalogue, in one ctest run. Builds only what those tests need (the catalogue is its own program,
# test_bad_inputs). Two of those tests are whole-face physics with a file at the end (the CLI's
# whole-face rig read by the glTF validator, 114 s under the sanitizers; the attachment's settle,
# 30 s): `make test` runs them, and the same writers and readers run sanitized here on smaller jobs.
ASAN_CI_TARGETS = test_core test_mesh test_anim test_io test_bad_inputs
ASAN_CI_SKIP = -E '^(GltfValidator\.CliRigGlbHasNoErrors|SceneAttachment\.AStifferAttachmentHoldsTheNamedVerticesCloserToRest)$$'
test-asan-ci: setup-test
	@$(ASAN_CMAKE)
	@cmake --build build-asan -j $(JOBS) --target $(ASAN_CI_TARGETS)
	@cd build-asan && $(ASAN_ENV) ctest --output-on-failure -j $(JOBS) -L '^(core|mesh|anim|io|bad_inputs)$$' $(ASAN_CI_SKIP)

# libFuzzer targets for the readers (fuzz/), built with clang-14 in build-fuzz: only the layers
# they parse with. `make fuzz` runs each for FUZZ_SECONDS; findings land in fuzz/findings/.
# `make fuzz-replay` (CI) replays the seed corpus (fuzz/corpus/) once through the same targets built
# in the sanitized GCC build, build-asan, with a replay main instead of libFuzzer: the layers are
# compiled once for the replay and the sanitized tests (docs/RELIABILITY.md).
FUZZ_SECONDS ?= 60
FUZZ_TARGETS = fuzz_obj fuzz_vertex_set fuzz_landmarks fuzz_scene fuzz_attachment fuzz_rig fuzz_markers fuzz_retarget_map fuzz_facs_map fuzz_performance fuzz_livelink_packet fuzz_vmc_packet fuzz_web_face
fuzz-build: setup-test
	@cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only" -DMYO_FUZZ=ON -DMYO_BUILD_TESTS=OFF -DMYO_BUILD_BENCH=OFF > /dev/null
	@cmake --build build-fuzz -j $(JOBS) --target $(FUZZ_TARGETS)

fuzz: fuzz-build
	@FUZZ_SECONDS=$(FUZZ_SECONDS) bash fuzz/run.sh

fuzz-replay: setup-test
	@$(ASAN_CMAKE)
	@cmake --build build-asan -j $(JOBS) --target $(FUZZ_TARGETS)
	@bash fuzz/replay.sh build-asan

demo: build
	@$(BUILD_DIR)/bin/myoshell demo --out out/demo

# The CLI's timing command (docs/PERFORMANCE.md), built with the benchmark programs (bench/).
bench: build-test
	@$(BUILD_DIR)/bin/myoshell bench

clean:
	rm -rf $(BUILD_DIR)
