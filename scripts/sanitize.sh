#!/usr/bin/env bash
# The sanitizer pass, part of .ci/run: core, CLI, GUI and their tests built in build-asan/ with
# -fsanitize=address,undefined (-O1 -g1: the optimisation level the AddressSanitizer documentation
# recommends, at about half the instrumented compile time of -O2 (core/identify/fit.cpp: 95 s
# against 177 s), and line tables for the reports instead of full debug info) and run; any
# sanitizer report fails the pass. GUI tests run offscreen; leaks inside Qt's and the system
# libraries' own code are suppressed by the reviewed list in scripts/lsan.supp (never a frame of
# ours).
# The heaviest fits run as smaller cases (tests/CMakeLists.txt: core_tst_identify_synthetic_small,
# core_tst_fit_dynamics_small) instead of the full ones that the Release pass runs.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
# shellcheck source=scripts/deps.sh
source "$root/scripts/deps.sh"
asan="${STICKSLIP_ASAN_DIR:-$root/build-asan}"
echo "== sanitize: build in $asan (ASan + UBSan; core, CLI, GUI and their tests)"
gui=OFF
if dpkg-query -W -f='${db:Status-Status}' qtbase5-dev 2>/dev/null | grep -q '^installed$'; then gui=ON; fi
launcher=()
if command -v ccache >/dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
if [ ! -f "$asan/CMakeCache.txt" ]; then
  # MPI off: without mpirun the CLI never initialises MPI, and Open MPI's own allocations would
  # need a suppression list of their own. The Python module cannot be loaded into Debian's
  # uninstrumented interpreter; benchmarks are not tests.
  cmake -S "$root" -B "$asan" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
        -DSTICKSLIP_SANITIZE=ON -DSTICKSLIP_BUILD_BENCH=OFF -DSTICKSLIP_BUILD_GUI="$gui" -DSTICKSLIP_BUILD_PYTHON=OFF \
        -DSTICKSLIP_WITH_MPI=OFF "${launcher[@]}"
fi
cmake --build "$asan" -j"$(nproc)"

# Any report stops the test with a non-zero status (the code is also built with
# -fno-sanitize-recover=all); leak detection is on.
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=0:detect_leaks=1:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1"
export LSAN_OPTIONS="suppressions=$root/scripts/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export QT_QPA_PLATFORM=offscreen
cd "$asan"
# Left to the Release pass: the full heaviest fits (their small cases run here; the loop on a
# synthesized set has the same stages as the small synthetic case), and the install
# test (it installs and runs the Release layout, Python module included).
ctest --output-on-failure -j"$(nproc)" \
      -E '^(core_tst_fit_dynamics|core_tst_identify_synthetic_D[0-9]+|core_tst_identify_synthesized|install_tree)$'
