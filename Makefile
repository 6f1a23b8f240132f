# Two commands do all set-up on a fresh Debian 12 machine:
#   make render   installs missing packages, builds, renders scenes/cornell-box.gltf
#   make test     same set-up, then every test (ctest) on lavapipe
#   make fuzz     the libFuzzer targets, FUZZ_SECONDS each (scripts/fuzz.sh)
#   make test-sanitize  every test with ASan and UBSan (scripts/test_sanitize.sh)
BUILD ?= build
JOBS ?= $(shell nproc)
SPP ?= 64
SIZE ?= 512

FUZZ_SECONDS ?= 60

.PHONY: all deps build render test test-sanitize fuzz clean

all: build

deps:
	@scripts/install-deps.sh

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

render: build
	@mkdir -p out
	$(BUILD)/strata render scenes/cornell-box.gltf --spp $(SPP) --width $(SIZE) --height $(SIZE) \
	  -o out/cornell-box.exr -o out/cornell-box.png --stats

test: build
	cd $(BUILD) && ctest --output-on-failure -j 1

test-sanitize: deps
	scripts/test_sanitize.sh

fuzz: deps
	FUZZ_SECONDS=$(FUZZ_SECONDS) scripts/fuzz.sh

clean:
	rm -rf $(BUILD) build-fuzz build-sanitize out
