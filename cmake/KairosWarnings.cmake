# SPDX-License-Identifier: MIT
# Warning and floating-point flags shared by every Kairos target.
function(kairos_warnings target)
    target_compile_options(${target} PRIVATE
        -Wall -Wextra -Wpedantic
        # Bit-identical results on one build: no fused multiply-add contraction, no fast-math.
        -ffp-contract=off
        # No errno from sqrt and friends (nothing reads it): a square root is then the one
        # instruction, without a NaN test and a libm call beside it. Results do not change.
        -fno-math-errno
        # GNU unique symbols would pin the library in memory and stop dlclose from unloading it
        # (GCC emits them; clang does not, and has no such flag).
        $<$<AND:$<COMPILE_LANGUAGE:CXX>,$<CXX_COMPILER_ID:GNU>>:-fno-gnu-unique>)
endfunction()
