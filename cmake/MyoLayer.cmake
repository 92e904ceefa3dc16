# The layers, in link order (DESIGN.md): each layer links only layers listed before it.
set(MYO_LAYER_ORDER core mesh shell reduce verify head muscles thesis anatomy fit anim io render gl)

# myo_add_layer(NAME DEPS...): a static library myo_<NAME> from every src/<NAME>/*.cpp, with the
# public headers under include/myoshell/<NAME>/. New files are picked up without editing CMake.
# A dependency myo_<X> on a layer that is not listed before NAME in MYO_LAYER_ORDER is a
# configure error, so the link graph keeps the layering honest.
function(myo_add_layer name)
  list(FIND MYO_LAYER_ORDER ${name} own)
  if(own EQUAL -1)
    message(FATAL_ERROR "myo_add_layer: '${name}' is not in MYO_LAYER_ORDER (cmake/MyoLayer.cmake)")
  endif()
  foreach(dep ${ARGN})
    if(dep MATCHES "^myo_(.+)$")
      list(FIND MYO_LAYER_ORDER ${CMAKE_MATCH_1} pos)
      if(pos EQUAL -1 OR NOT pos LESS own)
        message(FATAL_ERROR "layer '${name}' may not link ${dep}: only layers before it in MYO_LAYER_ORDER")
      endif()
    endif()
  endforeach()
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
  # Position-independent, so the layers also link into shared objects: the Python module (python/).
  set_target_properties(myo_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  myo_precompile(myo_${name} layer)
endfunction()
