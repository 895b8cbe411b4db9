# rtlab_folder_library(NAME folder ...): a STATIC library of every .cpp under the calling folder
# (recursively), or an INTERFACE library while the folder has headers only. Include paths start at
# the repository root. Extra arguments are passed to target_link_libraries(... PUBLIC ...).
function(rtlab_folder_library name)
    file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
    if(sources)
        add_library(${name} STATIC ${sources})
        target_link_libraries(${name} PUBLIC ${ARGN} PRIVATE rtlab_warnings)
        set(scope PUBLIC)
    else()
        add_library(${name} INTERFACE)
        target_link_libraries(${name} INTERFACE ${ARGN})
        set(scope INTERFACE)
    endif()
    target_include_directories(${name} ${scope}
        $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
        $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/rtlab>)
endfunction()
