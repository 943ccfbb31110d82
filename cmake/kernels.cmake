# Kernels are written once as templates over the lane type and compiled once per ISA.
# Each copy gets its own namespace (ssrt::isa_<name>) through SSRT_ISA_NS, so no symbol
# compiled with AVX2 flags can be picked by the linker for a baseline caller; core/dispatch.h
# chooses the copy at run time.
#
# SSRT_ISAS chooses the families a build compiles (every one by default). scalar is always
# among them: it is the oracle every other family is tested against and the fallback of
# core/dispatch.h. A build with fewer families (the sanitized build, which needs one SIMD
# family to check, not five) runs only those: isaSupported() says false for the others and
# --isa names what the binary was built with.
#
# The families are the target architecture's: x86-64's SSE2 to AVX-512, aarch64's NEON
# (xsimd::neon64: every aarch64 CPU has it, so it needs no flag). Scalar is in both.
if(CMAKE_SYSTEM_PROCESSOR MATCHES "^(aarch64|arm64|ARM64)$")
    set(SSRT_ALL_ISAS scalar neon)
elseif(CMAKE_SYSTEM_PROCESSOR MATCHES "^(x86_64|AMD64|amd64)$")
    set(SSRT_ALL_ISAS scalar sse2 sse42 avx2 avx512)
else()
    message(FATAL_ERROR "ssrt's kernels are built for x86-64 and aarch64, not for "
                        "'${CMAKE_SYSTEM_PROCESSOR}'")
endif()
set(SSRT_ISAS "${SSRT_ALL_ISAS}" CACHE STRING
    "Kernel families to compile (a subset of: ${SSRT_ALL_ISAS}; scalar is always built)")
foreach(isa ${SSRT_ISAS})
    if(NOT isa IN_LIST SSRT_ALL_ISAS)
        message(FATAL_ERROR "SSRT_ISAS: unknown family '${isa}' (known: ${SSRT_ALL_ISAS})")
    endif()
endforeach()
if(NOT scalar IN_LIST SSRT_ISAS)
    message(FATAL_ERROR "SSRT_ISAS must include scalar (the oracle and the fallback)")
endif()
set(SSRT_ISA_FLAGS_scalar "")
set(SSRT_ISA_FLAGS_sse2 "")
set(SSRT_ISA_FLAGS_sse42 -msse4.2)
# F16C (the half conversions, vcvtph2ps and vcvtps2ph) comes with every AVX2 and AVX-512 CPU
# but with neither flag: the two families get it, and core/isa.cpp requires it for both.
set(SSRT_ISA_FLAGS_avx2 -mavx2 -mf16c)
# (GCC 12 warns inside its own AVX-512 headers, of their _mm512_undefined_* pass-through
# operands, under -Wmaybe-uninitialized and -Wuninitialized; the same sources compiled for
# every other ISA still get both warnings.)
set(SSRT_ISA_FLAGS_avx512 -mavx512f -mavx512cd -mavx512dq -mavx512bw -mavx512vl -mf16c
    -Wno-maybe-uninitialized -Wno-uninitialized)
set(SSRT_ISA_FLAGS_neon "")

function(ssrt_add_isa_kernels target)
    foreach(isa ${SSRT_ISAS})
        set(obj ${target}_kernels_${isa})
        add_library(${obj} OBJECT ${ARGN})
        target_compile_definitions(${obj} PRIVATE SSRT_ISA_${isa}=1 SSRT_ISA_NS=isa_${isa})
        target_compile_options(${obj} PRIVATE ${SSRT_ISA_FLAGS_${isa}})
        target_include_directories(${obj} PRIVATE ${PROJECT_SOURCE_DIR})
        target_link_libraries(${obj} PRIVATE xsimd)
        target_sources(${target} PRIVATE $<TARGET_OBJECTS:${obj}>)
        # Which copies exist: core/dispatch.h refers only to these, core/isa.cpp offers only these.
        target_compile_definitions(${target} PUBLIC SSRT_BUILT_ISA_${isa}=1)
    endforeach()
endfunction()
