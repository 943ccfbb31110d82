#!/usr/bin/env bash
# Guards the per-ISA kernel objects (cmake/kernels.cmake, STYLE.md):
#  1. no static initialiser: it would run at start-up, before any ISA is chosen, with the
#     object's instructions (an AVX-512 one crashes an older CPU);
#  2. no weak symbol shared with other objects: the linker could hand the AVX2 copy of an
#     inline function to a baseline caller. Symbols inside the object's own namespace
#     (ssrt::isa_<name>) or templated on its own xsimd architecture are unique to it.
# Usage: check_kernel_objects.sh ISA XSIMD_ARCH OBJECT...
set -u
isa=$1 arch=$2
shift 2
status=0
for obj in "$@"; do
    if nm "$obj" | grep -q '_GLOBAL__sub_I'; then
        echo "FAIL $obj: static initialiser in an ISA kernel object" >&2
        status=1
    fi
    shared=$(nm -C "$obj" | grep -E '^[0-9a-f ]+ [WVu] ' | grep -v 'DW.ref.__gxx_personality_v0' |
             grep -v "ssrt::isa_${isa}::" | grep -v "xsimd::${arch}>" || true)
    if [ -n "$shared" ]; then
        echo "FAIL $obj: weak symbols shared across ISAs:" >&2
        echo "$shared" >&2
        status=1
    fi
done
[ $status -eq 0 ] && echo "kernel objects for $isa: clean ($# objects)"
exit $status
