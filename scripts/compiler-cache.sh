# Sourced by build.sh, test-sanitizers.sh and fuzz.sh from the project root. When ccache is
# installed (install-deps.sh test installs it), CMake compiles through it: a build of sources
# already compiled with the same flags, such as CI's fresh clone on a machine that built them
# before, takes the objects from ccache's store (~/.cache/ccache) instead of compiling again.
# Paths under the clone are hashed relative to it (CCACHE_BASEDIR) and the working directory is
# not hashed (CCACHE_NOHASHDIR), so a clone in another folder finds the same objects. Sets
# `compiler_cache`, the CMake arguments to add at configure time (empty without ccache).
compiler_cache=()
if command -v ccache >/dev/null; then
  export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1
  compiler_cache=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
