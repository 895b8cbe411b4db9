# ccache, when installed, serves repeated builds on one machine (scripts/test in CI clones main
# afresh each time). CCACHE_BASEDIR makes the absolute source and build paths relative, so a clone in
# another folder hits the same entries; CCACHE_NOHASHDIR leaves the working directory (only in the
# -g debug-info paths) out of the hash. Nothing depends on the cache: a cold one only costs time.
# Set RTLAB_CCACHE=OFF to build without it.
option(RTLAB_CCACHE "Compile through ccache when it is installed" ON)
if(RTLAB_CCACHE AND NOT CMAKE_CXX_COMPILER_LAUNCHER)
    find_program(RTLAB_CCACHE_PROGRAM ccache)
    if(RTLAB_CCACHE_PROGRAM)
        set(CMAKE_CXX_COMPILER_LAUNCHER ${CMAKE_COMMAND} -E env
            CCACHE_BASEDIR=${PROJECT_SOURCE_DIR} CCACHE_NOHASHDIR=true ${RTLAB_CCACHE_PROGRAM})
        message(STATUS "ccache: ${RTLAB_CCACHE_PROGRAM} (base directory ${PROJECT_SOURCE_DIR})")
    endif()
endif()
