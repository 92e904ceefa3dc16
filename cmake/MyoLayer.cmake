# myo_add_layer(NAME DEPS...): a static library myo_<NAME> from every src/<NAME>/*.cpp, with the
# public headers under include/myoshell/<NAME>/. New files are picked up without editing CMake.
function(myo_add_layer name)
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/src/${name}/*.cpp)
  if(NOT sources)  # a layer whose sources have not landed yet still links
    set(sources ${CMAKE_BINARY_DIR}/empty_${name}.cpp)
    file(WRITE ${sources} "// ${name}: no sources yet\n")
  endif()
  add_library(myo_${name} STATIC ${sources})
  add_library(Myoshell::${name} ALIAS myo_${name})
  target_include_directories(myo_${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_SOURCE_DIR}/include> $<INSTALL_INTERFACE:include>)
  target_link_libraries(myo_${name} PUBLIC ${ARGN})
  target_compile_options(myo_${name} PRIVATE -Wall -Wextra)
endfunction()
