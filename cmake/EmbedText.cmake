# myo_embed_text(TARGET FILE SYMBOL): compiles the text of FILE into TARGET as
# `extern const char SYMBOL[]` (NUL-terminated) in namespace myo::detail, so that data the library
# ships (muscle libraries, …) needs no file access at run time. Rebuilt when FILE changes. In an
# executable the symbol lives in myo::cli::detail instead.
function(myo_embed_text target file symbol)
  get_target_property(type ${target} TYPE)
  set(ns "myo::detail")
  if(type STREQUAL "EXECUTABLE")
    set(ns "myo::cli::detail")
  endif()
  file(READ "${file}" hex HEX)
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
  string(REGEX REPLACE "((0x..,){24})" "\\1\n    " bytes "${bytes}")
  set(out "${CMAKE_BINARY_DIR}/generated/${symbol}.cpp")
  file(CONFIGURE OUTPUT "${out}" CONTENT
       "// Generated from ${file} by cmake/EmbedText.cmake. Do not edit.\nnamespace ${ns} {\nextern const char ${symbol}[] = {\n    ${bytes}0x00};\n}  // namespace ${ns}\n" @ONLY)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${file}")
  target_sources(${target} PRIVATE "${out}")
endfunction()
