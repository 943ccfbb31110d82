# Sourced by the scripts that configure a build (build.sh, and lib/second-build.sh for CI's others):
# sets `compiler_cache`, the CMake option that puts ccache in front of the compiler when it is
# installed (install-deps.sh ci installs it; neither README command needs it), and clears it
# when not, so a build folder configured with ccache keeps building after ccache is gone.
#
# The cache lives in ccache's own folder (~/.cache/ccache), outside every checkout. base_dir
# turns the checkout's absolute paths into relative ones and hash_dir=false leaves the working
# folder out of the key, so a fresh clone in another folder (CI's) hits what an earlier clone
# compiled. SSRT_CCACHE=0 turns it off.
compiler_cache=(-DCMAKE_CXX_COMPILER_LAUNCHER=)
if [ "${SSRT_CCACHE:-1}" != 0 ] && command -v ccache >/dev/null; then
    compiler_cache=("-DCMAKE_CXX_COMPILER_LAUNCHER=env;CCACHE_BASEDIR=$PWD;CCACHE_NOHASHDIR=1;ccache")
fi
