# The two commands of the Quick start. Each installs what is missing, configures and builds.
PRESET ?= release
BUILD  := build/$(PRESET)
JOBS   ?= $(shell nproc)
# ON turns compiler warnings into errors (CI sets it)
WERROR ?= OFF

.PHONY: all deps configure build demo test test-asan test-tsan bench mutants format format-check clean

all: build

deps:
	@./scripts/install-deps.sh

configure: deps
	@cmake --preset $(PRESET) -DPALPATE_WERROR=$(WERROR) >/dev/null

build: configure
	@cmake --build --preset $(PRESET) -j $(JOBS)

# Only the tool: no test or benchmark is compiled first.
demo: configure
	@cmake --build --preset $(PRESET) -j $(JOBS) --target palpate_cli
	$(BUILD)/apps/palpate demo

test: build
	ctest --preset $(PRESET) -j $(JOBS)

test-asan:
	@$(MAKE) --no-print-directory test PRESET=asan

test-tsan:
	@$(MAKE) --no-print-directory test PRESET=tsan

bench: build
	$(BUILD)/apps/palpate bench haptics --quick
	$(BUILD)/apps/palpate bench render --quick

# Does the suite catch one-line bugs? tests/mutants.tsv, each applied alone to a scratch copy (slow:
# not in CI; run it before resolving work on the parts it covers).
mutants: deps
	@./scripts/mutants.py

format:
	git ls-files '*.cpp' '*.hpp' '*.h' | xargs clang-format -i

format-check: deps
	@./scripts/check-format.sh

clean:
	rm -rf build
